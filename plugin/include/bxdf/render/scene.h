// The renderable scene: triangle meshes in an Embree BVH, materials, lights and the world.
// Build it with add_material / add_mesh / add_light / set_world, then commit() once; after that
// it is immutable and safe to query from many threads.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bxdf/bsdf.h"
#include "bxdf/render/environment.h"
#include "bxdf/render/hittable_lights.h"
#include "bxdf/render/light_sampler.h"
#include "bxdf/render/lights.h"
#include "bxdf/render/material.h"
#include "bxdf/render/mesh.h"
#include "bxdf/render/object_transform.h"
#include "bxdf/render/ray.h"
#include "bxdf/render/shadow_terminator.h"

namespace bxdf::render {

// Hit::instance of a mesh drawn where it was declared (add_mesh).
inline constexpr uint32_t kNotInstanced = 0xffffffffu;

// What a ray hit, before shading.
struct Hit {
  float t = 0.0f;
  uint32_t mesh = 0, triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2
  uint32_t instance = kNotInstanced;  // which placement of an instanced mesh, or kNotInstanced
};

// A camera ray's first hit, found with others in one packet query (found false: it escaped).
struct CameraHit {
  Hit hit;
  bool found = false;
};

// The shading point built from a hit.
struct SurfacePoint {
  Vec3 p;          // on the triangle (from barycentrics, not from the ray: more accurate)
  Vec3 ng;         // geometric normal, on the side of ns
  Vec3 ns;         // interpolated shading normal
  Vec3 tangent;    // dp/du where UVs exist, else radial_tangent (Cycles' default)
  // Scene::smooth_normal at the hit (unnormalised, world space, never flipped), kept from the
  // vertex normals surface_point reads anyway: a normal map needs it.
  Vec3 smooth_normal;
  Point2 uv;
  uint32_t material = 0;
};

// How every shading point is oriented: a surface that only reflects is two-sided and turns its
// normals towards the viewer (`towards_viewer`); a transmissive one keeps its orientation, which
// tells the model inside from outside. True when the normals were flipped.
inline bool face_viewer(SurfacePoint& sp, const Vec3& towards_viewer, bool transmissive) {
  if (transmissive || !(dot(towards_viewer, sp.ng) < 0.0f)) return false;
  sp.ng = -sp.ng;
  sp.ns = -sp.ns;
  return true;
}

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Returns the material's index. Throws ParameterError if it has no component and no emission,
  // more components than a BSDF holds, or negative/non-finite emission.
  uint32_t add_material(Material material);
  // Copies the mesh; returns its index. Throws ParameterError naming the array and the
  // offending entry (index out of range, NaN position, unknown material...).
  uint32_t add_mesh(const MeshView& mesh);
  // A mesh declared once in its own object space and drawn only where add_instance places it
  // (one level: an Embree instance of a scene of its own, so N placements cost one mesh and
  // one BVH). Its object_to_world must be null; visibility and terminator offsets apply to
  // every placement. Returns its index (a mesh index, as add_mesh's).
  uint32_t add_instanced_mesh(const MeshView& mesh);
  // The same, taking the mesh's arrays over instead of copying them (the mesh is left empty or
  // partly emptied): for callers that built a mesh only to hand it over, at 10M triangles a
  // copy is hundreds of megabytes.
  uint32_t add_mesh(Mesh&& mesh);
  uint32_t add_instanced_mesh(Mesh&& mesh);
  // Places an instanced mesh with a 3×4 row-major object → world matrix (finite, invertible);
  // returns the instance's index. Throws ParameterError naming the mesh or the matrix.
  uint32_t add_instance(uint32_t mesh, const float* object_to_world);
  // Point, spot, sun and area lights (mesh lights come from emissive materials at commit).
  void add_light(Light light);
  // A constant world, or one with an environment image (see environment.h).
  void set_world(const RGB& radiance);
  void set_world(EnvironmentSettings settings);
  void set_world(std::shared_ptr<const Environment> world);  // e.g. from shared_environment
  // Builds the BVH, the light list (one mesh light per mesh with emissive triangles) and the
  // light sampler (by power). `expected_rays`: about how many rays the render will trace (0:
  // not known). Below kQuickBuildRaysPerTriangle per triangle the meshes' BVHs are Embree's
  // quick build (RTC_BUILD_QUALITY_LOW), whose slower tracing the render would not win back
  // the medium build's time with (not in a compact scene: 2 M triangles or more).
  void commit(double expected_rays = 0.0);
  static constexpr double kQuickBuildRaysPerTriangle = 96.0;

  bool committed() const { return committed_; }
  // Whether commit chose the quick build for the meshes' BVHs.
  bool quick_build() const { return quick_build_; }
  size_t num_meshes() const { return meshes_.size(); }
  size_t num_triangles() const;  // stored: an instanced mesh counts once
  size_t num_instances() const { return instances_.size(); }
  size_t num_rendered_triangles() const;  // as drawn: an instanced mesh once per placement
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<Light>& lights() const { return lights_; }
  const Environment& world() const { return *world_; }
  const LightSampler& light_sampler() const { return light_sampler_; }
  // The lights rays can hit (point/spot with a radius, area), and the indices into lights() of
  // the suns with an angle (found by escaped rays).
  const HittableLights& hittable_lights() const { return hittable_lights_; }
  const std::vector<uint32_t>& wide_suns() const { return wide_suns_; }
  float bounding_radius() const { return bounding_radius_; }
  // Whether a ray can bring light back by itself, before any shading where it lands: the world
  // or a sun with an angle when it escapes, a light it passes, an emitting surface it hits.
  // Where none can, a path's next ray counts only through the vertex it finds (committed
  // scenes).
  bool rays_find_light() const { return rays_find_light_; }

  // Closest hit in [ray.tmin, ray.tmax]; camera rays skip meshes invisible to the camera.
  bool intersect(const Ray& ray, Hit* hit, bool camera_ray = false) const;
  // Up to kCameraPacket camera rays at once (one Embree packet query): what intersect(ray, hit,
  // true) finds for each. Camera rays of nearby samples are coherent, and a packet walks the
  // BVH for all of them together.
  static constexpr int kCameraPacket = 8;
  void intersect_camera_rays(const Ray* rays, int count, CameraHit* hits) const;
  // intersect() for `count` rays at once (one Embree stream query); camera[k] as its camera_ray.
  void intersect_stream(const Ray* const* rays, const uint8_t* camera, int count, Hit* hits,
                        uint8_t* found) const;
  // Start loading what shading `hit` reads, for a batch of hits to shade after: the triangle's
  // indices and material index (stage 0), then, once those have arrived, its vertices'
  // positions, normals and UVs and its corners' first UV map and tangents (stage 1). Only
  // hints: nothing changes.
  void prefetch_triangle(const Hit& hit) const;
  void prefetch_vertices(const Hit& hit) const;
  // The material index surface_point gives the hit.
  uint32_t material_of(const Hit& hit) const {
    const StoredMesh& m = meshes_[hit.mesh];
    return m.material_indices.empty() ? m.material : m.material_indices[hit.triangle];
  }
  // True when something blocks the segment origin + t·dir, t in (0, tmax); meshes that do not
  // cast shadows are skipped.
  bool occluded(const Vec3& origin, const Vec3& dir, float tmax) const;
  // occluded() of `count` shadow rays in one Embree stream query: occluded[k] for ray k.
  void occluded_stream(const Vec3* origins, const Vec3* dirs, const float* tmax, int count,
                       uint8_t* occluded) const;
  SurfacePoint surface_point(const Hit& hit) const;
  // The same, written into *out (a path vertex's point, filled where it is kept); without the
  // tangent where with_tangent is false (out->tangent is then zero), for a caller whose
  // closures read none.
  void surface_point(const Hit& hit, SurfacePoint* out, bool with_tangent = true) const;

  // Mesh attributes at a hit, for material graphs (hit barycentrics may lie outside the
  // triangle: attributes extrapolate linearly, as ray differentials need).
  Vec3 uv(const Hit& hit, int map) const;  // (u, v, 0); zero where the mesh has no such map
  // The UV map's tangent in object space (interpolated, unnormalised) and sign; false when the
  // mesh has none.
  bool tangent(const Hit& hit, int map, Vec3* tangent, float* sign) const;
  // Interpolated vertex normal, unnormalised (the geometric normal on a flat mesh).
  Vec3 smooth_normal(const Hit& hit) const;
  // Normals between world and object space (Aᵀ n and A⁻ᵀ n for the object matrix A; not
  // normalised). The object is the instance's for a hit on an instanced mesh.
  Vec3 normal_to_object(const Hit& hit, const Vec3& n) const;
  Vec3 normal_to_world(const Hit& hit, const Vec3& n) const;
  Vec3 object_position(const Hit& hit, const Vec3& p) const;
  Vec3 generated(const Hit& hit, const Vec3& p) const;  // object position in the texture space
  // Cycles' default tangent: radial about the object's Z axis, in world space, not normalised.
  Vec3 radial_tangent(const Hit& hit, const Vec3& p) const;
  // The hit moved by `dp` (world space, along the triangle's plane): its barycentrics follow,
  // so attributes read there are the triangle's own, extrapolated linearly past its edges.
  Hit offset_hit(const Hit& hit, const Vec3& dp) const;
  // True when some material's emission may be negative (a node material's; Cycles lets a
  // negative Emission take light away), so that negative path radiance is not an error.
  bool signed_emission() const { return signed_emission_; }
  // Emitted radiance of the material at a hit (both sides).
  const RGB& emission(uint32_t material) const { return materials_[material].emission; }
  // η_t/η_i of the material's first transmissive component (1 when none), read from the
  // registry parameters eta_i, eta_t; the integrator uses it to keep Russian roulette blind
  // to the (η_i/η_t)² radiance scaling of refraction (pbrt's etaScale).
  float relative_eta(uint32_t material) const { return material_eta_[material]; }
  bool transmissive(uint32_t material) const { return material_eta_[material] != 0.0f; }
  // Index into lights() of the area light made from the hit mesh (or the hit instance), or -1.
  int area_light_of(const Hit& hit) const {
    return hit.instance == kNotInstanced ? mesh_area_light_[hit.mesh]
                                         : instance_area_light_[hit.instance];
  }
  // The hit triangle's vertices and vertex normals; false when the mesh is flat-shaded.
  bool smooth_triangle(const Hit& hit, SmoothTriangle* tri) const;
  // The mesh's terminator offsets as they apply: a flat-shaded mesh's geometry offset is 0.
  const TerminatorOffsets& terminator(uint32_t mesh) const { return meshes_[mesh].terminator; }

  // The Embree scene handle (RTCScene), for benchmarks that cast rays directly.
  void* embree_scene() const;

 private:
  struct StoredMesh {
    // positions carry one float past the last vertex: Embree reads vertices 16 bytes at a
    // time from this very buffer (shared, not copied).
    std::vector<float> positions, normals, uvs;
    size_t num_vertices = 0;
    std::vector<uint32_t> indices, material_indices;
    uint32_t material = 0;
    std::vector<std::vector<float>> uv_maps, tangents;  // per corner
    // World space; or, for an instanced mesh, object space (and `object` the identity).
    ObjectTransform object;
    bool instanced = false;
    Vec3 texspace_location, texspace_inv_size{1, 1, 1};  // generated = (p − loc)·inv/2 + ½
    MeshVisibility visibility;
    TerminatorOffsets terminator;
  };
  struct StoredInstance {
    uint32_t mesh = 0;
    ObjectTransform object;
  };
  struct EmbreeState;
  static void add_graph_attributes(const MeshView& mesh, const std::string& who, StoredMesh& s);
  uint32_t store_mesh(const MeshView& mesh, bool instanced, Mesh* owned);
  // The placement a hit's mesh-space data moves to world space by: null for meshes stored in
  // world space.
  const ObjectTransform* placement(const Hit& hit) const {
    return hit.instance == kNotInstanced ? nullptr : &instances_[hit.instance].object;
  }
  // Object space of the hit (an instance's, or the mesh's own).
  const ObjectTransform& object_of(const Hit& hit) const {
    return hit.instance == kNotInstanced ? meshes_[hit.mesh].object : instances_[hit.instance].object;
  }
  Vec3 world_vertex(const StoredMesh& m, const Hit& hit, uint32_t vertex) const;
  // An Embree hit (geometry, instance and primitive IDs, barycentrics) as a Hit.
  Hit decode_hit(float t, uint32_t geometry, uint32_t instance, uint32_t triangle, float u,
                 float v) const;
  // The mesh light of a mesh drawn as itself (instance kNotInstanced) or of one placement.
  void add_mesh_light(uint32_t mesh, uint32_t instance, int* light_index);

  std::vector<Material> materials_;
  std::vector<float> material_eta_;  // 0 = no transmission; else η_t/η_i (1 if unknown)
  std::vector<StoredMesh> meshes_;
  std::vector<StoredInstance> instances_;
  std::vector<Light> lights_;
  std::vector<int> mesh_area_light_, instance_area_light_;
  HittableLights hittable_lights_;
  std::vector<uint32_t> wide_suns_;
  std::shared_ptr<const Environment> world_;  // never null; may be shared with other scenes
  LightSampler light_sampler_;
  float bounding_radius_ = 0.0f;
  bool committed_ = false;
  bool quick_build_ = false;
  bool signed_emission_ = false;
  bool rays_find_light_ = true;
  std::unique_ptr<EmbreeState> embree_;
};

}  // namespace bxdf::render

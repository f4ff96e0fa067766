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
#include "bxdf/render/light_sampler.h"
#include "bxdf/render/lights.h"
#include "bxdf/render/material.h"
#include "bxdf/render/mesh.h"
#include "bxdf/render/ray.h"
#include "bxdf/render/shadow_terminator.h"

namespace bxdf::render {

// What a ray hit, before shading.
struct Hit {
  float t = 0.0f;
  uint32_t mesh = 0, triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2
};

// The shading point built from a hit.
struct SurfacePoint {
  Vec3 p;          // on the triangle (from barycentrics, not from the ray: more accurate)
  Vec3 ng;         // geometric normal, on the side of ns
  Vec3 ns;         // interpolated shading normal
  Vec3 tangent;    // dp/du where UVs exist, else radial_tangent (Cycles' default)
  Point2 uv;
  uint32_t material = 0;
};

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
  // Point, spot, sun and area lights (mesh lights come from emissive materials at commit).
  void add_light(Light light);
  // A constant world, or one with an environment image (see environment.h).
  void set_world(const RGB& radiance);
  void set_world(EnvironmentSettings settings);
  // Builds the BVH, the light list (one mesh light per mesh with emissive triangles) and the
  // light sampler (by power).
  void commit();

  bool committed() const { return committed_; }
  size_t num_meshes() const { return meshes_.size(); }
  size_t num_triangles() const;
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<Light>& lights() const { return lights_; }
  const Environment& world() const { return world_; }
  const LightSampler& light_sampler() const { return light_sampler_; }
  // Indices into lights() of the lights rays can hit (point/spot with a radius, area) and of
  // suns with an angle (found by escaped rays).
  const std::vector<uint32_t>& hittable_lights() const { return hittable_lights_; }
  const std::vector<uint32_t>& wide_suns() const { return wide_suns_; }
  float bounding_radius() const { return bounding_radius_; }

  // Closest hit in [ray.tmin, ray.tmax]; camera rays skip meshes invisible to the camera.
  bool intersect(const Ray& ray, Hit* hit, bool camera_ray = false) const;
  // True when something blocks the segment origin + t·dir, t in (0, tmax); meshes that do not
  // cast shadows are skipped.
  bool occluded(const Vec3& origin, const Vec3& dir, float tmax) const;
  SurfacePoint surface_point(const Hit& hit) const;

  // Mesh attributes at a hit, for material graphs (hit barycentrics may lie outside the
  // triangle: attributes extrapolate linearly, as ray differentials need).
  Vec3 uv(const Hit& hit, int map) const;  // (u, v, 0); zero where the mesh has no such map
  // The UV map's tangent in object space (interpolated, unnormalised) and sign; false when the
  // mesh has none.
  bool tangent(const Hit& hit, int map, Vec3* tangent, float* sign) const;
  // Interpolated vertex normal, unnormalised (the geometric normal on a flat mesh).
  Vec3 smooth_normal(const Hit& hit) const;
  // Normals between world and object space (Aᵀ n and A⁻ᵀ n for the object matrix A; not
  // normalised).
  Vec3 normal_to_object(const Hit& hit, const Vec3& n) const;
  Vec3 normal_to_world(const Hit& hit, const Vec3& n) const;
  // True when the mesh's object matrix neither rotates nor scales (both maps above are then
  // the identity, exactly), so per-hit code may skip them.
  bool normals_in_world_space(const Hit& hit) const { return meshes_[hit.mesh].linear_identity; }
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
  // Index into lights() of the area light made from a mesh, or -1.
  int area_light_of_mesh(uint32_t mesh) const { return mesh_area_light_[mesh]; }
  // The hit triangle's vertices and vertex normals; false when the mesh is flat-shaded.
  bool smooth_triangle(const Hit& hit, SmoothTriangle* tri) const;
  const TerminatorOffsets& terminator(uint32_t mesh) const { return meshes_[mesh].terminator; }

  // The Embree scene handle (RTCScene), for benchmarks that cast rays directly.
  void* embree_scene() const;

 private:
  struct StoredMesh {
    std::vector<float> positions, normals, uvs;
    std::vector<uint32_t> indices, material_indices;
    uint32_t material = 0;
    std::vector<std::vector<float>> uv_maps, tangents;  // per corner
    std::array<float, 12> world_to_object{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    std::array<float, 9> object_linear{1, 0, 0, 0, 1, 0, 0, 0, 1};  // object → world, 3×3
    bool linear_identity = true;  // object_linear is the identity: normals need no transform
    Vec3 texspace_location, texspace_inv_size{1, 1, 1};  // generated = (p − loc)·inv/2 + ½
    MeshVisibility visibility;
    TerminatorOffsets terminator;
  };
  struct EmbreeState;
  static void add_graph_attributes(const MeshView& mesh, const std::string& who, StoredMesh& s);

  std::vector<Material> materials_;
  std::vector<float> material_eta_;  // 0 = no transmission; else η_t/η_i (1 if unknown)
  std::vector<StoredMesh> meshes_;
  std::vector<Light> lights_;
  std::vector<int> mesh_area_light_;
  std::vector<uint32_t> hittable_lights_, wide_suns_;
  Environment world_;
  LightSampler light_sampler_;
  float bounding_radius_ = 0.0f;
  bool committed_ = false;
  bool signed_emission_ = false;
  std::unique_ptr<EmbreeState> embree_;
};

}  // namespace bxdf::render

#include "bxdf/render/scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "bxdf/params.h"
#include "bxdf/render/recycled_buffers.h"
#include "bxdf/render/textured_emission.h"

namespace bxdf::render {

struct Scene::EmbreeState {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RTCScene> instanced;  // per mesh: its own scene when it is instanced, else null
  ~EmbreeState() {
    if (scene) rtcReleaseScene(scene);
    for (RTCScene s : instanced)
      if (s) rtcReleaseScene(s);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

std::string embree_error(RTCDevice device) {
  switch (rtcGetDeviceError(device)) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
  }
}

constexpr float kHuge = 3.0e38f;
// From this many stored triangles on, BVHs are built compact (RTC_SCENE_FLAG_COMPACT, as Cycles
// always builds them): indexed triangles instead of vertex copies, measured ~60 instead of ~120
// bytes per triangle, for somewhat slower traversal that only scenes this large should pay.
constexpr size_t kCompactBvhTriangles = 2'000'000;
// Embree geometry masks: which kinds of ray see a mesh.
constexpr unsigned kMaskCamera = 1u, kMaskShadow = 2u, kMaskOther = 4u;

// An occlusion query from `origin` along `dir` up to `tmax`, seeing the shadow-casting meshes.
RTCRay embree_shadow_ray(const Vec3& origin, const Vec3& dir, float tmax) {
  RTCRay r;
  r.org_x = origin.x;
  r.org_y = origin.y;
  r.org_z = origin.z;
  r.dir_x = dir.x;
  r.dir_y = dir.y;
  r.dir_z = dir.z;
  r.tnear = 0.0f;
  r.tfar = tmax;
  r.time = 0.0f;
  r.mask = kMaskShadow;
  r.id = 0;
  r.flags = 0;
  return r;
}

// A closest-hit query for `ray` as Embree takes it: no hit yet, seeing the meshes of `mask`.
RTCRayHit embree_ray_hit(const Ray& ray, unsigned mask) {
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.time = 0.0f;
  rh.ray.mask = mask;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

Vec3 load3(const std::vector<float>& a, uint32_t i) {
  return {a[3 * size_t(i)], a[3 * size_t(i) + 1], a[3 * size_t(i) + 2]};
}

void require_finite(const float* p, size_t n, size_t width, const std::string& what) {
  for (size_t i = 0; i < n * width; ++i)
    if (!std::isfinite(p[i]))
      throw ParameterError(what + "[" + std::to_string(i / width) + "] is not finite");
}

// η_t/η_i of a graph's first transmissive closure with constant eta_i/eta_t (1 otherwise).
float graph_eta(const MaterialGraph& graph) {
  for (const GraphClosure& c : graph.closures) {
    const BxDF* m = c.prebuilt.get();
    if (!m || !(m->flags() & kTransmission)) continue;
    const ParamSet& p = m->params();
    if (p.has("eta_i") && p.has("eta_t") && p.number("eta_i") > 0.0)
      return static_cast<float>(p.number("eta_t") / p.number("eta_i"));
  }
  return 1.0f;
}

}  // namespace

// UV maps, tangents, the object transform and the texture space a material graph reads.
void Scene::add_graph_attributes(const MeshView& m, const std::string& who, StoredMesh& s) {
  const size_t corners = 3 * m.num_triangles;
  for (size_t k = 0; k < m.num_uv_maps; ++k) {
    const std::string name = who + ": uv_maps[" + std::to_string(k) + "]";
    if (!m.uv_maps || !m.uv_maps[k]) throw ParameterError(name + " is missing");
    require_finite(m.uv_maps[k], corners, 2, name);
    s.uv_maps.emplace_back(m.uv_maps[k], m.uv_maps[k] + 2 * corners);
    std::vector<float> tangents;
    if (m.tangents && m.tangents[k]) {
      require_finite(m.tangents[k], corners, 4, who + ": tangents[" + std::to_string(k) + "]");
      tangents.assign(m.tangents[k], m.tangents[k] + 4 * corners);
    }
    s.tangents.push_back(std::move(tangents));
  }
  if (m.object_to_world) {
    require_finite(m.object_to_world, 1, 12, who + ": object_to_world");
    if (!s.object.set(m.object_to_world))
      throw ParameterError(who + ": object_to_world is singular (no object coordinates)");
  }
  // Tangents arrive in world space (moved with the mesh); normal maps work in object space,
  // as Cycles does, so they are taken back once here.
  const float* w = s.object.to_object.data();
  for (std::vector<float>& tangents : s.tangents)
    for (size_t c = 0; c < tangents.size() / 4; ++c) {
      float* v = &tangents[4 * c];
      const float x = v[0], y = v[1], z = v[2];
      v[0] = w[0] * x + w[1] * y + w[2] * z;
      v[1] = w[4] * x + w[5] * y + w[6] * z;
      v[2] = w[8] * x + w[9] * y + w[10] * z;
    }
  Vec3 location, size;
  if (m.texture_space) {
    require_finite(m.texture_space, 1, 6, who + ": texture_space");
    location = Vec3(m.texture_space[0], m.texture_space[1], m.texture_space[2]);
    size = Vec3(m.texture_space[3], m.texture_space[4], m.texture_space[5]);
  } else {
    // Blender's automatic texture space: the object-space bounding box, a zero extent as 1.
    Vec3 lo(kInf, kInf, kInf), hi(-kInf, -kInf, -kInf);
    for (size_t i = 0; i < m.num_vertices; ++i) {
      const Vec3 p = s.object.point_to_object(load3(s.positions, uint32_t(i)));
      lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
      hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
    }
    location = (lo + hi) * 0.5f;
    size = (hi - lo) * 0.5f;
    for (float* c : {&size.x, &size.y, &size.z})
      if (*c == 0.0f) *c = 1.0f;
  }
  s.texspace_location = location;
  s.texspace_inv_size = Vec3(size.x != 0.0f ? 1.0f / size.x : 0.0f,
                             size.y != 0.0f ? 1.0f / size.y : 0.0f,
                             size.z != 0.0f ? 1.0f / size.z : 0.0f);
}

Scene::Scene()
    : world_(std::make_shared<const Environment>()), embree_(std::make_unique<EmbreeState>()) {}
Scene::~Scene() {
  // The meshes' arrays go to the next scene (recycled_buffers.h), once Embree, which shares
  // the positions, is gone.
  embree_.reset();
  for (StoredMesh& m : meshes_) {
    recycled::keep(std::move(m.positions));
    recycled::keep(std::move(m.normals));
    recycled::keep(std::move(m.uvs));
    recycled::keep(std::move(m.indices));
    recycled::keep(std::move(m.material_indices));
  }
}

uint32_t Scene::add_material(Material material) {
  if (committed_) throw ParameterError("add_material: the scene is already committed");
  if (material.components.size() > static_cast<size_t>(BSDF::kMaxComponents))
    throw ParameterError("material has " + std::to_string(material.components.size()) +
                         " components; at most " + std::to_string(BSDF::kMaxComponents));
  for (const BxDFPtr& c : material.components)
    if (!c) throw ParameterError("material has a null component");
  if (!finite_nonnegative(material.emission))
    throw ParameterError("material emission must be in [0, inf) per channel");
  if (material.graph) {
    if (!material.components.empty())
      throw ParameterError("a material has either components or a graph, not both");
    material.emission = material.graph->emission_is_constant()
                            ? material.graph->emitted(nullptr)
                            : RGB(0.0f);
    const RGB& e = material.emission;
    signed_emission_ = signed_emission_ || !material.graph->emission_is_constant() ||
                       e.r < 0.0f || e.g < 0.0f || e.b < 0.0f;
  }
  float eta = 0.0f;
  if (material.graph && (material.graph->flags() & kTransmission)) eta = graph_eta(*material.graph);
  for (const BxDFPtr& c : material.components) {
    if (!(c->flags() & kTransmission)) continue;
    const ParamSet& p = c->params();
    eta = 1.0f;
    if (p.has("eta_i") && p.has("eta_t") && p.number("eta_i") > 0.0)
      eta = static_cast<float>(p.number("eta_t") / p.number("eta_i"));
    // Cycles' Glass and Refraction (parameter `ior`) refract without scaling radiance (their
    // BTDF carries the light side's η², cycles_lobes.h), and the Transparent and Translucent
    // closures do not refract: for all of them there is no scaling to undo, η stays 1. They are
    // transmissive all the same, so their normal keeps its orientation and a ray leaving the
    // glass sees the inverted index, as in Cycles.
    break;
  }
  material_eta_.push_back(eta);
  materials_.push_back(std::move(material));
  return static_cast<uint32_t>(materials_.size() - 1);
}

uint32_t Scene::add_mesh(const MeshView& m) { return store_mesh(m, false, nullptr); }

uint32_t Scene::add_instanced_mesh(const MeshView& m) { return store_mesh(m, true, nullptr); }

uint32_t Scene::add_mesh(Mesh&& mesh) { return store_mesh(mesh.view(), false, &mesh); }

uint32_t Scene::add_instanced_mesh(Mesh&& mesh) { return store_mesh(mesh.view(), true, &mesh); }

namespace {

// Takes the owned vector (its buffer, which `view` points into, moves along unchanged) or
// copies the view's `count` floats or indices.
template <typename T>
void take_or_copy(std::vector<T>* owned, const T* view, size_t count, std::vector<T>* out) {
  if (owned && owned->data() == view && owned->size() == count) {
    *out = std::move(*owned);
  } else {
    *out = recycled::copied<T>(view, count, count + 1);  // + 1: the positions' padding float
  }
}

}  // namespace

uint32_t Scene::add_instance(uint32_t mesh, const float* object_to_world) {
  const std::string who = "instance " + std::to_string(instances_.size());
  if (committed_) throw ParameterError("add_instance: the scene is already committed");
  if (mesh >= meshes_.size() || !meshes_[mesh].instanced)
    throw ParameterError(who + ": mesh " + std::to_string(mesh) +
                         " is not an instanced mesh (add_instanced_mesh)");
  if (!object_to_world) throw ParameterError(who + ": object_to_world is missing");
  for (int i = 0; i < 12; ++i)
    if (!(std::fabs(object_to_world[i]) <= kMaxSceneCoordinate))  // NaN fails too
      throw ParameterError(who + ": object_to_world[" + std::to_string(i) + "] is " +
                           std::to_string(object_to_world[i]) + ", outside [-1e9, 1e9]");
  StoredInstance inst;
  inst.mesh = mesh;
  if (!inst.object.set(object_to_world))
    throw ParameterError(who + ": object_to_world is singular (a placement must be invertible)");
  instances_.push_back(inst);
  return static_cast<uint32_t>(instances_.size() - 1);
}

uint32_t Scene::store_mesh(const MeshView& m, bool instanced, Mesh* owned) {
  if (committed_) throw ParameterError("add_mesh: the scene is already committed");
  const std::string who = "mesh " + std::to_string(meshes_.size());
  if (instanced && m.object_to_world)
    throw ParameterError(who + ": an instanced mesh is in its own object space; its "
                               "object_to_world must be null (each instance places it)");
  if (!m.positions || m.num_vertices == 0)
    throw ParameterError(who + ": positions are empty (need an array of shape (V, 3))");
  if (!m.indices || m.num_triangles == 0)
    throw ParameterError(who + ": indices are empty (need an array of shape (T, 3))");
  if (m.num_vertices > 0xffffffffull || m.num_triangles > 0x3fffffffull)
    throw ParameterError(who + ": too many vertices or triangles");
  StoredMesh s;
  s.instanced = instanced;
  s.num_vertices = m.num_vertices;
  take_or_copy(owned ? &owned->positions : nullptr, m.positions, 3 * m.num_vertices, &s.positions);
  s.positions.reserve(3 * m.num_vertices + 1);  // a no-op when the owner left room for the pad
  for (size_t i = 0; i < s.positions.size(); ++i)
    if (!(std::fabs(s.positions[i]) <= kMaxSceneCoordinate))  // NaN fails too
      throw ParameterError(who + ": positions[" + std::to_string(i / 3) + "] has the coordinate " +
                           std::to_string(s.positions[i]) + ", outside [-1e9, 1e9] m");
  if (m.normals) {
    take_or_copy(owned ? &owned->normals : nullptr, m.normals, 3 * m.num_vertices, &s.normals);
    for (size_t i = 0; i < m.num_vertices; ++i) {
      Vec3 n = load3(s.normals, static_cast<uint32_t>(i));
      // A zero or broken normal falls back to the face normal at shading time.
      if (!normalize_direction(n)) n = Vec3(0, 0, 0);
      std::memcpy(&s.normals[3 * i], &n, sizeof(float) * 3);
    }
  }
  if (m.uvs) {
    take_or_copy(owned ? &owned->uvs : nullptr, m.uvs, 2 * m.num_vertices, &s.uvs);
    for (size_t i = 0; i < s.uvs.size(); ++i)
      if (!std::isfinite(s.uvs[i]))
        throw ParameterError(who + ": uvs[" + std::to_string(i / 2) + "] is not finite");
  }
  add_graph_attributes(m, who, s);
  take_or_copy(owned ? &owned->indices : nullptr, m.indices, 3 * m.num_triangles, &s.indices);
  for (size_t i = 0; i < s.indices.size(); ++i)
    if (s.indices[i] >= m.num_vertices)
      throw ParameterError(who + ": indices[" + std::to_string(i / 3) + "] has vertex " +
                           std::to_string(s.indices[i]) + ", valid range [0, " +
                           std::to_string(m.num_vertices - 1) + "]");
  s.material = m.material;
  if (!(m.terminator.geometry >= 0.0f && m.terminator.geometry <= 1.0f))
    throw ParameterError(who + ": terminator geometry offset " + std::to_string(m.terminator.geometry) +
                         " must be in [0, 1]");
  if (!(m.terminator.shading >= 0.0f && m.terminator.shading < 1.0f))
    throw ParameterError(who + ": terminator shading offset " + std::to_string(m.terminator.shading) +
                         " must be in [0, 1)");
  s.visibility = m.visibility;
  s.terminator = m.terminator;
  // A flat-shaded mesh has no smooth surface to lift a shadow ray onto (smooth_triangle refuses
  // it): without the offset, the light sample skips the test that would find that out.
  if (s.normals.empty()) s.terminator.geometry = 0.0f;
  if (m.material_indices) {
    take_or_copy(owned ? &owned->material_indices : nullptr, m.material_indices, m.num_triangles,
                 &s.material_indices);
    for (size_t i = 0; i < s.material_indices.size(); ++i)
      if (s.material_indices[i] >= materials_.size())
        throw ParameterError(who + ": material_indices[" + std::to_string(i) + "] is " +
                             std::to_string(s.material_indices[i]) + ", but there are " +
                             std::to_string(materials_.size()) + " materials");
  } else if (m.material >= materials_.size()) {
    throw ParameterError(who + ": material " + std::to_string(m.material) + ", but there are " +
                         std::to_string(materials_.size()) + " materials");
  }
  s.positions.push_back(0.0f);  // Embree's 16-byte read past the last vertex
  meshes_.push_back(std::move(s));
  return static_cast<uint32_t>(meshes_.size() - 1);
}

void Scene::add_light(Light light) {
  if (committed_) throw ParameterError("add_light: the scene is already committed");
  if (light.type == LightType::Mesh)
    throw ParameterError("add_light: mesh lights come from emissive materials");
  lights_.push_back(std::move(light));
}

void Scene::set_world(const RGB& radiance) {
  EnvironmentSettings s;
  s.constant = radiance;
  set_world(std::move(s));
}

void Scene::set_world(EnvironmentSettings settings) {
  if (committed_) throw ParameterError("set_world: the scene is already committed");
  world_ = std::make_shared<const Environment>(std::move(settings));
}

void Scene::set_world(std::shared_ptr<const Environment> world) {
  if (committed_) throw ParameterError("set_world: the scene is already committed");
  if (!world) throw ParameterError("set_world: the world is null");
  world_ = std::move(world);
}

size_t Scene::num_triangles() const {
  size_t n = 0;
  for (const StoredMesh& m : meshes_) n += m.indices.size() / 3;
  return n;
}

size_t Scene::num_rendered_triangles() const {
  size_t n = 0;
  for (const StoredMesh& m : meshes_)
    if (!m.instanced) n += m.indices.size() / 3;
  for (const StoredInstance& i : instances_) n += meshes_[i.mesh].indices.size() / 3;
  return n;
}

namespace {

// A triangle geometry over the mesh's own arrays (shared with Embree, not copied).
RTCGeometry triangle_geometry(RTCDevice device, const float* positions, size_t num_vertices,
                              const uint32_t* indices, size_t num_triangles, RTCBuildQuality quality) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                             3 * sizeof(float), num_vertices);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0,
                             3 * sizeof(uint32_t), num_triangles);
  rtcSetGeometryBuildQuality(g, quality);  // its own BVH in a two-level scene
  rtcCommitGeometry(g);
  return g;
}

unsigned visibility_mask(const MeshVisibility& v) {
  return kMaskOther | (v.camera ? kMaskCamera : 0u) | (v.shadow ? kMaskShadow : 0u);
}

}  // namespace

Vec3 Scene::world_vertex(const StoredMesh& m, const Hit& hit, uint32_t vertex) const {
  const Vec3 p = load3(m.positions, vertex);
  const ObjectTransform* placed = placement(hit);
  return placed ? placed->point_to_world(p) : p;
}

// One mesh light from the emissive triangles of a mesh, in world space (moved by `placed` for
// an instance, with the winding kept as the instance's normals have it).
void Scene::add_mesh_light(uint32_t mesh, uint32_t instance, int* light_index) {
  const StoredMesh& m = meshes_[mesh];
  const ObjectTransform* placed = instance == kNotInstanced ? nullptr : &instances_[instance].object;
  Light area;
  area.type = LightType::Mesh;
  area.mesh = mesh;
  area.instance = instance;
  area.mirrored = placed && placed->mirrors;
  std::vector<Vec3> registers;  // for the textured estimates, allocated once if needed
  for (size_t t = 0; t < m.indices.size() / 3; ++t) {
    const uint32_t mat = m.material_indices.empty() ? m.material : m.material_indices[t];
    const Material& material = materials_[mat];
    const bool textured = material.graph && !material.graph->emission_is_constant();
    RGB le = material.emission;
    if (textured) {
      // The power estimate: the emission at the centroid, seen along the normal.
      if (registers.empty()) registers.resize(MaterialGraph::kMaxRegisters);
      Hit centroid;
      centroid.mesh = mesh;
      centroid.instance = instance;
      centroid.triangle = static_cast<uint32_t>(t);
      centroid.b1 = centroid.b2 = 1.0f / 3.0f;
      le = textured_emission(*this, centroid, surface_point(centroid).ng, registers.data());
    } else if (le.is_black()) {
      continue;
    }
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = load3(m.positions, m.indices[3 * t + size_t(k)]);
      if (placed) p[k] = placed->point_to_world(p[k]);
    }
    // A mirroring placement flips the winding; vertices 1 and 2 trade places (and so do a
    // sample's barycentrics: Light::mirrored).
    if (area.mirrored) std::swap(p[1], p[2]);
    EmissiveTriangle tri;
    tri.p0 = p[0];
    tri.e1 = p[1] - tri.p0;
    tri.e2 = p[2] - tri.p0;
    Vec3 n = cross(tri.e1, tri.e2);
    tri.area = 0.5f * length(n);
    tri.inv_area = 1.0f / tri.area;
    // Degenerate, or so small that 1 / area overflows: cannot emit.
    if (!normalize_direction(n) || !(tri.area > 0.0f) || !std::isfinite(tri.inv_area)) continue;
    tri.normal = n;
    tri.radiance = le;
    tri.triangle = static_cast<uint32_t>(t);
    tri.textured = textured;
    area.total_area += tri.area;
    area.cdf.push_back(area.total_area);
    area.triangles.push_back(tri);
  }
  if (area.triangles.empty()) return;
  *light_index = static_cast<int>(lights_.size());
  lights_.push_back(std::move(area));
}

void Scene::commit(double expected_rays) {
  if (committed_) return;
  EmbreeState& e = *embree_;
  e.device = rtcNewDevice(nullptr);
  if (!e.device) throw std::runtime_error("Embree: cannot create a device");
  e.scene = rtcNewScene(e.device);
  // Medium quality (binned SAH, no spatial splits): HIGH's spatial splits took ~20x longer to
  // build (1.1 s against 0.06 s for 50k triangles) for a few percent faster traversal, which a
  // render of a few seconds never wins back. Below the compact size, in two levels: each mesh
  // its own medium BVH and a BVH over the meshes on top (Embree's LOW scene quality, which
  // takes each geometry's own). Against one medium BVH over every triangle (what Cycles
  // builds), measured on every harness scene and on 100 overlapping objects: built 10-20%
  // sooner, traced as fast or up to 10% faster. The meshes' own BVHs are not built compact
  // (+32 bytes per triangle at 10 M), so large scenes keep one compact BVH.
  const bool compact = num_triangles() >= kCompactBvhTriangles;
  // The meshes' own BVHs: Embree's quick (Morton) build where the render traces few rays per
  // triangle. Measured in bxdf.render on the harness scenes at 64 spp against the medium
  // build: 242k triangles built in 6 instead of 23 ms, traced 1-4% slower; where the rays per
  // triangle (pixels x samples x (1 + max bounces)) were 19-67, build and render took 2-11%
  // less time; at 108 (cornell) and 117 (cycles_glass_room), 2-6% more. A compact scene is
  // one BVH of the scene's quality (medium).
  const bool quick = !compact && expected_rays > 0.0 &&
                     expected_rays < kQuickBuildRaysPerTriangle * double(num_triangles());
  const RTCBuildQuality mesh_quality = quick ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM;
  quick_build_ = quick;
  rtcSetSceneBuildQuality(e.scene, compact ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_LOW);
  if (compact) rtcSetSceneFlags(e.scene, RTC_SCENE_FLAG_COMPACT);
  const bool masks = rtcGetDeviceProperty(e.device, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) != 0;
  for (const StoredMesh& m : meshes_)
    if (!masks && (!m.visibility.camera || !m.visibility.shadow))
      throw std::runtime_error("Embree: this build has no ray masks, which camera and shadow "
                               "visibility need");
  Vec3 lo(kHuge, kHuge, kHuge), hi(-kHuge, -kHuge, -kHuge);
  auto grow = [&](const Vec3& p) {
    lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
    hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
  };
  // Object-space bounds of the instanced meshes, whose placements' corners bound the scene.
  std::vector<std::array<Vec3, 2>> object_bounds(meshes_.size());
  e.instanced.assign(meshes_.size(), nullptr);
  for (size_t mi = 0; mi < meshes_.size(); ++mi) {
    const StoredMesh& m = meshes_[mi];
    Vec3 mlo(kHuge, kHuge, kHuge), mhi(-kHuge, -kHuge, -kHuge);
    for (size_t i = 0; i < m.num_vertices; ++i) {
      const Vec3 p = load3(m.positions, uint32_t(i));
      mlo = Vec3(std::min(mlo.x, p.x), std::min(mlo.y, p.y), std::min(mlo.z, p.z));
      mhi = Vec3(std::max(mhi.x, p.x), std::max(mhi.y, p.y), std::max(mhi.z, p.z));
    }
    object_bounds[mi] = {mlo, mhi};
    RTCGeometry g = triangle_geometry(e.device, m.positions.data(), m.num_vertices,
                                      m.indices.data(), m.indices.size() / 3, mesh_quality);
    if (m.instanced) {
      // Its own scene, which every instance references; visibility is tested on the instance.
      e.instanced[mi] = rtcNewScene(e.device);
      rtcSetSceneBuildQuality(e.instanced[mi], mesh_quality);
      if (compact) rtcSetSceneFlags(e.instanced[mi], RTC_SCENE_FLAG_COMPACT);
      rtcAttachGeometryByID(e.instanced[mi], g, 0);
      rtcReleaseGeometry(g);
      rtcCommitScene(e.instanced[mi]);
      continue;
    }
    grow(mlo);
    grow(mhi);
    if (masks) rtcSetGeometryMask(g, visibility_mask(m.visibility));
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(e.scene, g, static_cast<unsigned>(mi));  // geometry id = mesh index
    rtcReleaseGeometry(g);
  }
  for (size_t ii = 0; ii < instances_.size(); ++ii) {
    const StoredInstance& inst = instances_[ii];
    RTCGeometry g = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, e.instanced[inst.mesh]);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, inst.object.to_world.data());
    if (masks) rtcSetGeometryMask(g, visibility_mask(meshes_[inst.mesh].visibility));
    rtcCommitGeometry(g);
    // Instances follow the meshes in the id space: id − num_meshes is the instance index.
    rtcAttachGeometryByID(e.scene, g, static_cast<unsigned>(meshes_.size() + ii));
    rtcReleaseGeometry(g);
    const auto& b = object_bounds[inst.mesh];
    for (int c = 0; c < 8; ++c)
      grow(inst.object.point_to_world(
          Vec3(c & 1 ? b[1].x : b[0].x, c & 2 ? b[1].y : b[0].y, c & 4 ? b[1].z : b[0].z)));
  }
  rtcCommitScene(e.scene);
  if (rtcGetDeviceError(e.device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: building the BVH failed: " + embree_error(e.device));

  // One mesh light per drawn mesh (and per placement of an instanced one) with emissive
  // triangles.
  mesh_area_light_.assign(meshes_.size(), -1);
  for (size_t mi = 0; mi < meshes_.size(); ++mi)
    if (!meshes_[mi].instanced) add_mesh_light(static_cast<uint32_t>(mi), kNotInstanced, &mesh_area_light_[mi]);
  instance_area_light_.assign(instances_.size(), -1);
  for (size_t ii = 0; ii < instances_.size(); ++ii)
    add_mesh_light(instances_[ii].mesh, static_cast<uint32_t>(ii), &instance_area_light_[ii]);
  for (const Light& l : lights_)
    if (l.type == LightType::Point || l.type == LightType::Spot || l.type == LightType::Area) {
      const Vec3 p = l.position;
      const float r = l.type == LightType::Area ? 0.5f * (length(l.axis_u) + length(l.axis_v)) : l.radius;
      lo = Vec3(std::min(lo.x, p.x - r), std::min(lo.y, p.y - r), std::min(lo.z, p.z - r));
      hi = Vec3(std::max(hi.x, p.x + r), std::max(hi.y, p.y + r), std::max(hi.z, p.z + r));
    }
  bounding_radius_ = hi.x >= lo.x ? std::max(0.5f * length(hi - lo), 1e-3f) : 1.0f;
  hittable_lights_ = HittableLights(lights_);
  for (size_t i = 0; i < lights_.size(); ++i)
    if (lights_[i].type == LightType::Sun && !lights_[i].is_delta())
      wide_suns_.push_back(static_cast<uint32_t>(i));
  light_sampler_ = LightSampler(lights_, world_.get(), bounding_radius_);
  const bool emits = std::any_of(materials_.begin(), materials_.end(),
                                 [](const Material& m) { return m.may_emit(); });
  rays_find_light_ = !world_->is_black() || !hittable_lights_.empty() || !wide_suns_.empty() || emits;
  committed_ = true;
}

bool Scene::intersect(const Ray& ray, Hit* hit, bool camera_ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = embree_ray_hit(ray, camera_ray ? kMaskCamera : kMaskOther);
  rtcIntersect1(embree_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  *hit = decode_hit(rh.ray.tfar, rh.hit.geomID, rh.hit.instID[0], rh.hit.primID, rh.hit.u,
                    rh.hit.v);
  return true;
}

Hit Scene::decode_hit(float t, uint32_t geometry, uint32_t instance, uint32_t triangle, float u,
                      float v) const {
  Hit hit;
  hit.t = t;
  if (instance != RTC_INVALID_GEOMETRY_ID) {
    hit.instance = instance - static_cast<uint32_t>(meshes_.size());
    hit.mesh = instances_[hit.instance].mesh;
  } else {
    hit.instance = kNotInstanced;
    hit.mesh = geometry;
  }
  hit.triangle = triangle;
  hit.b1 = u;
  hit.b2 = v;
  return hit;
}

void Scene::intersect_camera_rays(const Ray* rays, int count, CameraHit* hits) const {
  static_assert(kCameraPacket == 8, "one RTCRayHit8 packet");
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 rh;
  for (int k = 0; k < 8; ++k) {
    // Unused lanes are invalid and carry a harmless ray.
    const Ray& ray = rays[k < count ? k : 0];
    valid[k] = k < count ? -1 : 0;
    rh.ray.org_x[k] = ray.origin.x;
    rh.ray.org_y[k] = ray.origin.y;
    rh.ray.org_z[k] = ray.origin.z;
    rh.ray.dir_x[k] = ray.dir.x;
    rh.ray.dir_y[k] = ray.dir.y;
    rh.ray.dir_z[k] = ray.dir.z;
    rh.ray.tnear[k] = ray.tmin;
    rh.ray.tfar[k] = ray.tmax;
    rh.ray.time[k] = 0.0f;
    rh.ray.mask[k] = kMaskCamera;
    rh.ray.id[k] = 0;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(valid, embree_->scene, &ctx, &rh);
  for (int k = 0; k < count; ++k) {
    hits[k].found = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    if (hits[k].found)
      hits[k].hit = decode_hit(rh.ray.tfar[k], rh.hit.geomID[k], rh.hit.instID[0][k],
                               rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k]);
  }
}

bool Scene::occluded(const Vec3& origin, const Vec3& dir, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r = embree_shadow_ray(origin, dir, tmax);
  rtcOccluded1(embree_->scene, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void Scene::occluded_stream(const Vec3* origins, const Vec3* dirs, const float* tmax, int count,
                            uint8_t* occluded) const {
  constexpr int kMax = 256;
  RTCRay rays[kMax];
  for (int first = 0; first < count; first += kMax) {
    const int n = std::min(kMax, count - first);
    for (int k = 0; k < n; ++k)
      rays[k] = embree_shadow_ray(origins[first + k], dirs[first + k], tmax[first + k]);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcOccluded1M(embree_->scene, &ctx, rays, unsigned(n), sizeof(RTCRay));
    for (int k = 0; k < n; ++k) occluded[first + k] = rays[k].tfar < 0.0f;
  }
}

void Scene::intersect_stream(const Ray* const* rays, const uint8_t* camera, int count, Hit* hits,
                             uint8_t* found) const {
  constexpr int kMax = 256;
  RTCRayHit rh[kMax];
  for (int first = 0; first < count; first += kMax) {
    const int n = std::min(kMax, count - first);
    for (int k = 0; k < n; ++k)
      rh[k] = embree_ray_hit(*rays[first + k], camera[first + k] ? kMaskCamera : kMaskOther);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcIntersect1M(embree_->scene, &ctx, rh, unsigned(n), sizeof(RTCRayHit));
    for (int k = 0; k < n; ++k) {
      const RTCRayHit& r = rh[k];
      found[first + k] = r.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      if (found[first + k])
        hits[first + k] = decode_hit(r.ray.tfar, r.hit.geomID, r.hit.instID[0], r.hit.primID,
                                     r.hit.u, r.hit.v);
    }
  }
}

void Scene::prefetch_triangle(const Hit& hit) const {
  const StoredMesh& m = meshes_[hit.mesh];
  __builtin_prefetch(m.indices.data() + 3 * size_t(hit.triangle));
  if (!m.material_indices.empty()) __builtin_prefetch(m.material_indices.data() + hit.triangle);
}

void Scene::prefetch_vertices(const Hit& hit) const {
  const StoredMesh& m = meshes_[hit.mesh];
  const uint32_t* t = m.indices.data() + 3 * size_t(hit.triangle);
  for (int k = 0; k < 3; ++k) {
    __builtin_prefetch(m.positions.data() + 3 * size_t(t[k]));
    if (!m.normals.empty()) __builtin_prefetch(m.normals.data() + 3 * size_t(t[k]));
    if (!m.uvs.empty()) __builtin_prefetch(m.uvs.data() + 2 * size_t(t[k]));
  }
  if (!m.uv_maps.empty()) __builtin_prefetch(m.uv_maps[0].data() + 6 * size_t(hit.triangle));
  if (!m.tangents.empty() && !m.tangents[0].empty()) {
    const float* corners = m.tangents[0].data() + 12 * size_t(hit.triangle);
    __builtin_prefetch(corners);
    __builtin_prefetch(corners + 11);  // 48 bytes may span two cache lines
  }
}

SurfacePoint Scene::surface_point(const Hit& hit) const {
  SurfacePoint sp;
  surface_point(hit, &sp);
  return sp;
}

void Scene::surface_point(const Hit& hit, SurfacePoint* out, bool with_tangent) const {
  // Computed in the mesh's space (world, or an instanced mesh's object space), then moved to
  // world space by the hit's placement: points and dp/du as points and vectors, normals by the
  // inverse transpose (which keeps an instance's outside out even when it mirrors).
  // The normals and the tangent are worked on in locals and stored once at the end: copying a
  // just-normalised field of the returned point into another (sp.ns = sp.ng) read it back
  // from memory before its stores had landed, a store-forwarding stall of ~10% of this function.
  const StoredMesh& m = meshes_[hit.mesh];
  const ObjectTransform* placed = placement(hit);
  const uint32_t i0 = m.indices[3 * size_t(hit.triangle)];
  const uint32_t i1 = m.indices[3 * size_t(hit.triangle) + 1];
  const uint32_t i2 = m.indices[3 * size_t(hit.triangle) + 2];
  const float b0 = 1.0f - hit.b1 - hit.b2;
  const Vec3 p0 = load3(m.positions, i0), p1 = load3(m.positions, i1), p2 = load3(m.positions, i2);
  SurfacePoint& sp = *out;
  Vec3 p = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  Vec3 ng = cross(e1, e2);
  if (placed) {
    p = placed->point_to_world(p);
    ng = placed->normal_to_world(ng);
  }
  if (!normalize_direction(ng)) ng = Vec3(0, 0, 1);
  Vec3 ns = ng;
  Vec3 smooth = ng;
  if (!m.normals.empty()) {
    Vec3 n = load3(m.normals, i0) * b0 + load3(m.normals, i1) * hit.b1 +
             load3(m.normals, i2) * hit.b2;
    if (placed) n = placed->normal_to_world(n);
    smooth = n;
    if (normalize_direction(n)) {
      ns = n;
      // The geometric normal follows the side the shading normals give (pbrt's convention).
      if (dot(ng, ns) < 0.0f) ng = -ng;
    }
  }
  sp.p = p;
  sp.ng = ng;
  sp.ns = ns;
  sp.smooth_normal = smooth;
  bool have_tangent = false;
  Vec3 tangent;
  if (!m.uvs.empty()) {
    const float* uv = m.uvs.data();
    const float u0 = uv[2 * i0], v0 = uv[2 * i0 + 1];
    const float du1 = uv[2 * i1] - u0, dv1 = uv[2 * i1 + 1] - v0;
    const float du2 = uv[2 * i2] - u0, dv2 = uv[2 * i2 + 1] - v0;
    sp.uv = Point2(u0 * b0 + uv[2 * i1] * hit.b1 + uv[2 * i2] * hit.b2,
                   v0 * b0 + uv[2 * i1 + 1] * hit.b1 + uv[2 * i2 + 1] * hit.b2);
    const float det = du1 * dv2 - dv1 * du2;
    if (with_tangent && std::fabs(det) > 1e-20f) {
      tangent = (e1 * dv2 - e2 * dv1) / det;  // dp/du
      if (placed) tangent = placed->vector_to_world(tangent);
      have_tangent = normalize_direction(tangent);
    }
  } else {
    sp.uv = Point2(hit.b1, hit.b2);
  }
  sp.tangent = have_tangent ? tangent : with_tangent ? radial_tangent(hit, p) : Vec3(0, 0, 0);
  sp.material = material_of(hit);
}

Vec3 Scene::uv(const Hit& hit, int map) const {
  const StoredMesh& m = meshes_[hit.mesh];
  const float b0 = 1.0f - hit.b1 - hit.b2;
  if (map >= 0 && size_t(map) < m.uv_maps.size()) {
    const float* c = m.uv_maps[size_t(map)].data() + 6 * size_t(hit.triangle);
    return {c[0] * b0 + c[2] * hit.b1 + c[4] * hit.b2, c[1] * b0 + c[3] * hit.b1 + c[5] * hit.b2,
            0.0f};
  }
  if (map == 0 && m.uv_maps.empty() && !m.uvs.empty()) {
    const uint32_t* t = &m.indices[3 * size_t(hit.triangle)];
    const float* uv = m.uvs.data();
    return {uv[2 * t[0]] * b0 + uv[2 * t[1]] * hit.b1 + uv[2 * t[2]] * hit.b2,
            uv[2 * t[0] + 1] * b0 + uv[2 * t[1] + 1] * hit.b1 + uv[2 * t[2] + 1] * hit.b2, 0.0f};
  }
  return {0.0f, 0.0f, 0.0f};
}

bool Scene::tangent(const Hit& hit, int map, Vec3* tangent, float* sign) const {
  const StoredMesh& m = meshes_[hit.mesh];
  if (map < 0 || size_t(map) >= m.tangents.size() || m.tangents[size_t(map)].empty()) return false;
  const float* c = m.tangents[size_t(map)].data() + 12 * size_t(hit.triangle);
  const float b0 = 1.0f - hit.b1 - hit.b2;
  *tangent = Vec3(c[0], c[1], c[2]) * b0 + Vec3(c[4], c[5], c[6]) * hit.b1 +
             Vec3(c[8], c[9], c[10]) * hit.b2;
  *sign = c[3] * b0 + c[7] * hit.b1 + c[11] * hit.b2;
  return true;
}

Vec3 Scene::smooth_normal(const Hit& hit) const {
  const StoredMesh& m = meshes_[hit.mesh];
  const ObjectTransform* placed = placement(hit);
  const uint32_t* t = &m.indices[3 * size_t(hit.triangle)];
  if (m.normals.empty()) {
    Vec3 n = cross(load3(m.positions, t[1]) - load3(m.positions, t[0]),
                   load3(m.positions, t[2]) - load3(m.positions, t[0]));
    if (placed) n = placed->normal_to_world(n);
    return normalize_direction(n) ? n : Vec3(0, 0, 1);
  }
  const float b0 = 1.0f - hit.b1 - hit.b2;
  const Vec3 n = load3(m.normals, t[0]) * b0 + load3(m.normals, t[1]) * hit.b1 +
                 load3(m.normals, t[2]) * hit.b2;
  return placed ? placed->normal_to_world(n) : n;
}

Vec3 Scene::object_position(const Hit& hit, const Vec3& p) const {
  return object_of(hit).point_to_object(p);
}

Vec3 Scene::generated(const Hit& hit, const Vec3& p) const {
  const StoredMesh& m = meshes_[hit.mesh];
  const Vec3 d = object_position(hit, p) - m.texspace_location;
  return {d.x * m.texspace_inv_size.x * 0.5f + 0.5f, d.y * m.texspace_inv_size.y * 0.5f + 0.5f,
          d.z * m.texspace_inv_size.z * 0.5f + 0.5f};
}

Vec3 Scene::normal_to_object(const Hit& hit, const Vec3& n) const {
  return object_of(hit).normal_to_object(n);
}

Vec3 Scene::radial_tangent(const Hit& hit, const Vec3& p) const {
  // svm_node_tangent's radial mode about Z, on generated coordinates, taken to world space as
  // a normal is (Cycles does the same: object_normal_transform).
  const Vec3 g = generated(hit, p);
  return normal_to_world(hit, Vec3(-(g.y - 0.5f), g.x - 0.5f, 0.0f));
}

Vec3 Scene::normal_to_world(const Hit& hit, const Vec3& n) const {
  return object_of(hit).normal_to_world(n);
}

Hit Scene::offset_hit(const Hit& hit, const Vec3& world_dp) const {
  const StoredMesh& m = meshes_[hit.mesh];
  const ObjectTransform* placed = placement(hit);
  // Barycentrics do not change under an affine map: solved in the mesh's own space.
  const Vec3 dp = placed ? placed->vector_to_object(world_dp) : world_dp;
  const uint32_t* t = &m.indices[3 * size_t(hit.triangle)];
  const Vec3 p0 = load3(m.positions, t[0]);
  const Vec3 e1 = load3(m.positions, t[1]) - p0, e2 = load3(m.positions, t[2]) - p0;
  // dp = e1·d1 + e2·d2 in the least-squares sense (Cramer's rule on the normal equations).
  const float a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2);
  const float r1 = dot(dp, e1), r2 = dot(dp, e2);
  const float det = a * c - b * b;
  Hit moved = hit;
  if (std::fabs(det) > 1e-30f) {
    moved.b1 += (c * r1 - b * r2) / det;
    moved.b2 += (a * r2 - b * r1) / det;
  }
  return moved;
}

bool Scene::smooth_triangle(const Hit& hit, SmoothTriangle* tri) const {
  const StoredMesh& m = meshes_[hit.mesh];
  if (m.normals.empty()) return false;
  const ObjectTransform* placed = placement(hit);
  for (int k = 0; k < 3; ++k) {
    const uint32_t i = m.indices[3 * size_t(hit.triangle) + k];
    tri->v[k] = world_vertex(m, hit, i);
    tri->n[k] = load3(m.normals, i);
    if (tri->n[k] == Vec3(0, 0, 0)) return false;  // broken normal: shaded flat
    if (placed) {
      tri->n[k] = placed->normal_to_world(tri->n[k]);
      if (!normalize_direction(tri->n[k])) return false;
    }
  }
  return true;
}

void* Scene::embree_scene() const { return embree_->scene; }

}  // namespace bxdf::render

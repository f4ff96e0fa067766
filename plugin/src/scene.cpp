#include "bxdf/render/scene.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "bxdf/params.h"

namespace bxdf::render {

struct Scene::EmbreeState {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~EmbreeState() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

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

Vec3 load3(const std::vector<float>& a, uint32_t i) {
  return {a[3 * size_t(i)], a[3 * size_t(i) + 1], a[3 * size_t(i) + 2]};
}

}  // namespace

Scene::Scene() : embree_(std::make_unique<EmbreeState>()) {}
Scene::~Scene() = default;

uint32_t Scene::add_material(Material material) {
  if (committed_) throw ParameterError("add_material: the scene is already committed");
  if (material.components.size() > static_cast<size_t>(BSDF::kMaxComponents))
    throw ParameterError("material has " + std::to_string(material.components.size()) +
                         " components; at most " + std::to_string(BSDF::kMaxComponents));
  for (const BxDFPtr& c : material.components)
    if (!c) throw ParameterError("material has a null component");
  if (!finite_nonnegative(material.emission))
    throw ParameterError("material emission must be in [0, inf) per channel");
  float eta = 0.0f;
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

uint32_t Scene::add_mesh(const MeshView& m) {
  if (committed_) throw ParameterError("add_mesh: the scene is already committed");
  const std::string who = "mesh " + std::to_string(meshes_.size());
  if (!m.positions || m.num_vertices == 0)
    throw ParameterError(who + ": positions are empty (need an array of shape (V, 3))");
  if (!m.indices || m.num_triangles == 0)
    throw ParameterError(who + ": indices are empty (need an array of shape (T, 3))");
  if (m.num_vertices > 0xffffffffull || m.num_triangles > 0x3fffffffull)
    throw ParameterError(who + ": too many vertices or triangles");
  StoredMesh s;
  s.positions.assign(m.positions, m.positions + 3 * m.num_vertices);
  for (size_t i = 0; i < s.positions.size(); ++i)
    if (!std::isfinite(s.positions[i]))
      throw ParameterError(who + ": positions[" + std::to_string(i / 3) + "] is not finite");
  if (m.normals) {
    s.normals.assign(m.normals, m.normals + 3 * m.num_vertices);
    for (size_t i = 0; i < m.num_vertices; ++i) {
      Vec3 n = load3(s.normals, static_cast<uint32_t>(i));
      // A zero or broken normal falls back to the face normal at shading time.
      if (!normalize_direction(n)) n = Vec3(0, 0, 0);
      std::memcpy(&s.normals[3 * i], &n, sizeof(float) * 3);
    }
  }
  if (m.uvs) {
    s.uvs.assign(m.uvs, m.uvs + 2 * m.num_vertices);
    for (size_t i = 0; i < s.uvs.size(); ++i)
      if (!std::isfinite(s.uvs[i]))
        throw ParameterError(who + ": uvs[" + std::to_string(i / 2) + "] is not finite");
  }
  s.indices.assign(m.indices, m.indices + 3 * m.num_triangles);
  for (size_t i = 0; i < s.indices.size(); ++i)
    if (s.indices[i] >= m.num_vertices)
      throw ParameterError(who + ": indices[" + std::to_string(i / 3) + "] has vertex " +
                           std::to_string(s.indices[i]) + ", valid range [0, " +
                           std::to_string(m.num_vertices - 1) + "]");
  s.material = m.material;
  if (m.material_indices) {
    s.material_indices.assign(m.material_indices, m.material_indices + m.num_triangles);
    for (size_t i = 0; i < s.material_indices.size(); ++i)
      if (s.material_indices[i] >= materials_.size())
        throw ParameterError(who + ": material_indices[" + std::to_string(i) + "] is " +
                             std::to_string(s.material_indices[i]) + ", but there are " +
                             std::to_string(materials_.size()) + " materials");
  } else if (m.material >= materials_.size()) {
    throw ParameterError(who + ": material " + std::to_string(m.material) + ", but there are " +
                         std::to_string(materials_.size()) + " materials");
  }
  meshes_.push_back(std::move(s));
  return static_cast<uint32_t>(meshes_.size() - 1);
}

void Scene::add_light(Light light) {
  if (committed_) throw ParameterError("add_light: the scene is already committed");
  if (light.type == LightType::Area || light.type == LightType::World)
    throw ParameterError("add_light: area lights come from emissive materials and the world "
                         "from set_world");
  lights_.push_back(std::move(light));
}

void Scene::set_world(const RGB& radiance) {
  if (committed_) throw ParameterError("set_world: the scene is already committed");
  if (!finite_nonnegative(radiance))
    throw ParameterError("world color must be in [0, inf) per channel");
  world_ = radiance;
}

size_t Scene::num_triangles() const {
  size_t n = 0;
  for (const StoredMesh& m : meshes_) n += m.indices.size() / 3;
  return n;
}

void Scene::commit() {
  if (committed_) return;
  EmbreeState& e = *embree_;
  e.device = rtcNewDevice(nullptr);
  if (!e.device) throw std::runtime_error("Embree: cannot create a device");
  e.scene = rtcNewScene(e.device);
  rtcSetSceneBuildQuality(e.scene, RTC_BUILD_QUALITY_HIGH);
  for (const StoredMesh& m : meshes_) {
    RTCGeometry g = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t nv = m.positions.size() / 3, nt = m.indices.size() / 3;
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
    if (!vb || !ib) throw std::runtime_error("Embree: " + embree_error(e.device));
    std::memcpy(vb, m.positions.data(), m.positions.size() * sizeof(float));
    std::memcpy(ib, m.indices.data(), m.indices.size() * sizeof(uint32_t));
    rtcCommitGeometry(g);
    rtcAttachGeometry(e.scene, g);  // ids are 0, 1, ... in order: the mesh index
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(e.scene);
  if (rtcGetDeviceError(e.device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: building the BVH failed: " + embree_error(e.device));

  // One area light per mesh that has emissive triangles.
  mesh_area_light_.assign(meshes_.size(), -1);
  for (size_t mi = 0; mi < meshes_.size(); ++mi) {
    const StoredMesh& m = meshes_[mi];
    Light area;
    area.type = LightType::Area;
    for (size_t t = 0; t < m.indices.size() / 3; ++t) {
      const uint32_t mat = m.material_indices.empty() ? m.material : m.material_indices[t];
      const RGB& le = materials_[mat].emission;
      if (le.is_black()) continue;
      EmissiveTriangle tri;
      tri.p0 = load3(m.positions, m.indices[3 * t]);
      tri.e1 = load3(m.positions, m.indices[3 * t + 1]) - tri.p0;
      tri.e2 = load3(m.positions, m.indices[3 * t + 2]) - tri.p0;
      Vec3 n = cross(tri.e1, tri.e2);
      tri.area = 0.5f * length(n);
      if (!normalize_direction(n) || !(tri.area > 0.0f)) continue;  // degenerate: cannot emit
      tri.normal = n;
      tri.radiance = le;
      area.total_area += tri.area;
      area.cdf.push_back(area.total_area);
      area.triangles.push_back(tri);
    }
    if (area.triangles.empty()) continue;
    mesh_area_light_[mi] = static_cast<int>(lights_.size());
    lights_.push_back(std::move(area));
  }
  if (!world_.is_black()) lights_.push_back(world_light(world_));
  committed_ = true;
}

bool Scene::intersect(const Ray& ray, Hit* hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
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
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit->t = rh.ray.tfar;
  hit->mesh = rh.hit.geomID;
  hit->triangle = rh.hit.primID;
  hit->b1 = rh.hit.u;
  hit->b2 = rh.hit.v;
  return true;
}

bool Scene::occluded(const Vec3& origin, const Vec3& dir, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
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
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(embree_->scene, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

SurfacePoint Scene::surface_point(const Hit& hit) const {
  const StoredMesh& m = meshes_[hit.mesh];
  const uint32_t i0 = m.indices[3 * size_t(hit.triangle)];
  const uint32_t i1 = m.indices[3 * size_t(hit.triangle) + 1];
  const uint32_t i2 = m.indices[3 * size_t(hit.triangle) + 2];
  const float b0 = 1.0f - hit.b1 - hit.b2;
  const Vec3 p0 = load3(m.positions, i0), p1 = load3(m.positions, i1), p2 = load3(m.positions, i2);
  SurfacePoint sp;
  sp.p = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  sp.ng = cross(e1, e2);
  if (!normalize_direction(sp.ng)) sp.ng = Vec3(0, 0, 1);
  sp.ns = sp.ng;
  if (!m.normals.empty()) {
    Vec3 n = load3(m.normals, i0) * b0 + load3(m.normals, i1) * hit.b1 +
             load3(m.normals, i2) * hit.b2;
    if (normalize_direction(n)) {
      sp.ns = n;
      // The geometric normal follows the side the shading normals give (pbrt's convention).
      if (dot(sp.ng, sp.ns) < 0.0f) sp.ng = -sp.ng;
    }
  }
  bool have_tangent = false;
  if (!m.uvs.empty()) {
    const float* uv = m.uvs.data();
    const float u0 = uv[2 * i0], v0 = uv[2 * i0 + 1];
    const float du1 = uv[2 * i1] - u0, dv1 = uv[2 * i1 + 1] - v0;
    const float du2 = uv[2 * i2] - u0, dv2 = uv[2 * i2 + 1] - v0;
    sp.uv = Point2(u0 * b0 + uv[2 * i1] * hit.b1 + uv[2 * i2] * hit.b2,
                   v0 * b0 + uv[2 * i1 + 1] * hit.b1 + uv[2 * i2 + 1] * hit.b2);
    const float det = du1 * dv2 - dv1 * du2;
    if (std::fabs(det) > 1e-20f) {
      sp.tangent = (e1 * dv2 - e2 * dv1) / det;  // dp/du
      have_tangent = normalize_direction(sp.tangent);
    }
  } else {
    sp.uv = Point2(hit.b1, hit.b2);
  }
  if (!have_tangent) sp.tangent = Vec3(-sp.p.y, sp.p.x, 0.0f);  // radial about Z, as Cycles
  sp.material = m.material_indices.empty() ? m.material : m.material_indices[hit.triangle];
  return sp;
}

void* Scene::embree_scene() const { return embree_->scene; }

}  // namespace bxdf::render

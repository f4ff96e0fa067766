#include "bxdf/render/transparent_shadows.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bxdf/frame.h"
#include "bxdf/models/cycles_transparent.h"
#include "bxdf/params.h"

namespace bxdf::render {

namespace {

const CyclesTransparent* as_transparent(const BxDF* b) {
  return dynamic_cast<const CyclesTransparent*>(b);
}

bool has_transparent(const Material& m) {
  for (const BxDFPtr& c : m.components)
    if (TransparentShadows::is_transparent(c.get())) return true;
  if (m.graph)
    for (const GraphClosure& c : m.graph->closures)
      if (c.model && c.model->name == "cycles_transparent") return true;
  return false;
}

// Graph registers and closures of one shadow hit: the path's own scratch holds the BSDF of
// the point the shadow ray leaves from, so the shadow has its own.
struct ShadowScratch {
  Vec3 registers[MaterialGraph::kMaxRegisters];
  ClosureArena arena;
};

}  // namespace

bool TransparentShadows::is_transparent(const BxDF* component) {
  return as_transparent(component) != nullptr;
}

TransparentShadows::TransparentShadows(const Scene& scene, int max_transparent_bounces)
    : scene_(scene), max_hits_(max_transparent_bounces) {
  if (max_transparent_bounces < 0)
    throw ParameterError("max_transparent_bounces " + std::to_string(max_transparent_bounces) +
                         " must be in [0, inf)");
  for (const Material& m : scene.materials()) {
    transparent_.push_back(has_transparent(m) ? 1 : 0);
    any_ = any_ || transparent_.back() != 0;
  }
}

RGB TransparentShadows::surface_transparency(const Hit& hit, SurfacePoint sp,
                                             const Vec3& dir) const {
  thread_local ShadowScratch scratch;
  const Material& mat = scene_.materials()[sp.material];
  const Vec3 wo = -dir;
  // As the path tracer shades, the viewer here being the shadow ray's origin.
  const bool flipped = face_viewer(sp, wo, scene_.transmissive(sp.material));
  BSDF bsdf(Frame::from_normal_tangent(sp.ns, sp.tangent), sp.ns);
  if (mat.graph) {
    const ShadingContext ctx{&scene_, &hit, sp.p, sp.ns, sp.ng, wo, flipped, &sp};
    mat.graph->evaluate(ctx, scratch.registers);
    scratch.arena.reset();
    mat.graph->add_closures(scratch.registers, sp.tangent, scratch.arena, bsdf);
  } else {
    for (const BxDFPtr& c : mat.components) bsdf.add(c.get());
  }
  return transparent_weight(bsdf);
}

RGB TransparentShadows::transparent_weight(const BSDF& bsdf) {
  RGB sum(0.0f);
  for (int i = 0; i < bsdf.num_components(); ++i)
    if (const CyclesTransparent* t = as_transparent(bsdf.component(i)))
      sum += bsdf.weight(i) * t->color();
  return sum;
}

float TransparentShadows::past_hit(const Ray& ray, float t) {
  const Vec3 p = ray.at(t);
  const float scale = 1.0f + std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
  return t + 3e-5f * scale;
}

RGB TransparentShadows::throughput(const Vec3& origin, const Vec3& dir, float tmax,
                                   int path_transparent_bounces) const {
  const int budget = std::max(max_hits_ - path_transparent_bounces, 0);
  if (!any_) return scene_.occluded(origin, dir, tmax) ? RGB(0.0f) : RGB(1.0f);
  RGB t(1.0f);
  Ray ray;
  ray.origin = origin;
  ray.dir = dir;
  ray.tmax = tmax;
  for (int hits = 0;; ++hits) {
    Hit hit;
    if (!scene_.intersect(ray, &hit)) return t;
    const SurfacePoint sp = scene_.surface_point(hit);
    if (!transparent(sp.material) || hits >= budget) return RGB(0.0f);
    t *= surface_transparency(hit, sp, dir);
    if (t.is_black()) return RGB(0.0f);
    ray.tmin = past_hit(ray, hit.t);  // on past the surface, along the same ray
    if (!(ray.tmin < ray.tmax)) return t;
  }
}

}  // namespace bxdf::render

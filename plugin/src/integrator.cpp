#include "bxdf/render/integrator.h"

#include <algorithm>
#include <limits>
#include <string>

#include "bxdf/params.h"
#include "bxdf/sampling.h"

namespace bxdf::render {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// What a material graph needs per hit, reused along a path without touching the heap.
struct ShadingScratch {
  Vec3 registers[MaterialGraph::kMaxRegisters];
  ClosureArena arena;
};

// Distance by which a new ray starts off the surface, relative to the coordinates' size: the
// hit point comes from barycentrics, accurate to a few ulps, so ~250 ulps is safe.
float offset_scale(const Vec3& p) {
  return 3e-5f * (1.0f + std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z))));
}

// Moves p off the surface along the geometric normal, to the side that `dir` leaves towards.
Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  const float eps = offset_scale(p);
  return dot(dir, ng) >= 0.0f ? p + ng * eps : p - ng * eps;
}

}  // namespace

PathTracer::PathTracer(const Scene& scene, const IntegratorSettings& settings)
    : scene_(scene), settings_(settings) {
  if (!scene.committed()) throw ParameterError("PathTracer: the scene is not committed");
  if (settings.max_bounces < 0)
    throw ParameterError("max_bounces " + std::to_string(settings.max_bounces) +
                         " must be in [0, inf)");
  if (settings.russian_roulette_depth < 0)
    throw ParameterError("russian_roulette_depth must be in [0, inf)");
  const auto& lights = scene.lights();
  light_select_pdf_ = lights.empty() ? 0.0f : 1.0f / static_cast<float>(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type == LightType::World || (l.type == LightType::Sun && l.cos_sun_max < 1.0f))
      environment_lights_.push_back(static_cast<int>(i));
  }
}

RGB PathTracer::sample_one_light(const SurfacePoint& sp, const BSDF& bsdf, const Vec3& wo,
                                 PCG32& rng, PathStats& stats) const {
  const auto& lights = scene_.lights();
  if (lights.empty()) return RGB(0.0f);
  const size_t n = lights.size();
  const size_t index = std::min(static_cast<size_t>(rng.uniform() * static_cast<float>(n)), n - 1);
  const Light& light = lights[index];
  const float u1 = rng.uniform(), u2 = rng.uniform();
  const LightSample ls = sample_light(light, sp.p, Point2(u1, u2));
  if (!(ls.pdf > 0.0f) || ls.radiance.is_black()) return RGB(0.0f);
  const RGB f = bsdf.f_cos(wo, ls.wi);
  if (f.is_black()) return RGB(0.0f);

  const Vec3 origin = offset_origin(sp.p, sp.ng, ls.wi);
  float tmax = kInfinity;
  if (std::isfinite(ls.distance)) {
    // Stop short of the light's own surface (area lights) by a little more than the offset.
    const float eps = offset_scale(sp.p);
    tmax = std::max(0.0f, ls.distance * (1.0f - 1e-4f) - 2.0f * eps);
  }
  ++stats.shadow_rays;
  if (scene_.occluded(origin, ls.wi, tmax)) return RGB(0.0f);

  const float light_pdf = ls.pdf * light_select_pdf_;
  if (light.is_delta()) return f * ls.radiance / light_pdf;
  const float bsdf_pdf = bsdf.pdf(wo, ls.wi);
  return f * ls.radiance * (power_heuristic(1.0f, light_pdf, 1.0f, bsdf_pdf) / light_pdf);
}

PathResult PathTracer::trace(const Ray& camera_ray, PCG32& rng, PathStats& stats) const {
  PathResult result;
  RGB L(0.0f), beta(1.0f);
  float eta_scale = 1.0f;  // product of (η_wi/η_wo)² over refractions: undoes radiance scaling
  Ray ray = camera_ray;
  bool specular_bounce = false;
  float prev_pdf = 0.0f;  // BSDF pdf of the direction that led here (for MIS)
  Vec3 prev_p;
  const auto& lights = scene_.lights();
  // Per thread, made once: graph registers and per-hit closures (reset at every hit).
  thread_local ShadingScratch scratch;

  for (int bounce = 0;; ++bounce) {
    Hit hit;
    ++stats.rays;
    if (!scene_.intersect(ray, &hit)) {
      // Escaped: the world and any sun with a cone. Counted in full where light sampling could
      // not have found them (camera rays, delta bounces), else weighted against light sampling.
      for (int li : environment_lights_) {
        const RGB le = environment_radiance(lights[size_t(li)], ray.dir);
        if (le.is_black()) continue;
        if (bounce == 0 || specular_bounce) {
          L += beta * le;
        } else {
          const float lp = light_select_pdf_ * environment_pdf(lights[size_t(li)], ray.dir);
          L += beta * le * power_heuristic(1.0f, prev_pdf, 1.0f, lp);
        }
      }
      break;
    }
    if (bounce == 0) result.alpha = 1.0f;

    SurfacePoint sp = scene_.surface_point(hit);
    const Vec3 wo = -ray.dir;
    const Material& mat = scene_.materials()[sp.material];

    // Surfaces that only reflect are two-sided: face them towards the viewer. Transmissive
    // ones keep their orientation, which tells the model inside from outside.
    const bool transmissive = scene_.transmissive(sp.material);
    const bool flipped = dot(wo, sp.ng) < 0.0f && !transmissive;
    if (flipped) {
      sp.ng = -sp.ng;
      sp.ns = -sp.ns;
    }
    BSDF bsdf(Frame::from_normal_tangent(sp.ns, sp.tangent), sp.ng);
    RGB emitted = mat.emission;
    if (mat.graph) {
      // A node material: run its program at this point, then build its closures in place
      // (not at a path's last hit, where only emission counts).
      const bool scatters = bounce <= settings_.max_bounces;
      if (scatters || !mat.graph->emission_is_constant()) {
        const ShadingContext ctx{&scene_, &hit, sp.p, sp.ns, sp.ng, wo, flipped};
        mat.graph->evaluate(ctx, scratch.registers);
      }
      if (!mat.graph->emission_is_constant()) emitted = mat.graph->emitted(scratch.registers);
      if (scatters) {
        scratch.arena.reset();
        mat.graph->add_closures(scratch.registers, sp.tangent, scratch.arena, bsdf);
      }
    } else {
      for (const BxDFPtr& c : mat.components) bsdf.add(c.get());
    }

    if (!emitted.is_black()) {
      if (bounce == 0 || specular_bounce) {
        L += beta * emitted;
      } else {
        // Textured emission is found by BSDF sampling alone (it is not an area light).
        const bool textured = mat.graph && !mat.graph->emission_is_constant();
        const int li = textured ? -1 : scene_.area_light_of_mesh(hit.mesh);
        const float lp =
            li < 0 ? 0.0f
                   : light_select_pdf_ * area_light_pdf(lights[size_t(li)], prev_p, sp.p, sp.ng);
        L += beta * emitted * power_heuristic(1.0f, prev_pdf, 1.0f, lp);
      }
    }
    if (bounce > settings_.max_bounces || bsdf.num_components() == 0) break;

    if (bsdf.has_non_delta()) L += beta * sample_one_light(sp, bsdf, wo, rng, stats);

    const float u1 = rng.uniform(), u2 = rng.uniform();
    const BSDFSample bs = bsdf.sample_f(wo, Point2(u1, u2));
    if (!bs.valid() || bs.f.is_black()) break;
    beta *= bs.f_cos / bs.pdf;
    if (beta.is_black()) break;
    if (transmissive && (bs.flags & kTransmission)) {
      // Entering (wo on the front side) scales radiance by (η_i/η_t)²; leaving undoes it.
      const float eta = scene_.relative_eta(sp.material);
      eta_scale *= dot(wo, sp.ng) > 0.0f ? eta * eta : 1.0f / (eta * eta);
    }
    specular_bounce = bs.is_delta();
    prev_pdf = bs.pdf;
    prev_p = sp.p;
    ray.origin = offset_origin(sp.p, sp.ng, bs.wi);
    ray.dir = bs.wi;
    ray.tmin = 0.0f;
    ray.tmax = kInfinity;

    if (bounce >= settings_.russian_roulette_depth) {
      // Judged on the throughput without refraction's radiance scaling, as pbrt does, so that a
      // path inside glass is not ended more often only because its radiance is scaled down.
      const float m = beta.max_component() * eta_scale;
      if (m < 1.0f) {
        const float q = std::max(0.05f, 1.0f - m);
        if (rng.uniform() < q) break;
        beta *= 1.0f / (1.0f - q);
      }
    }
  }

  if (!finite_nonnegative(L)) {
    ++stats.rejected;
    L = RGB(0.0f);
  }
  result.radiance = L;
  return result;
}

}  // namespace bxdf::render

// The path tracer (pbrt's PathIntegrator with one-light next-event estimation): at each vertex
// one light is picked uniformly and sampled, the BSDF is sampled to continue the path, and both
// strategies are combined with the power heuristic; delta lights and delta lobes are counted by
// the one strategy that can find them. Russian roulette from the fourth bounce on.
#pragma once

#include <cstdint>
#include <vector>

#include "bxdf/render/ray.h"
#include "bxdf/render/scene.h"
#include "bxdf/rng.h"

namespace bxdf::render {

struct IntegratorSettings {
  // 0 = direct light only (emitters seen from the first hit); n = up to n indirect bounces.
  int max_bounces = 8;
  int russian_roulette_depth = 3;  // first bounce at which a path may be ended at random
};

// Per-thread counters, summed after the render.
struct PathStats {
  uint64_t rays = 0;         // closest-hit queries
  uint64_t shadow_rays = 0;  // occlusion queries
  uint64_t rejected = 0;     // samples with NaN, Inf or negative radiance, dropped
};

// A camera sample's result: radiance along the ray and coverage (1 if it hit geometry).
struct PathResult {
  RGB radiance;
  float alpha = 0.0f;
};

class PathTracer {
 public:
  // The scene must be committed. Throws ParameterError for max_bounces < 0.
  PathTracer(const Scene& scene, const IntegratorSettings& settings);

  // Radiance along a camera ray; never NaN, Inf or negative (such samples are counted in
  // stats->rejected and returned as 0).
  PathResult trace(const Ray& camera_ray, PCG32& rng, PathStats& stats) const;

 private:
  RGB sample_one_light(const SurfacePoint& sp, const BSDF& bsdf, const Vec3& wo, PCG32& rng,
                       PathStats& stats) const;

  const Scene& scene_;
  IntegratorSettings settings_;
  float light_select_pdf_ = 0.0f;          // lights are picked uniformly
  std::vector<int> environment_lights_;    // world and suns with a cone: found by escaping rays
};

}  // namespace bxdf::render

// Picks the light for next-event estimation in proportion to its emitted power (pbrt's
// PowerLightSampler), instead of uniformly: a dim fill light gets few samples, the key light
// many. Entry lights.size() stands for an importance-sampled world. Lights of zero power are
// never picked; when every light has zero power they are picked uniformly.
#pragma once

#include <vector>

#include "bxdf/render/environment.h"
#include "bxdf/render/lights.h"

namespace bxdf::render {

class LightSampler {
 public:
  LightSampler() = default;
  // scene_radius: radius of the scene's bounding sphere (the sun's and world's power scale).
  LightSampler(const std::vector<Light>& lights, const Environment* world, float scene_radius);

  bool empty() const { return pmf_.empty(); }
  size_t size() const { return pmf_.size(); }
  // The chosen index (lights.size() = the world) and its probability. `remapped` (optional):
  // u's place within the chosen light's interval, again uniform in [0, 1), so that one number
  // both picks the light and (Cycles' light_distribution_sample) stays a coordinate of the
  // light point, keeping that point's 2D stratification.
  size_t sample(float u, float* probability, float* remapped = nullptr) const;
  float probability(size_t index) const { return index < pmf_.size() ? pmf_[index] : 0.0f; }

 private:
  std::vector<float> pmf_, cdf_;
};

}  // namespace bxdf::render

#include "bxdf/render/light_sampler.h"

#include <algorithm>
#include <cmath>

namespace bxdf::render {

LightSampler::LightSampler(const std::vector<Light>& lights, const Environment* world,
                           float scene_radius) {
  std::vector<float> power;
  for (const Light& l : lights) power.push_back(light_power(l, scene_radius));
  if (world && world->importance_sampled()) power.push_back(world->power(scene_radius));
  if (power.empty()) return;
  double total = 0.0;
  for (float& p : power) {
    if (!(p > 0.0f) || !std::isfinite(p)) p = 0.0f;
    total += p;
  }
  if (!(total > 0.0)) {
    std::fill(power.begin(), power.end(), 1.0f);
    total = static_cast<double>(power.size());
  }
  double running = 0.0;
  for (float p : power) {
    pmf_.push_back(static_cast<float>(p / total));
    running += p / total;
    cdf_.push_back(static_cast<float>(running));
  }
  cdf_.back() = 1.0f;
}

size_t LightSampler::sample(float u, float* probability, float* remapped) const {
  size_t i = static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
  i = std::min(i, pmf_.size() - 1);
  *probability = pmf_[i];
  if (remapped) {
    // A picked light has pmf > 0 (upper_bound passes over empty intervals).
    const float lo = i == 0 ? 0.0f : cdf_[i - 1];
    *remapped = std::min(std::max((u - lo) / pmf_[i], 0.0f), 0x1.fffffep-1f);
  }
  return i;
}

}  // namespace bxdf::render

// Picks the light for next-event estimation. Globally, in proportion to emitted power (pbrt's
// PowerLightSampler): a dim fill light gets few samples, the key light many. Entry
// lights.size() stands for an importance-sampled world. Lights of zero power are never picked;
// when every light has zero power they are picked uniformly.
//
// At a shading point (a LightReceiver), the local lights (point, spot, area, mesh) share their
// joint global probability by how much each can give that point, as a light tree's leaves do
// (Conty & Kulla 2018; Cycles 3.5): power times bounds on the receiver's and the emitter's
// cosines over the light's bounding sphere, over the squared distance. A tenth of the share
// stays in proportion to power alone (a defensive mixture), so that a light the bounds
// underrate (a normal-mapped closure, a light inside its own bounding sphere) is still picked
// now and then and the estimate stays unbiased. A one-sided area light is never picked by a
// point behind it, which it cannot light. The world and the suns keep their global share.
// Used from 2 to kMaxSpatialLights local lights (a flat pass over them per shading point);
// with more, every point uses the global distribution.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "bxdf/render/environment.h"
#include "bxdf/render/lights.h"

namespace bxdf::render {

// Where a light is picked for: the shading point, its normal on the viewer's side, and whether
// light from behind the surface counts too (a transmissive surface). sample(r, ...) also
// leaves the distribution's normalisation at r here, so that probability(r, i) for the light a
// BSDF ray from r finds is one light's work instead of a pass over all of them.
struct LightReceiver {
  Vec3 p;
  Vec3 n{0, 0, 1};
  bool two_sided = false;
  bool normalised = false;         // the factors below are set (for this p, n, two_sided)
  float importance_factor = 0.0f;  // a local light's share: factor · its importance
  float power_factor = 0.0f;       //   + factor · its power (where it can reach p)
  float scale = 1.0f;  // 1, or 1 / the other entries' share where no local light reaches p
};

class LightSampler {
 public:
  // Local lights up to which picking depends on the shading point.
  static constexpr int kMaxSpatialLights = 32;
  // The share of the local lights' probability kept in proportion to power.
  static constexpr float kPowerShare = 0.1f;

  LightSampler() = default;
  // scene_radius: radius of the scene's bounding sphere (the sun's and world's power scale).
  LightSampler(const std::vector<Light>& lights, const Environment* world, float scene_radius);

  bool empty() const { return pmf_.empty(); }
  size_t size() const { return pmf_.size(); }
  // True when picking depends on the shading point (2 to kMaxSpatialLights local lights).
  bool spatial() const { return local_.count > 0; }

  // The global distribution. The chosen index (lights.size() = the world) and its probability.
  // `remapped` (optional): u's place within the chosen light's interval, again uniform in
  // [0, 1), so that one number both picks the light and (Cycles' light_distribution_sample)
  // stays a coordinate of the light point, keeping that point's 2D stratification.
  size_t sample(float u, float* probability, float* remapped = nullptr) const;
  float probability(size_t index) const { return index < pmf_.size() ? pmf_[index] : 0.0f; }

  // The distribution at receiver r (the global one where !spatial()); the same entries and
  // remapping as above, and probability(r, i) is what sample(r, ...) picks i with. Where no
  // local light can reach r and nothing else is left to pick, sample() returns size() with
  // probability 0.
  size_t sample(LightReceiver& r, float u, float* probability, float* remapped = nullptr) const;
  float probability(const LightReceiver& r, size_t index) const;

 private:
  // The local lights' bounds, made once, as a structure of arrays (the pass over them at a
  // shading point is vectorised): each one's bounding sphere, its emitting normal and whether
  // it emits to that side only (1) or both (0), and its power.
  struct LocalLights {
    alignas(16) std::array<float, kMaxSpatialLights> cx{}, cy{}, cz{}, radius{}, nx{}, ny{},
        nz{}, one_sided{}, power{};
    int count = 0;
  };
  // Lights k..k+3's importance at r, and each one's power where it can reach r (else 0), in
  // one pass of 4-wide vector operations (k a multiple of 4; the arrays are padded with
  // lights of power 0). A single light's figures are read from its group's, so that they are
  // the same bits wherever they are needed.
  static void evaluate4(const LocalLights& l, int k, const LightReceiver& r, float* importance,
                        float* reaching_power);
  // Sets r's normalisation from every local light's importance and reaching power.
  void normalise(LightReceiver& r, float* importance, float* reaching_power) const;
  // Local light k's probability at r (normalised), given its importance and reaching power.
  float local_probability(const LightReceiver& r, float importance, float reaching_power) const {
    return local_share_ * (r.importance_factor * importance + r.power_factor * reaching_power);
  }

  std::vector<float> pmf_, cdf_;
  LocalLights local_;          // count 0: picking is global
  std::vector<int> local_of_;  // per entry, its index in local_ (-1: not local)
  float local_share_ = 0.0f;   // the local lights' joint global probability
};

}  // namespace bxdf::render

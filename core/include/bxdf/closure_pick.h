// How a sample picks one of a material's closures. Cycles picks in proportion to the closures'
// sample weights, except at a path's first surface, where it first raises every closure's sample
// weight to at least an eighth of their sum (surface_shader_prepare_closures, "defensive
// sampling"): the Fresnel reflection of glass seen head-on (weight F ~ 0.04 against 0.96) is then
// drawn for about one camera sample in nine instead of one in twenty-five, each carrying less.
// The pdfs use the raised weights, so the estimate stays unbiased; what changes is where its
// variance lies, which is where Cycles has it.
#pragma once

namespace bxdf {

enum class ClosurePick {
  kByWeight,   // in proportion to the sample weights
  kDefensive,  // Cycles' first surface: each weight at least kDefensiveShare of their sum
};

constexpr float kDefensiveShare = 0.125f;

// Raises weights[0..n) in place as Cycles' defensive sampling does; a zero weight (a closure
// that is not built) stays zero. Returns the new sum.
inline float raise_to_defensive_floor(float* weights, int n) {
  float sum = 0.0f;
  for (int i = 0; i < n; ++i) sum += weights[i];
  const float floor = kDefensiveShare * sum;
  float raised = 0.0f;
  for (int i = 0; i < n; ++i) {
    if (weights[i] > 0.0f && weights[i] < floor) weights[i] = floor;
    raised += weights[i];
  }
  return raised;
}

}  // namespace bxdf

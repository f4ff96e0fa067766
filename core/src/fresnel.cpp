#include "bxdf/fresnel.h"

#include <cmath>

namespace bxdf {

float eta_from_f0(float f0) {
  const float s = std::sqrt(clamp(f0, 0.0f, 0.999999f));
  return (1.0f + s) / (1.0f - s);
}

float k_from_f0(float f0) {
  const float f = clamp(f0, 0.0f, 0.999999f);
  return 2.0f * std::sqrt(f / (1.0f - f));
}

}  // namespace bxdf

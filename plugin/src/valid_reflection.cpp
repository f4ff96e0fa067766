#include "bxdf/render/valid_reflection.h"

#include <algorithm>
#include <cmath>

namespace bxdf::render {

Vec3 bend_to_valid_reflection(const Vec3& ng, const Vec3& wo, const Vec3& n, float threshold) {
  // In the frame z = ng, x = n's part across ng, solve 2 (n'·wo) n'_z − wo_z = threshold for a
  // unit n' = (√(1 − n'_z²), 0, n'_z): n'_z² = (c ± b) / (2a).
  const Vec3 across = n - ng * dot(n, ng);
  const float across_len = length(across);
  if (!(across_len > 0.0f)) return ng;
  const Vec3 x_axis = across / across_len;
  const float ix = dot(wo, x_axis), iz = dot(wo, ng);
  const float a = ix * ix + iz * iz;
  if (!(a > 0.0f)) return ng;
  const float b = safe_sqrt(ix * ix * (a - threshold * threshold));
  const float c = iz * threshold + a;
  const float z2_plus = 0.5f * (c + b) / a, z2_minus = 0.5f * (c - b) / a;
  const auto plausible = [](float z2) { return z2 > 1e-5f && z2 <= 1.0f + 1e-5f; };
  const auto reflection_z = [&](float z2) {
    const float x = safe_sqrt(1.0f - z2), z = safe_sqrt(z2);
    return 2.0f * (x * ix + z * iz) * z - iz;
  };
  bool use_plus = plausible(z2_plus), use_minus = plausible(z2_minus);
  float z2;
  if (use_plus && use_minus) {
    // Both solve it: keep the one whose reflection is above the surface, and of two such the
    // shallower, which is closer to n (n's own reflection was not shallow enough).
    const float r_plus = reflection_z(z2_plus), r_minus = reflection_z(z2_minus);
    if (r_plus >= 1e-5f && r_minus >= 1e-5f)
      z2 = r_plus < r_minus ? z2_plus : z2_minus;
    else
      z2 = r_plus > r_minus ? z2_plus : z2_minus;
  } else if (use_plus || use_minus) {
    z2 = use_plus ? z2_plus : z2_minus;
  } else {
    return ng;
  }
  return x_axis * safe_sqrt(1.0f - z2) + ng * safe_sqrt(z2);
}

}  // namespace bxdf::render

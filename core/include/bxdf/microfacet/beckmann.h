// The Beckmann distribution, anisotropic:
// D = exp(−tan²θh (cos²φ/αx² + sin²φ/αy²)) / (π αx αy cos⁴θh).
// Sampling draws wh with density D(wh) cos θh (pbrt-v3 with sampleVisibleArea off).
#pragma once

#include "bxdf/microfacet/common.h"

namespace bxdf {
namespace microfacet {

struct Beckmann {
  float alpha_x = 0.3f, alpha_y = 0.3f;

  Beckmann() = default;
  Beckmann(float ax, float ay) : alpha_x(clamp_alpha(ax)), alpha_y(clamp_alpha(ay)) {}

  BXDF_KERNEL float D(const Vec3& wh) const {
    // tan²θ(cos²φ/αx² + sin²φ/αy²) = (x²/αx² + y²/αy²)/z².
    const float sx = wh.x / alpha_x, sy = wh.y / alpha_y;
    const float z2 = wh.z * wh.z;
    const float e = (sx * sx + sy * sy) / z2;
    // exp(−80) ≈ 2e−35: past this D is far below anything a renderer adds up, and near the
    // horizon the quotient would be a denormal divided by a denormal.
    // exp_poly rather than std::exp so that batch loops over D vectorise; its argument is kept
    // in range (e >= 80 and NaN become 80, whose result is not used).
    const float e_in_range = e < 80.0f ? e : 80.0f;
    const float d = exp_poly(-e_in_range) / (kPi * alpha_x * alpha_y * z2 * z2);
    const float d_in_range = e < 80.0f ? d : 0.0f;
    return wh.z > 0.0f ? d_in_range : 0.0f;
  }
  BXDF_KERNEL float lambda(const Vec3& w) const { return beckmann_lambda(w, alpha_x, alpha_y); }
  BXDF_KERNEL float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }

  Vec3 sample_wh(const Vec3& /*wo*/, Point2 u) const {
    // φ: the marginal of D cos θ is ∝ 1/(cos²φ/αx² + sin²φ/αy²), which the map
    // tan φ = (αy/αx) tan(2πu2) produces; atan2 keeps the quadrant.
    const float t = 2.0f * kPi * u.y;
    const float phi = std::atan2(alpha_y * std::sin(t), alpha_x * std::cos(t));
    const float cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    // θ: tan²θ = −α(φ)² ln(1 − u1) with 1/α(φ)² = cos²φ/αx² + sin²φ/αy².
    const float inv_alpha2 =
        cos_phi * cos_phi / (alpha_x * alpha_x) + sin_phi * sin_phi / (alpha_y * alpha_y);
    const float tan2 = -std::log1p(-u.x) / inv_alpha2;
    const float cos_t = 1.0f / std::sqrt(1.0f + tan2);
    const float sin_t = safe_sqrt(1.0f - cos_t * cos_t);
    return {sin_t * cos_phi, sin_t * sin_phi, cos_t};
  }
  BXDF_KERNEL float pdf_wh(const Vec3& /*wo*/, const Vec3& wh) const { return D(wh) * std::max(0.0f, wh.z); }
};

}  // namespace microfacet
}  // namespace bxdf

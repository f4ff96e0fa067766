// Ashikhmin–Shirley's anisotropic distribution (the seed):
// D = sqrt((ex + 2)(ey + 2))/(2π) · cos θh^(ex cos²φh + ey sin²φh).
// Sampling (Ashikhmin & Shirley 2000, as pbrt-v2): φ in the first quadrant from
// tan φ = sqrt((ex + 1)/(ey + 1)) tan(πu/2), mirrored into the quadrant that u1 picks, then
// cos θh = u2^(1/(ex cos²φ + ey sin²φ + 1)); the half-vector density is
// sqrt((ex + 1)(ey + 1))/(2π) · cos θh^(ex cos²φ + ey sin²φ).
#pragma once

#include "bxdf/microfacet/common.h"

namespace bxdf {
namespace microfacet {

struct AshikhminShirley {
  float exponent_x = 10.0f, exponent_y = 100.0f;
  // Per-axis Beckmann roughness for Λ only (see common.h).
  float alpha_x = beckmann_alpha_from_exponent(10.0f);
  float alpha_y = beckmann_alpha_from_exponent(100.0f);

  AshikhminShirley() = default;
  AshikhminShirley(float ex, float ey)
      : exponent_x(ex),
        exponent_y(ey),
        alpha_x(beckmann_alpha_from_exponent(ex)),
        alpha_y(beckmann_alpha_from_exponent(ey)) {}

  // cos θh^(ex cos²φ + ey sin²φ), as (1 + tan²θh)^(−n/2) (see blinn.h for why).
  float cos_power(const Vec3& wh) const {
    const float xy2 = wh.x * wh.x + wh.y * wh.y;
    if (xy2 == 0.0f) return 1.0f;
    const float n = (exponent_x * wh.x * wh.x + exponent_y * wh.y * wh.y) / xy2;
    return std::exp(-0.5f * n * std::log1p(xy2 / (wh.z * wh.z)));
  }
  float D(const Vec3& wh) const {
    if (wh.z <= 0.0f) return 0.0f;
    return std::sqrt((exponent_x + 2.0f) * (exponent_y + 2.0f)) * kInv2Pi * cos_power(wh);
  }
  // Smith Λ of the anisotropic Beckmann surface with α = sqrt(2/(e + 2)) per axis.
  float lambda(const Vec3& w) const { return beckmann_lambda(w, alpha_x, alpha_y); }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }

  Vec3 sample_wh(const Vec3& /*wo*/, Point2 u) const {
    // u.x picks the quadrant and is stretched back to [0, 1) within it.
    float phi = 0.0f;
    if (u.x < 0.25f) {
      phi = first_quadrant_phi(4.0f * u.x);
    } else if (u.x < 0.5f) {
      phi = kPi - first_quadrant_phi(4.0f * (0.5f - u.x));
    } else if (u.x < 0.75f) {
      phi = kPi + first_quadrant_phi(4.0f * (u.x - 0.5f));
    } else {
      phi = 2.0f * kPi - first_quadrant_phi(4.0f * (1.0f - u.x));
    }
    const float cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    const float n = exponent_x * cos_phi * cos_phi + exponent_y * sin_phi * sin_phi;
    const float cos_t = std::pow(u.y, 1.0f / (n + 1.0f));
    const float sin_t = safe_sqrt(1.0f - cos_t * cos_t);
    return {sin_t * cos_phi, sin_t * sin_phi, cos_t};
  }
  float pdf_wh(const Vec3& /*wo*/, const Vec3& wh) const {
    if (wh.z <= 0.0f) return 0.0f;
    return std::sqrt((exponent_x + 1.0f) * (exponent_y + 1.0f)) * kInv2Pi * cos_power(wh);
  }

 private:
  float first_quadrant_phi(float u) const {
    // u = 1 (at a quadrant boundary) must give π/2, not atan(tan(float(π/2))) < 0.
    if (u >= 1.0f) return kPiOver2;
    if (exponent_x == exponent_y) return kPiOver2 * u;
    return std::atan(std::sqrt((exponent_x + 1.0f) / (exponent_y + 1.0f)) * std::tan(kPiOver2 * u));
  }
};

}  // namespace microfacet
}  // namespace bxdf

// Blinn's microfacet distribution (the seed): D = (e + 2)/(2π) cos^e θh, normalised so
// that ∫ D cos θh dω = 1. Sampling draws cos θh = u1^(1/(e+1)), φ = 2πu2, i.e. density
// (e + 1)/(2π) cos^e θh over the half vector.
#pragma once

#include "bxdf/microfacet/common.h"
#include "bxdf/sampling.h"

namespace bxdf {
namespace microfacet {

struct Blinn {
  float exponent = 20.0f;
  float alpha = beckmann_alpha_from_exponent(20.0f);  // for Λ only (see common.h)

  Blinn() = default;
  explicit Blinn(float e) : exponent(e), alpha(beckmann_alpha_from_exponent(e)) {}

  // cos^e θh computed as (1 + tan²θh)^(−e/2): exact for a unit vector and, unlike
  // pow(z, e), not flattened by z rounding to 1 near the pole when e is large.
  float cos_power(const Vec3& wh) const {
    return std::exp(-0.5f * exponent * std::log1p(tan2_theta_of(wh)));
  }
  float D(const Vec3& wh) const {
    if (wh.z <= 0.0f) return 0.0f;
    return (exponent + 2.0f) * kInv2Pi * cos_power(wh);
  }
  // Smith Λ of the Beckmann surface with α = sqrt(2/(e + 2)) (Blinn has no closed form).
  float lambda(const Vec3& w) const { return beckmann_lambda(w, alpha, alpha); }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }

  Vec3 sample_wh(const Vec3& /*wo*/, Point2 u) const { return sample_cosine_power(u, exponent); }
  float pdf_wh(const Vec3& /*wo*/, const Vec3& wh) const {
    if (wh.z <= 0.0f) return 0.0f;
    return (exponent + 1.0f) * kInv2Pi * cos_power(wh);
  }
};

}  // namespace microfacet
}  // namespace bxdf

// Cycles 3.4's Velvet BSDF (closure/bsdf_ashikhmin_velvet.h), Ashikhmin's velvet lobe:
//   D = exp(−cot²θh/σ²) / (π σ² sin⁴θh),  G = min(1, 2 cos θh cos θo/(ωo·ωh), 2 cos θh cos θi/(ωo·ωh)),
//   f = colour · D G / (4 cos θo cos θi),
// with σ clamped to at least 0.01, cos θh/(ωo·ωh) to at least 1e-5, and f = 0 where
// |cos θh| >= 1 − 1e-5 or ωo·ωh <= 1e-5 (as Cycles). f is symmetric in ωo and ωi.
// Uniform-hemisphere sampling (pdf 1/2π), as Cycles. Two-sided: wo below is mirrored above.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/sampling.h"

namespace bxdf {

class CyclesVelvet final : public BxDFImpl<CyclesVelvet> {
 public:
  static constexpr float kMinSigma = 0.01f;

  CyclesVelvet(const RGB& color, float sigma)
      : BxDFImpl(kReflection | kDiffuse),
        color_(color),
        inv_sigma2_(1.0f / (std::max(sigma, kMinSigma) * std::max(sigma, kMinSigma))) {}

  RGB eval(Vec3 wo, Vec3 wi) const {
    if (!turn_pair_upward(&wo, &wi)) return RGB(0.0f);
    const Vec3 h = normalize(wi + wo);
    const float cos_h = h.z, h_o = std::fabs(dot(wo, h));
    if (!(std::fabs(cos_h) < 1.0f - 1e-5f && h_o > 1e-5f)) return RGB(0.0f);
    const float cos_h_over_h_o = std::max(cos_h / h_o, 1e-5f);
    const float g = std::min(1.0f, 2.0f * cos_h_over_h_o * std::min(wo.z, wi.z));
    const float sin2_h = 1.0f - cos_h * cos_h;
    const float cot2_h = cos_h * cos_h / sin2_h;
    const float d = std::exp(-cot2_h * inv_sigma2_) * inv_sigma2_ * kInvPi / (sin2_h * sin2_h);
    return color_ * (0.25f * d * g / (wo.z * wi.z));
  }
  DirectionSample sample_direction(const Vec3& wo, Point2 u) const {
    DirectionSample d;
    if (wo.z == 0.0f) return d;
    d.wi = sample_uniform_hemisphere(u);
    if (wo.z < 0.0f) d.wi.z = -d.wi.z;
    d.ok = d.wi.z != 0.0f;
    d.flags = kReflection | kDiffuse;
    return d;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    return same_hemisphere(wo, wi) ? uniform_hemisphere_pdf() : 0.0f;
  }

  float closure_sample_weight() const override { return color_.average(); }

 private:

  RGB color_;
  float inv_sigma2_;
};

}  // namespace bxdf

// Cycles 3.4's Glossy/Anisotropic BSDF with the Ashikhmin–Shirley distribution
// (closure/bsdf_ashikhmin_shirley.h): the 2000 specular lobe without its Fresnel term,
//   f = colour · norm · cos θh^e / (|ωh·ωo| · max(cos θo, cos θi)),
//   norm = sqrt((nx + 1)(ny + 1))/(8π), e = (nx h_x² + ny h_y²)/(1 − cos²θh),
// with the exponents n = 2/α² − 2 of α clamped to [1e-4, 1] (α = roughness², anisotropy as
// for GGX). Cycles clamps cos θh and |ωh·ωo| to at least 1e-6 and the denominator to 1e-6.
// Its eval is f·cos θi with cos θi clamped to 1e-6; f here omits that clamp (it only
// differs where cos θi < 1e-6, where f·cos θi is below 1e-6 of the lobe's scale), which keeps
// f exactly reciprocal, as Cycles' formula is.
// Sampling draws ωh from cos θh^e (Ashikhmin and Shirley's quadrant scheme, as Cycles does)
// and reflects; pdf = norm cos θh^e / |ωh·ωo|, Cycles' own pdf. α at the 1e-4 floor on both
// axes is Cycles' singular case: cycles_glossy then builds the mirror (CyclesGlossy).
// Two-sided like every reflection model here: wo below the surface is mirrored above.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/microfacet/ashikhmin_shirley.h"

namespace bxdf {

class CyclesGlossyAshikhminShirley final : public BxDFImpl<CyclesGlossyAshikhminShirley> {
 public:
  // Cycles' α bounds for this distribution.
  static constexpr float kMinAlpha = 1e-4f;
  static constexpr float kMaxAlpha = 1.0f;
  static float exponent_of(float alpha) { return 2.0f / (alpha * alpha) - 2.0f; }

  // alpha_x, alpha_y already clamped to [kMinAlpha, kMaxAlpha].
  CyclesGlossyAshikhminShirley(const RGB& color, float alpha_x, float alpha_y)
      : BxDFImpl(kReflection | kGlossy),
        color_(color),
        n_x_(exponent_of(alpha_x)),
        n_y_(exponent_of(alpha_y)),
        norm_(n_x_ == n_y_ ? (n_x_ + 1.0f) / (8.0f * kPi)
                           : std::sqrt((n_x_ + 1.0f) * (n_y_ + 1.0f)) / (8.0f * kPi)),
        sampler_(n_x_, n_y_) {}

  RGB eval(Vec3 wo, Vec3 wi) const {
    if (!turn_pair_upward(&wo, &wi)) return RGB(0.0f);
    const Vec3 h = normalize(wi + wo);
    const float h_o = std::max(std::fabs(dot(h, wo)), 1e-6f);
    const float pump = 1.0f / std::max(1e-6f, h_o * std::max(std::max(wi.z, 1e-6f),
                                                               std::max(wo.z, 1e-6f)));
    return color_ * (norm_ * lobe(h) * pump);
  }

  DirectionSample sample_direction(Vec3 wo, Point2 u) const {
    DirectionSample d;
    if (wo.z == 0.0f) return d;
    const bool below = wo.z < 0.0f;
    if (below) wo.z = -wo.z;
    const Vec3 h = sampler_.sample_wh(wo, u);
    Vec3 wi = reflect(wo, h);  // the same for h and −h, so Cycles' flip of h is not needed
    d.ok = wi.z > 0.0f;
    if (below) wi.z = -wi.z;
    d.wi = wi;
    d.flags = kReflection | kGlossy;
    return d;
  }

  float density(Vec3 wo, Vec3 wi) const {
    if (!turn_pair_upward(&wo, &wi)) return 0.0f;
    const Vec3 h = normalize(wi + wo);
    const float h_o = std::max(std::fabs(dot(h, wo)), 1e-6f);
    return norm_ * lobe(h) / h_o;
  }

  float exponent_x() const { return n_x_; }
  float exponent_y() const { return n_y_; }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  // cos θh^e, θh clamped as Cycles clamps it.
  float lobe(const Vec3& h) const {
    const float cos_h = std::max(h.z, 1e-6f);
    if (n_x_ == n_y_) return std::pow(cos_h, n_x_);
    if (!(cos_h < 1.0f)) return 1.0f;
    const float e = (n_x_ * h.x * h.x + n_y_ * h.y * h.y) / (1.0f - cos_h * cos_h);
    return std::pow(cos_h, e);
  }

  RGB color_;
  float n_x_, n_y_, norm_;
  microfacet::AshikhminShirley sampler_;  // Ashikhmin and Shirley's quadrant sampling of ωh
};

}  // namespace bxdf

// Cycles 3.4's Diffuse BSDF with roughness > 0 (Fujii's "improved" Oren–Nayar), written out so
// that a render can match Cycles exactly: σ = roughness (no degrees, no squaring),
// A = 1/(π + (π/2 − 2/3)σ), B = σA, s = ωi·ωo − cosθi cosθo,
// t = max(cosθi, cosθo) if s > 0 else 1, f = color (A + B s/t). roughness 0 is Lambertian.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/cosine_reflection.h"

namespace bxdf {

class CyclesOrenNayar final : public BxDFImpl<CyclesOrenNayar> {
 public:
  CyclesOrenNayar(const RGB& color, float roughness)
      : BxDFImpl(kReflection | kDiffuse), color_(color) {
    const float sigma = clamp(roughness, 0.0f, 1.0f);
    a_ = 1.0f / (kPi + (kPiOver2 - 2.0f / 3.0f) * sigma);
    b_ = sigma * a_;
  }

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.0f);
    // Two-sided: Cycles flips the normal towards the viewer, so use |cos θ| on both sides.
    // With both directions on one side, ωi·ωo − cosθi cosθo is just the tangential part.
    const float cos_i = abs_cos_theta(wi), cos_o = abs_cos_theta(wo);
    const float s = wi.x * wo.x + wi.y * wo.y;
    // t > 0 here, since same_hemisphere guarantees both cosines are non-zero. For s ≤ 0 the
    // term is negative but A + B s ≥ A − B = (1 − σ)A ≥ 0, since s ≥ −1.
    const float s_over_t = s > 0.0f ? s / std::max(cos_i, cos_o) : s;
    return color_ * std::max(0.0f, a_ + b_ * s_over_t);
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    return sample_cosine_reflection(*this, wo, u);
  }
  float density(const Vec3& wo, const Vec3& wi) const { return cosine_reflection_pdf(wo, wi); }
  bool samples_cosine_lobe() const override { return true; }
  // At roughness 0 eval is color · A wherever it is not 0.
  bool constant_cosine_lobe(RGB* f) const override {
    *f = color_ * a_;
    return b_ == 0.0f;
  }

  float a() const { return a_; }
  float b() const { return b_; }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  RGB color_;
  float a_ = kInvPi, b_ = 0.0f;
};

}  // namespace bxdf

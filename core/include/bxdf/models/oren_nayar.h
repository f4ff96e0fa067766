// Oren–Nayar rough diffuse reflection, the seed's (and pbrt's) qualitative form:
// f = R/π (A + B max(0, cos(φi − φo)) sin α tan β), α = max(θi, θo), β = min(θi, θo),
// with A, B from the slope deviation σ (given in degrees). σ = 0 is Lambertian.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/cosine_reflection.h"

namespace bxdf {

class OrenNayar final : public BxDFImpl<OrenNayar> {
 public:
  OrenNayar(const RGB& reflectance, float sigma_degrees)
      : BxDFImpl(kReflection | kDiffuse), r_over_pi_(reflectance * kInvPi) {
    const float sigma = radians(sigma_degrees);
    const float sigma2 = sigma * sigma;
    a_ = 1.0f - sigma2 / (2.0f * (sigma2 + 0.33f));
    b_ = 0.45f * sigma2 / (sigma2 + 0.09f);
  }

  // Written with a select instead of an early return, so that the batch loop vectorises.
  RGB eval(const Vec3& wo, const Vec3& wi) const {
    // With unit directions, cos(φi − φo) sin θi sin θo = wi.x wo.x + wi.y wo.y and
    // sin α sin β = sin θi sin θo, so max(0, cos(φi − φo)) sin α tan β reduces to
    // max(0, wi.x wo.x + wi.y wo.y) / cos β, where β, the angle closer to the normal, has the
    // larger |cos θ|. No square roots or divisions by sin θ: exact, finite at the pole (where
    // the term vanishes) and at grazing (cos β > 0 whenever both are in one hemisphere).
    const float cos_phi_sin_sin = std::max(0.0f, wi.x * wo.x + wi.y * wo.y);
    const float cos_beta = std::max(std::fabs(wi.z), std::fabs(wo.z));
    const float scale = a_ + b_ * cos_phi_sin_sin / cos_beta;  // NaN for 0/0: not selected
    const RGB v = r_over_pi_ * scale;
    const bool same = same_hemisphere(wo, wi);
    return {same ? v.r : 0.0f, same ? v.g : 0.0f, same ? v.b : 0.0f};
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    return sample_cosine_reflection(*this, wo, u);
  }
  float density(const Vec3& wo, const Vec3& wi) const { return cosine_reflection_pdf(wo, wi); }
  bool samples_cosine_lobe() const override { return true; }

  float a() const { return a_; }
  float b() const { return b_; }

 private:
  RGB r_over_pi_;
  float a_ = 1.0f, b_ = 0.0f;
};

}  // namespace bxdf

// Oren–Nayar rough diffuse reflection, the seed's (and pbrt's) qualitative form:
// f = R/π (A + B max(0, cos(φi − φo)) sin α tan β), α = max(θi, θo), β = min(θi, θo),
// with A, B from the slope deviation σ (given in degrees). σ = 0 is Lambertian.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/sampling.h"

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

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.0f);
    const float sin_theta_i = sin_theta(wi), sin_theta_o = sin_theta(wo);
    // cos(φi − φo) is undefined at the pole; the term vanishes there anyway (sin α tan β → 0).
    float max_cos = 0.0f;
    if (sin_theta_i > 1e-4f && sin_theta_o > 1e-4f) {
      const float d_cos = cos_phi(wi) * cos_phi(wo) + sin_phi(wi) * sin_phi(wo);
      max_cos = std::max(0.0f, d_cos);
    }
    // β is the angle closer to the normal: the one with the larger |cos θ|. Both |cos θ| are
    // positive here (same_hemisphere), so tan β stays finite even at grazing.
    float sin_alpha, tan_beta;
    if (abs_cos_theta(wi) > abs_cos_theta(wo)) {
      sin_alpha = sin_theta_o;
      tan_beta = sin_theta_i / abs_cos_theta(wi);
    } else {
      sin_alpha = sin_theta_i;
      tan_beta = sin_theta_o / abs_cos_theta(wo);
    }
    return r_over_pi_ * (a_ + b_ * max_cos * sin_alpha * tan_beta);
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    s.wi = sample_cosine_hemisphere(u);
    if (wo.z < 0.0f) s.wi.z = -s.wi.z;
    s.pdf = cosine_hemisphere_pdf(std::fabs(s.wi.z));
    s.f = eval(wo, s.wi);
    s.flags = kReflection | kDiffuse;
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(std::fabs(wi.z)) : 0.0f;
  }

  float a() const { return a_; }
  float b() const { return b_; }

 private:
  RGB r_over_pi_;
  float a_ = 1.0f, b_ = 0.0f;
};

}  // namespace bxdf

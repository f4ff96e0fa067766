// Lambertian transmission: f = T/π for wo and wi on opposite sides of the surface, the
// diffuse counterpart of Lambertian for thin translucent sheets. ρhd = ρhh = T exactly.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/sampling.h"

namespace bxdf {

class LambertianTransmission final : public BxDFImpl<LambertianTransmission> {
 public:
  explicit LambertianTransmission(const RGB& transmittance)
      : BxDFImpl(kTransmission | kDiffuse), t_(transmittance), t_over_pi_(transmittance * kInvPi) {}

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    return opposite_hemispheres(wo, wi) ? t_over_pi_ : RGB(0.0f);
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    s.wi = sample_cosine_hemisphere(u);
    if (wo.z > 0.0f) s.wi.z = -s.wi.z;  // the side opposite to wo
    s.pdf = cosine_hemisphere_pdf(std::fabs(s.wi.z));
    s.f = t_over_pi_;
    s.flags = kTransmission | kDiffuse;
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    return opposite_hemispheres(wo, wi) ? cosine_hemisphere_pdf(std::fabs(wi.z)) : 0.0f;
  }

  RGB rho_hd(const Vec3&, int, uint64_t) const override { return t_; }
  RGB rho_hh(int, uint64_t) const override { return t_; }
  // Cycles' Translucent BSDF folds its Color into the closure weight (closure_sample_weight).
  float closure_sample_weight() const override { return t_.average(); }
  const RGB& transmittance() const { return t_; }

 private:
  static bool opposite_hemispheres(const Vec3& a, const Vec3& b) { return a.z * b.z < 0.0f; }

  RGB t_, t_over_pi_;
};

}  // namespace bxdf

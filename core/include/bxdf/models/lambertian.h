// Lambertian reflection: f = R/π, the seed's ideal diffuse reflector. ρhd = ρhh = R exactly.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/cosine_reflection.h"

namespace bxdf {

class Lambertian final : public BxDFImpl<Lambertian> {
 public:
  explicit Lambertian(const RGB& reflectance)
      : BxDFImpl(kReflection | kDiffuse), r_(reflectance), r_over_pi_(reflectance * kInvPi) {}

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    return same_hemisphere(wo, wi) ? r_over_pi_ : RGB(0.0f);
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    return sample_cosine_reflection(*this, wo, u);
  }
  float density(const Vec3& wo, const Vec3& wi) const { return cosine_reflection_pdf(wo, wi); }
  bool samples_cosine_lobe() const override { return true; }
  bool constant_cosine_lobe(RGB* f) const override {
    *f = r_over_pi_;
    return true;
  }

  RGB rho_hd(const Vec3&, int, uint64_t) const override { return r_; }
  RGB rho_hh(int, uint64_t) const override { return r_; }
  const RGB& reflectance() const { return r_; }
  // Cycles' Diffuse BSDF folds its Color into the closure weight (BxDF::closure_sample_weight).
  float closure_sample_weight() const override { return r_.average(); }

 private:
  RGB r_, r_over_pi_;
};

}  // namespace bxdf

// Smooth glass (pbrt-v3 FresnelSpecular): one sample either reflects, with probability
// F(cos θo), or refracts, with probability 1 − F (radiance transport), so that f |cos θi| / pdf
// is R for a reflected sample and T (η_wo/η_wi)² for a refracted one. Total internal
// reflection has F = 1: it always reflects.
// As for every delta lobe in this library (DESIGN.md), the sample reports pdf 1; the choice
// probability is folded into f: pbrt's F R / |cos θi| with pdf F becomes R / |cos θi| with pdf 1.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/fresnel.h"
#include "bxdf/specular.h"

namespace bxdf {

class FresnelSpecular final : public BxDFImpl<FresnelSpecular> {
 public:
  FresnelSpecular(const RGB& reflectance, const RGB& transmittance, float eta_i, float eta_t)
      : BxDFImpl(kReflection | kTransmission | kSpecular),
        r_(reflectance),
        t_(transmittance),
        eta_i_(eta_i),
        eta_t_(eta_t) {}

  RGB eval(const Vec3&, const Vec3&) const { return RGB(0.0f); }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    if (abs_cos_theta(wo) < kMinSpecularCos) return s;  // grazing: 1/|cos θi| overflows
    // Signed cos θo: below the surface the light is inside the glass and the indices swap.
    const float fresnel = fresnel_dielectric(cos_theta(wo), eta_i_, eta_t_);
    if (u.x < fresnel) {
      s.wi = specular_reflect(wo);
      s.pdf = 1.0f;
      s.f = r_ / abs_cos_theta(s.wi);
      s.flags = kReflection | kSpecular;
      return s;
    }
    float radiance_scale = 1.0f;
    // F < 1 here, so refraction exists; the check only guards rounding at the critical angle.
    if (!specular_refract(wo, eta_i_, eta_t_, &s.wi, &radiance_scale)) return s;
    s.pdf = 1.0f;
    s.f = t_ * (radiance_scale / abs_cos_theta(s.wi));
    s.flags = kTransmission | kSpecular;
    return s;
  }
  float density(const Vec3&, const Vec3&) const { return 0.0f; }

 private:
  RGB r_, t_;
  float eta_i_, eta_t_;
};

}  // namespace bxdf

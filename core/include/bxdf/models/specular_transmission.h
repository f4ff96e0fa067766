// Perfect specular transmission through a smooth dielectric (pbrt-v3 SpecularTransmission,
// radiance transport): a delta lobe in the refracted direction with weight
// T (1 − F) (η_wo/η_wi)² / |cos θi|. wo above the surface (cos θo > 0) is outside (eta_i);
// below is inside (eta_t). The (η_wo/η_wi)² is because radiance itself changes across the
// interface (L/η² is what a refracted ray conserves; see specular_refract): light entering
// glass gets brighter per solid angle, light leaving it dimmer. Total internal reflection
// gives no sample: this lobe only transmits.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/fresnel.h"
#include "bxdf/specular.h"

namespace bxdf {

class SpecularTransmission final : public BxDFImpl<SpecularTransmission> {
 public:
  SpecularTransmission(const RGB& transmittance, float eta_i, float eta_t)
      : BxDFImpl(kTransmission | kSpecular), t_(transmittance), eta_i_(eta_i), eta_t_(eta_t) {}

  RGB eval(const Vec3&, const Vec3&) const { return RGB(0.0f); }
  BxDFSample sample(const Vec3& wo, Point2) const {
    BxDFSample s;
    float radiance_scale = 1.0f;
    if (!specular_refract(wo, eta_i_, eta_t_, &s.wi, &radiance_scale)) return s;
    // F is the same seen from either end of the refracted pair (Stokes). It is evaluated from
    // the side of lower index, whose cosine is exact; the other side's cosine comes from
    // sqrt(1 − sin²θ), which near the critical angle has lost digits (pbrt-v3 evaluates at
    // cos θi and is off by 3.5e-4 relative for a grazing wo entering glass from air).
    const bool wo_side_lower = (cos_theta(wo) > 0.0f ? eta_i_ : eta_t_) <=
                               (cos_theta(wo) > 0.0f ? eta_t_ : eta_i_);
    // 1 − F directly: near grazing F is close to 1 and 1 − F would cancel.
    const float transmitted = fresnel_dielectric_transmittance(
        wo_side_lower ? cos_theta(wo) : cos_theta(s.wi), eta_i_, eta_t_);
    s.pdf = 1.0f;
    s.f = t_ * (transmitted * radiance_scale / abs_cos_theta(s.wi));
    s.flags = kTransmission | kSpecular;
    return s;
  }
  float density(const Vec3&, const Vec3&) const { return 0.0f; }

 private:
  RGB t_;
  float eta_i_, eta_t_;
};

}  // namespace bxdf

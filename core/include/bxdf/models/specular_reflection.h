// Perfect specular reflection (the seed's SpecularReflection): a delta lobe in the mirror
// direction with weight F(cos θo) R / |cos θi|. f and pdf are 0 for any given pair of
// directions; only sample_f finds the lobe. The Fresnel term is none, dielectric or conductor
// (the seed's conductor formula).
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/fresnel.h"
#include "bxdf/specular.h"

namespace bxdf {

class SpecularReflection final : public BxDFImpl<SpecularReflection> {
 public:
  SpecularReflection(const RGB& reflectance, const Fresnel& fresnel)
      : BxDFImpl(kReflection | kSpecular), r_(reflectance), fresnel_(fresnel) {}

  RGB eval(const Vec3&, const Vec3&) const { return RGB(0.0f); }
  BxDFSample sample(const Vec3& wo, Point2) const {
    BxDFSample s;
    if (abs_cos_theta(wo) < kMinSpecularCos) return s;  // grazing: 1/|cos θi| overflows
    s.wi = specular_reflect(wo);
    s.pdf = 1.0f;
    // |cos θo|: reflection models are two-sided, so a dielectric coat reflects the same from
    // either side (the seed's signed cosine would swap the indices below the surface; glass
    // with an inside is fresnel_specular's job).
    s.f = fresnel_.evaluate(abs_cos_theta(wo)) * r_ / abs_cos_theta(s.wi);
    s.flags = kReflection | kSpecular;
    return s;
  }
  float density(const Vec3&, const Vec3&) const { return 0.0f; }

  const Fresnel& fresnel() const { return fresnel_; }

 private:
  RGB r_;
  Fresnel fresnel_;
};

}  // namespace bxdf

// Torrance–Sparrow microfacet reflection (the seed, pbrt's MicrofacetReflection):
// f = R · D(ωh) · G(ωo, ωi) · F(ωi·ωh) / (4 cos θi cos θo), ωh = normalize(ωo + ωi).
// A class template over the distribution (microfacet/*.h), so that D, Λ and the sampling
// inline into the kernels. Two-sided: a pair of directions below the surface is mirrored
// above it first, as the seed's BRDFs do with |cos θ|.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/fresnel.h"
#include "bxdf/microfacet/common.h"

namespace bxdf {

enum class MicrofacetShadowing {
  VGroove,  // the seed's min(1, 2(n·h)(n·ωo)/(ωo·h), 2(n·h)(n·ωi)/(ωo·h))
  Smith,    // height-correlated Smith, 1/(1 + Λ(ωo) + Λ(ωi)) (pbrt-v3)
};

template <class Distribution>
class TorranceSparrow final : public BxDFImpl<TorranceSparrow<Distribution>> {
 public:
  TorranceSparrow(const RGB& reflectance, const Distribution& distribution,
                  MicrofacetShadowing shadowing, const Fresnel& fresnel)
      : BxDFImpl<TorranceSparrow<Distribution>>(kReflection | kGlossy),
        r_(reflectance),
        distribution_(distribution),
        shadowing_(shadowing),
        fresnel_(fresnel) {}

  RGB eval(Vec3 wo, Vec3 wi) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.0f);
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    Vec3 wh = wo + wi;
    if (!normalize_direction(wh)) return RGB(0.0f);
    return f_upper(wo, wi, wh);
  }

  BxDFSample sample(Vec3 wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    const bool below = wo.z < 0.0f;
    if (below) wo.z = -wo.z;
    const Vec3 wh = distribution_.sample_wh(wo, u);
    const float wo_h = dot(wo, wh);
    if (!(wo_h > 0.0f)) return s;  // a facet that faces away from wo: no sample
    Vec3 wi = reflect(wo, wh);
    if (!(wi.z > 0.0f)) return s;  // reflected below the surface: no sample
    // f and pdf from the half vector of (wo, wi) as eval() and density() compute it, not the
    // sampled one: near grazing normalize(wo + wi) is ill-conditioned in float, and a sample
    // must report the same pdf as pdf(wo, wi) (pbrt-v3 does the same).
    s.pdf = density(wo, wi);
    s.f = eval(wo, wi);
    if (below) wi.z = -wi.z;
    s.wi = wi;
    s.flags = kReflection | kGlossy;
    return s;
  }

  float density(Vec3 wo, Vec3 wi) const {
    if (!same_hemisphere(wo, wi)) return 0.0f;
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    Vec3 wh = wo + wi;
    if (!normalize_direction(wh)) return 0.0f;
    const float wo_h = dot(wo, wh);
    if (!(wo_h > 0.0f)) return 0.0f;
    // The Jacobian of ωi = reflect(ωo, ωh) is 1/(4 ωo·ωh).
    return distribution_.pdf_wh(wo, wh) / (4.0f * wo_h);
  }

  float G(const Vec3& wo, const Vec3& wi, const Vec3& wh) const {
    if (shadowing_ == MicrofacetShadowing::VGroove) return microfacet::v_groove_G(wo, wi, wh);
    return microfacet::smith_G_correlated(distribution_.lambda(wo), distribution_.lambda(wi));
  }
  const Distribution& distribution() const { return distribution_; }

 private:
  // wo, wi above the surface, wh their unit half vector.
  RGB f_upper(const Vec3& wo, const Vec3& wi, const Vec3& wh) const {
    const float cos_o = wo.z, cos_i = wi.z;
    if (!(cos_o > 0.0f) || !(cos_i > 0.0f)) return RGB(0.0f);
    const float d = distribution_.D(wh);
    if (d == 0.0f) return RGB(0.0f);
    const RGB fr = fresnel_.evaluate(dot(wi, wh));
    return r_ * fr * (d * G(wo, wi, wh) / (4.0f * cos_i * cos_o));
  }

  RGB r_;
  Distribution distribution_;
  MicrofacetShadowing shadowing_;
  Fresnel fresnel_;
};

}  // namespace bxdf

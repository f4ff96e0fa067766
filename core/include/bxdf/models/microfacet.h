// Torrance–Sparrow microfacet reflection (the seed, pbrt's MicrofacetReflection), with an
// optional Lambertian term under the glossy lobe (pbrt's "plastic", Ngan et al. 2005's fits):
// f = Rd/π + R · D(ωh) · G(ωo, ωi) · F(ωi·ωh) / (4 cos θi cos θo), ωh = normalize(ωo + ωi).
// A class template over the distribution (microfacet/*.h), so that D, Λ and the sampling
// inline into the kernels. Two-sided: a pair of directions below the surface is mirrored
// above it first, as the seed's BRDFs do with |cos θ|.
#pragma once

#include <algorithm>

#include "bxdf/bxdf.h"
#include "bxdf/fresnel.h"
#include "bxdf/microfacet/common.h"
#include "bxdf/sampling.h"

namespace bxdf {

enum class MicrofacetShadowing {
  VGroove,  // the seed's min(1, 2(n·h)(n·ωo)/(ωo·h), 2(n·h)(n·ωi)/(ωo·h))
  Smith,    // height-correlated Smith, 1/(1 + Λ(ωo) + Λ(ωi)) (pbrt-v3)
};

template <class Distribution>
class TorranceSparrow final : public BxDFImpl<TorranceSparrow<Distribution>> {
 public:
  // diffuse: Rd of the Lambertian term; black means none (then the model is exactly the
  // plain Torrance–Sparrow lobe: no flag, no sampling probability spent on it).
  TorranceSparrow(const RGB& reflectance, const Distribution& distribution,
                  MicrofacetShadowing shadowing, const Fresnel& fresnel,
                  const RGB& diffuse = RGB(0.0f))
      : BxDFImpl<TorranceSparrow<Distribution>>(kReflection | kGlossy |
                                                (diffuse.is_black() ? 0u : uint32_t(kDiffuse))),
        r_(reflectance),
        distribution_(distribution),
        shadowing_(shadowing),
        fresnel_(fresnel),
        diffuse_over_pi_(diffuse * kInvPi),
        p_diffuse_(diffuse_probability(diffuse, reflectance, fresnel)) {}

  RGB eval(Vec3 wo, Vec3 wi) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.0f);
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    RGB f = specular_upper(wo, wi);
    if (p_diffuse_ > 0.0f) f += diffuse_over_pi_;
    return f;
  }

  // Picks the diffuse lobe with probability p_diffuse_ (u.x decides, then is stretched back to
  // [0, 1)), else the glossy lobe; f and pdf are those of the whole model, so a sample always
  // reports what f() and pdf() give for its direction.
  BxDFSample sample(Vec3 wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    const bool below = wo.z < 0.0f;
    if (below) wo.z = -wo.z;
    Vec3 wi;
    uint32_t lobe = kReflection | kGlossy;
    if (u.x < p_diffuse_) {
      u.x = std::min(u.x / p_diffuse_, kOneBelowOne);
      wi = sample_cosine_hemisphere(u);
      if (!(wi.z > 0.0f)) return s;
      lobe = kReflection | kDiffuse;
    } else {
      if (p_diffuse_ > 0.0f) u.x = std::min((u.x - p_diffuse_) / (1.0f - p_diffuse_), kOneBelowOne);
      const Vec3 wh = distribution_.sample_wh(wo, u);
      const float wo_h = dot(wo, wh);
      if (!(wo_h > 0.0f)) return s;  // a facet that faces away from wo: no sample
      wi = reflect(wo, wh);
      if (!(wi.z > 0.0f)) return s;  // reflected below the surface: no sample
    }
    // f and pdf from the half vector of (wo, wi) as eval() and density() compute it, not the
    // sampled one: near grazing normalize(wo + wi) is ill-conditioned in float, and a sample
    // must report the same pdf as pdf(wo, wi) (pbrt-v3 does the same).
    s.pdf = density(wo, wi);
    s.f = eval(wo, wi);
    if (below) wi.z = -wi.z;
    s.wi = wi;
    s.flags = lobe;
    return s;
  }

  float density(Vec3 wo, Vec3 wi) const {
    if (!same_hemisphere(wo, wi)) return 0.0f;
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    const float specular = specular_density(wo, wi);
    if (p_diffuse_ == 0.0f) return specular;
    return p_diffuse_ * cosine_hemisphere_pdf(wi.z) + (1.0f - p_diffuse_) * specular;
  }

  float G(const Vec3& wo, const Vec3& wi, const Vec3& wh) const {
    if (shadowing_ == MicrofacetShadowing::VGroove) return microfacet::v_groove_G(wo, wi, wh);
    return microfacet::smith_G_correlated(distribution_.lambda(wo), distribution_.lambda(wi));
  }
  const Distribution& distribution() const { return distribution_; }
  // The probability with which sample() picks the diffuse lobe (0 without one).
  float diffuse_probability() const { return p_diffuse_; }

 private:
  static constexpr float kOneBelowOne = 0x1.fffffep-1f;  // the largest float below 1

  // Luminance of Rd against an estimate of the glossy lobe's albedo, R · F(normal incidence)
  // (what the lobe reflects at most, about), clamped so neither lobe is starved.
  static float diffuse_probability(const RGB& diffuse, const RGB& r, const Fresnel& fresnel) {
    if (diffuse.is_black()) return 0.0f;
    const float d = diffuse.luminance();
    const float s = (r * fresnel.evaluate(1.0f)).luminance();
    return std::clamp(d / (d + s), 0.1f, 0.9f);
  }

  // The glossy lobe for wo, wi above the surface.
  RGB specular_upper(const Vec3& wo, const Vec3& wi) const {
    Vec3 wh = wo + wi;
    if (!normalize_direction(wh)) return RGB(0.0f);
    const float cos_o = wo.z, cos_i = wi.z;
    if (!(cos_o > 0.0f) || !(cos_i > 0.0f)) return RGB(0.0f);
    const float d = distribution_.D(wh);
    if (d == 0.0f) return RGB(0.0f);
    const RGB fr = fresnel_.evaluate(dot(wi, wh));
    return r_ * fr * (d * G(wo, wi, wh) / (4.0f * cos_i * cos_o));
  }
  float specular_density(const Vec3& wo, const Vec3& wi) const {
    Vec3 wh = wo + wi;
    if (!normalize_direction(wh)) return 0.0f;
    const float wo_h = dot(wo, wh);
    if (!(wo_h > 0.0f)) return 0.0f;
    // The Jacobian of ωi = reflect(ωo, ωh) is 1/(4 ωo·ωh).
    return distribution_.pdf_wh(wo, wh) / (4.0f * wo_h);
  }

  RGB r_;
  Distribution distribution_;
  MicrofacetShadowing shadowing_;
  Fresnel fresnel_;
  RGB diffuse_over_pi_;
  float p_diffuse_;
};

}  // namespace bxdf

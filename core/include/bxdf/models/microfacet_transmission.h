// Rough dielectric transmission (Walter et al. 2007; pbrt-v3's MicrofacetTransmission in
// radiance mode). With ωo on a side of index ηo and ωi on the other side of index ηi, the
// generalised half vector is ωh = normalize(ηo ωo + ηi ωi) turned to ωo's side, and
//   f = (1 − F(ωo·ωh)) · T · D(ωh) G(ωo, ωi) |ωi·ωh| |ωo·ωh| ηo²
//       / (|cos θi| |cos θo| (ηo ωo·ωh + ηi ωi·ωh)²),
// with G the height-correlated Smith term. This is Walter's radiance BTDF; pbrt-v3's
// importance (adjoint) form has ηi² in place of ηo². It obeys the generalised reciprocity
// f(ωo, ωi)/ηo² = f(ωi, ωo)/ηi². eta_i is the index above the surface (z > 0), eta_t below.
// Transmission only: the reflected part of rough glass is the `microfacet` model with a
// dielectric Fresnel term.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/fresnel.h"
#include "bxdf/microfacet/common.h"

namespace bxdf {

template <class Distribution>
class MicrofacetTransmission final : public BxDFImpl<MicrofacetTransmission<Distribution>> {
 public:
  MicrofacetTransmission(const RGB& transmittance, const Distribution& distribution, float eta_i,
                         float eta_t)
      : BxDFImpl<MicrofacetTransmission<Distribution>>(kTransmission | kGlossy),
        t_(transmittance),
        distribution_(distribution),
        eta_above_(eta_i),
        eta_below_(eta_t) {}

  RGB eval(const Vec3& wo_in, const Vec3& wi_in) const {
    const Side side = canonical(wo_in, wi_in);
    Vec3 wh;
    if (!half_vector(side, &wh)) return RGB(0.0f);
    return f_canonical(side, wh);
  }

  BxDFSample sample(const Vec3& wo_in, Point2 u) const {
    BxDFSample s;
    if (wo_in.z == 0.0f) return s;
    Side side = canonical(wo_in, Vec3(0.0f, 0.0f, -1.0f));
    const Vec3 wh = distribution_.sample_wh(side.wo, u);
    if (!(dot(side.wo, wh) > 0.0f)) return s;
    if (!refract(side.wo, wh, side.eta_o / side.eta_i, &side.wi)) return s;  // total reflection
    // f and pdf from the half vector of (wo, wi) as eval() and density() compute it, not the
    // sampled one, so that the sample reports exactly pdf(wo, wi) even where the generalised
    // half vector is ill-conditioned in float (near grazing).
    Vec3 h;
    if (!half_vector(side, &h)) return s;
    s.pdf = pdf_canonical(side, h);
    s.f = f_canonical(side, h);
    s.wi = side.mirrored ? Vec3(side.wi.x, side.wi.y, -side.wi.z) : side.wi;
    s.flags = kTransmission | kGlossy;
    return s;
  }

  float density(const Vec3& wo_in, const Vec3& wi_in) const {
    const Side side = canonical(wo_in, wi_in);
    Vec3 wh;
    if (!half_vector(side, &wh)) return 0.0f;
    return pdf_canonical(side, wh);
  }

  const Distribution& distribution() const { return distribution_; }

 private:
  // The pair mirrored so that wo is above the surface, with the indices of each side.
  struct Side {
    Vec3 wo, wi;
    float eta_o, eta_i;
    bool mirrored;
  };
  Side canonical(const Vec3& wo, const Vec3& wi) const {
    if (wo.z >= 0.0f) return {wo, wi, eta_above_, eta_below_, false};
    return {Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z), eta_below_, eta_above_, true};
  }

  // The generalised half vector, or false when (wo, wi) cannot be a refraction through a
  // facet that faces wo (same side, grazing, or a facet seen from behind).
  static bool half_vector(const Side& s, Vec3* wh) {
    if (!(s.wo.z > 0.0f) || !(s.wi.z < 0.0f)) return false;
    Vec3 h = s.wo * s.eta_o + s.wi * s.eta_i;
    if (!normalize_direction(h)) return false;
    if (h.z < 0.0f) h = -h;
    if (!(dot(s.wo, h) > 0.0f) || !(dot(s.wi, h) < 0.0f)) return false;
    *wh = h;
    return true;
  }

  RGB f_canonical(const Side& s, const Vec3& wh) const {
    const float d = distribution_.D(wh);
    if (d == 0.0f) return RGB(0.0f);
    const float wo_h = dot(s.wo, wh), wi_h = dot(s.wi, wh);
    const float denom = s.eta_o * wo_h + s.eta_i * wi_h;
    const float g =
        microfacet::smith_G_correlated(distribution_.lambda(s.wo), distribution_.lambda(s.wi));
    // F is the same seen from either side (Stokes); evaluating it from the side of lower
    // index avoids cos θt = sqrt(1 − sin²θt) near the critical angle, where float loses
    // digits, and keeps f(ωo, ωi) and f(ωi, ωo) computed alike.
    const float fr = s.eta_o <= s.eta_i ? fresnel_dielectric(wo_h, s.eta_o, s.eta_i)
                                        : fresnel_dielectric(-wi_h, s.eta_i, s.eta_o);
    const float v = (1.0f - fr) * d * g * std::fabs(wi_h * wo_h) * s.eta_o * s.eta_o /
                    (std::fabs(s.wi.z * s.wo.z) * denom * denom);
    return t_ * v;
  }

  // pdf_wh times the Jacobian dωh/dωi = ηi² |ωi·ωh| / (ηo ωo·ωh + ηi ωi·ωh)².
  float pdf_canonical(const Side& s, const Vec3& wh) const {
    const float wo_h = dot(s.wo, wh), wi_h = dot(s.wi, wh);
    const float denom = s.eta_o * wo_h + s.eta_i * wi_h;
    return distribution_.pdf_wh(s.wo, wh) * s.eta_i * s.eta_i * std::fabs(wi_h) / (denom * denom);
  }

  RGB t_;
  Distribution distribution_;
  float eta_above_, eta_below_;
};

}  // namespace bxdf

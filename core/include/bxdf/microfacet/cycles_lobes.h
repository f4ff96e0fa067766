// The microfacet lobes of Cycles 3.4's Glossy, Glass and Refraction closures
// (closure/bsdf_microfacet.h), as kernels on a pair already turned so that wo is above the
// surface (cos θo > 0). Neither carries a Fresnel term or a colour: the closures' weights do.
//
// Reflection (eval_reflect): f = D(ωh) G1(ωo) G1(ωi) / (4 cos θo cos θi), separable Smith G.
// Refraction (eval_transmit), with η the index on ωi's side over the index on ωo's side:
//   ht = −(ωo + η ωi), ωh = ht/|ht|,
//   f = |ωh·ωi| |ωh·ωo| η² D(ωh) G1(ωo) G1(ωi) / (cos θo |cos θi| |ht|²).
// Cycles checks only that ωo and ωi are on opposite sides: not that the facet ωh faces ωo
// and turns ωi away (Walter's condition), so f is not zero for pairs no refraction through a
// facet can join. Its η² (not pbrt's η_o²) makes the refraction carry no radiance scaling:
// f(ωi, ωo) = (η_ωo/η_ωi)² f(ωo, ωi), and ∫ f |cos θi| dωi ≤ 1 for light entering glass.
//
// Sampling: ωh from the distribution's sampler (visible normals for GGX), then a reflection
// or a refraction through ωh. The pdfs are those samplers' true densities; for refraction
// this is 0 on the pairs that Cycles' f accepts without a facet side check (Cycles reports its
// eval's pdf there, which its sampler never realises; cycles_glass.h covers them).
#pragma once

#include "bxdf/microfacet/common.h"

namespace bxdf {
namespace cycles {

// Cycles' singular threshold on αx·αy (bsdf_microfacet.h): at or below it a lobe is a delta.
constexpr float kSingularAlpha2 = 1e-7f;

// A direction pair turned so that wo is above the surface (Cycles turns its normal towards
// the viewer), with the relative index seen from wo's side: `ior` from above, 1/ior from below
// (Cycles' back-face IOR).
struct CanonicalPair {
  Vec3 wo, wi;
  float eta;
  bool mirrored;
};
inline CanonicalPair canonical_pair(const Vec3& wo, const Vec3& wi, float ior) {
  if (wo.z >= 0.0f) return {wo, wi, ior, false};
  return {Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z), 1.0f / ior, true};
}

template <class Distribution>
struct ReflectionLobe {
  Distribution distribution;

  float f(const Vec3& wo, const Vec3& wi) const {
    const float cos_o = wo.z, cos_i = wi.z;
    if (!(cos_o > 0.0f) || !(cos_i > 0.0f)) return 0.0f;
    Vec3 wh = wo + wi;
    if (!normalize_direction(wh)) return 0.0f;
    const float d = distribution.D(wh);
    if (d == 0.0f) return 0.0f;
    const float g = distribution.G1(wo) * distribution.G1(wi);  // separable, as Cycles 3.4
    return d * g / (4.0f * cos_o * cos_i);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
    Vec3 wh = wo + wi;
    if (!normalize_direction(wh)) return 0.0f;
    const float wo_h = dot(wo, wh);
    if (!(wo_h > 0.0f)) return 0.0f;
    return distribution.pdf_wh(wo, wh) / (4.0f * wo_h);
  }
  // False when the drawn facet does not reflect wo above the surface.
  bool sample(const Vec3& wo, Point2 u, Vec3* wi) const {
    const Vec3 wh = distribution.sample_wh(wo, u);
    if (!(dot(wo, wh) > 0.0f)) return false;
    *wi = reflect(wo, wh);
    return wi->z > 0.0f;
  }
};

template <class Distribution>
struct RefractionLobe {
  Distribution distribution;

  float f(const Vec3& wo, const Vec3& wi, float eta) const {
    const float cos_o = wo.z, cos_i = wi.z;
    if (!(cos_o > 0.0f) || !(cos_i < 0.0f)) return 0.0f;
    const Vec3 ht = -(wo + wi * eta);
    const float ht2 = dot(ht, ht);
    Vec3 wh = ht;
    if (!normalize_direction(wh)) return 0.0f;
    if (wh.z < 0.0f) wh = -wh;  // D and G are even in ωh; the sign of ht is not a side check
    const float d = distribution.D(wh);
    if (d == 0.0f) return 0.0f;
    const float g = distribution.G1(wo) * distribution.G1(wi);
    return std::fabs(dot(wh, wi) * dot(wh, wo)) * eta * eta * d * g /
           (cos_o * -cos_i * ht2);
  }
  // The density of sample(): D(ωh) pdf of the facet times |dωh/dωi| = η² |ωi·ωh| / |ht|²,
  // on the pairs a facet facing wo refracts into.
  float pdf(const Vec3& wo, const Vec3& wi, float eta) const {
    if (!(wo.z > 0.0f) || !(wi.z < 0.0f)) return 0.0f;
    const Vec3 ht = -(wo + wi * eta);
    Vec3 wh = ht;
    if (!normalize_direction(wh)) return 0.0f;
    if (wh.z < 0.0f) wh = -wh;
    const float wo_h = dot(wo, wh), wi_h = dot(wi, wh);
    if (!(wo_h > 0.0f) || !(wi_h < 0.0f)) return 0.0f;
    const float denom = wo_h + eta * wi_h;
    return distribution.pdf_wh(wo, wh) * eta * eta * -wi_h / (denom * denom);
  }
  // False when the facet faces away from wo or reflects it totally.
  bool sample(const Vec3& wo, Point2 u, float eta, Vec3* wi) const {
    const Vec3 wh = distribution.sample_wh(wo, u);
    if (!(dot(wo, wh) > 0.0f)) return false;
    return refract(wo, wh, 1.0f / eta, wi) && wi->z < 0.0f;
  }
};

}  // namespace cycles
}  // namespace bxdf

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

// The unit half vector of a reflection pair; false (f and pdf 0) unless both directions are
// above the surface and their sum can be normalised.
inline bool reflection_half_vector(const Vec3& wo, const Vec3& wi, Vec3* wh) {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return false;
  *wh = wo + wi;
  return normalize_direction(*wh);
}

template <class Distribution>
struct ReflectionLobe {
  Distribution distribution;

  float f(const Vec3& wo, const Vec3& wi) const {
    Vec3 wh;
    return reflection_half_vector(wo, wi, &wh) ? f_at(wo, wi, wh) : 0.0f;
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    Vec3 wh;
    return reflection_half_vector(wo, wi, &wh) ? pdf_at(wo, wh) : 0.0f;
  }
  // f and pdf at once, the same bits: one half vector, one D(ωh) (and for GGX one G1(ωo)),
  // which the compiler shares between the two inlined formulas.
  float f_pdf(const Vec3& wo, const Vec3& wi, float* pdf) const {
    Vec3 wh;
    if (!reflection_half_vector(wo, wi, &wh)) {
      *pdf = 0.0f;
      return 0.0f;
    }
    *pdf = pdf_at(wo, wh);
    return f_at(wo, wi, wh);
  }
  // False when the drawn facet does not reflect wo above the surface.
  bool sample(const Vec3& wo, Point2 u, Vec3* wi) const {
    const Vec3 wh = distribution.sample_wh(wo, u);
    if (!(dot(wo, wh) > 0.0f)) return false;
    *wi = reflect(wo, wh);
    return wi->z > 0.0f;
  }

 private:
  float f_at(const Vec3& wo, const Vec3& wi, const Vec3& wh) const {
    const float d = distribution.D(wh);
    if (d == 0.0f) return 0.0f;
    const float g = distribution.G1(wo) * distribution.G1(wi);  // separable, as Cycles 3.4
    return d * g / (4.0f * wo.z * wi.z);
  }
  float pdf_at(const Vec3& wo, const Vec3& wh) const {
    const float wo_h = dot(wo, wh);
    // Without a branch, so that D(ωh) here is computed on every path and f_at can reuse it.
    const float pdf = distribution.pdf_wh(wo, wh) / (4.0f * wo_h);
    return wo_h > 0.0f ? pdf : 0.0f;
  }
};

template <class Distribution>
struct RefractionLobe {
  Distribution distribution;

  float f(const Vec3& wo, const Vec3& wi, float eta) const {
    Vec3 wh;
    float ht2;
    return half_vector(wo, wi, eta, &wh, &ht2) ? f_at(wo, wi, eta, wh, ht2) : 0.0f;
  }
  // The density of sample(): D(ωh) pdf of the facet times |dωh/dωi| = η² |ωi·ωh| / |ht|²,
  // on the pairs a facet facing wo refracts into.
  float pdf(const Vec3& wo, const Vec3& wi, float eta) const {
    Vec3 wh;
    float ht2;
    return half_vector(wo, wi, eta, &wh, &ht2) ? pdf_at(wo, wi, eta, wh) : 0.0f;
  }
  // f and pdf at once, the same bits: one half vector and one D(ωh) (and for GGX one G1(ωo)).
  float f_pdf(const Vec3& wo, const Vec3& wi, float eta, float* pdf) const {
    Vec3 wh;
    float ht2;
    if (!half_vector(wo, wi, eta, &wh, &ht2)) {
      *pdf = 0.0f;
      return 0.0f;
    }
    *pdf = pdf_at(wo, wi, eta, wh);
    return f_at(wo, wi, eta, wh, ht2);
  }
  // False when the facet faces away from wo or reflects it totally.
  bool sample(const Vec3& wo, Point2 u, float eta, Vec3* wi) const {
    const Vec3 wh = distribution.sample_wh(wo, u);
    if (!(dot(wo, wh) > 0.0f)) return false;
    return refract(wo, wh, 1.0f / eta, wi) && wi->z < 0.0f;
  }

 private:
  // ωh (turned up: D and G are even in ωh, and the sign of ht is not a side check) and |ht|²
  // of a pair with wo above the surface and wi below it.
  static bool half_vector(const Vec3& wo, const Vec3& wi, float eta, Vec3* wh, float* ht2) {
    if (!(wo.z > 0.0f) || !(wi.z < 0.0f)) return false;
    const Vec3 ht = -(wo + wi * eta);
    *ht2 = dot(ht, ht);
    *wh = ht;
    if (!normalize_direction(*wh)) return false;
    if (wh->z < 0.0f) *wh = -*wh;
    return true;
  }
  float f_at(const Vec3& wo, const Vec3& wi, float eta, const Vec3& wh, float ht2) const {
    const float d = distribution.D(wh);
    if (d == 0.0f) return 0.0f;
    const float g = distribution.G1(wo) * distribution.G1(wi);
    return std::fabs(dot(wh, wi) * dot(wh, wo)) * eta * eta * d * g / (wo.z * -wi.z * ht2);
  }
  float pdf_at(const Vec3& wo, const Vec3& wi, float eta, const Vec3& wh) const {
    const float wo_h = dot(wo, wh), wi_h = dot(wi, wh);
    const float denom = wo_h + eta * wi_h;
    // Without a branch, so that D(ωh) here is computed on every path and f_at can reuse it.
    const float pdf = distribution.pdf_wh(wo, wh) * eta * eta * -wi_h / (denom * denom);
    return wo_h > 0.0f && wi_h < 0.0f ? pdf : 0.0f;
  }
};

}  // namespace cycles
}  // namespace bxdf

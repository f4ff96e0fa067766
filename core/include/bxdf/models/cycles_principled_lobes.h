// The closures that Cycles 3.4's Principled BSDF builds, each as Cycles' kernel evaluates it
// (closure/bsdf_principled_diffuse.h, bsdf_principled_sheen.h, bsdf_microfacet.h), for a wo in
// the upper hemisphere of the closure's normal (the model mirrors back faces there first).
// Each returns f without the cosine and, separately, the density of the way this library
// samples it; the model sums them with Cycles' closure weights.
#pragma once

#include <algorithm>
#include <cmath>

#include "bxdf/math.h"
#include "bxdf/microfacet/cycles_lobes.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/microfacet/multiscatter_ggx.h"
#include "bxdf/microfacet/refraction_cover.h"
#include "bxdf/sampling.h"
#include "bxdf/spectrum.h"

namespace bxdf {
namespace cycles {

// bsdf_util.h: (1 − u)^5 with 1 − u clamped to [0, 1].
inline float schlick_fresnel(float u) {
  const float m = clamp(1.0f - u, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

// Principled diffuse, FULL mode: Lambert with the Schlick entry/exit factors plus Burley's
// retro-reflection; eval = f cos θi with f = [(1 − FV/2)(1 − FL/2) + RR(FL + FV + FL FV (RR − 1))]/π.
inline float principled_diffuse_f(const Vec3& wo, const Vec3& wi, float roughness) {
  if (!(wi.z > 0.0f)) return 0.0f;
  const float fv = schlick_fresnel(wo.z), fl = schlick_fresnel(wi.z);
  const float rr = roughness * (dot(wi, wo) + 1.0f);  // 2 roughness (L·H)²
  const float f = (1.0f - 0.5f * fv) * (1.0f - 0.5f * fl) + rr * (fl + fv + fl * fv * (rr - 1.0f));
  return f * kInvPi;
}

// Principled sheen: eval = (1 − L·H)^5 cos θi, so f = (1 − L·H)^5 (no 1/π, as in Cycles).
inline float principled_sheen_f(const Vec3& wo, const Vec3& wi) {
  if (!(wi.z > 0.0f) || wo.z < 0.0f) return 0.0f;
  Vec3 h = wi + wo;
  if (!normalize_direction(h)) return 0.0f;
  return schlick_fresnel(dot(wi, h));
}
// Cycles scales the sheen's sample weight by this average of its eval (the half vector put on
// the normal): (1 − cos θo)^5 cos θo.
inline float principled_sheen_sample_factor(const Vec3& wo) {
  return wo.z < 0.0f ? 0.0f : schlick_fresnel(wo.z) * wo.z;
}

// GGX reflection with Cycles' interpolated Fresnel (MICROFACET_GGX_FRESNEL): separable Smith
// G1(wo)G1(wi), f = F(wi·m) D G / (4 cos θo cos θi), F = cspec0 + (1 − cspec0) FH.
struct GGXFresnelReflection {
  microfacet::GGX ggx;
  float eta = 1.5f;
  RGB cspec0{1.0f};

  RGB f(const Vec3& wo, const Vec3& wi) const {
    Vec3 m;
    if (!reflection_half_vector(wo, wi, &m)) return RGB(0.0f);
    const float d = ggx.D(m);
    const float g = ggx.G1(wo) * ggx.G1(wi);
    return microfacet::cycles_interpolate_fresnel(dot(wi, m), eta, cspec0) *
           (d * g / (4.0f * wo.z * wi.z));
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    Vec3 m;
    if (!reflection_half_vector(wo, wi, &m)) return 0.0f;
    const float wo_m = dot(wo, m);
    return wo_m > 0.0f ? ggx.pdf_wh(wo, m) / (4.0f * wo_m) : 0.0f;
  }
  bool sample(const Vec3& wo, Point2 u, Vec3* wi) const {
    const Vec3 m = ggx.sample_wh(wo, u);
    if (!(dot(wo, m) > 0.0f)) return false;
    *wi = reflect(wo, m);
    return wi->z > 0.0f;
  }
  // The closure's Fresnel colour at the normal, which scales its sample weight.
  RGB fresnel_at_normal(const Vec3& wo) const {
    return microfacet::cycles_interpolate_fresnel(wo.z, eta, cspec0);
  }
};

// Cycles' clearcoat (MICROFACET_GGX_CLEARCOAT): GTR1 D with α, G1 with a fixed α of 0.25, the
// interpolated Fresnel of η 1.5 with cspec0 0.04 (= the dielectric Fresnel), times 0.25
// (the model multiplies by the clearcoat amount). The exact sampler draws GTR1 itself
// (D cos θm); Cycles draws GGX's visible normals of the same α and reports a GTR1 density,
// G1(wo) D / (4 cos θo), which does not match what it drew (cycles_sample, cycles_pdf_excess).
struct GTR1Clearcoat {
  float alpha = 0.1f;

  static float d_gtr1(float cos_m, float alpha) {
    if (alpha >= 1.0f) return kInvPi;
    const float a2 = alpha * alpha;
    const float t = 1.0f + (a2 - 1.0f) * cos_m * cos_m;
    return (a2 - 1.0f) / (kPi * std::log(a2) * t);
  }
  static float g1_fixed(float cos_n) {
    constexpr float kAlpha2 = 0.0625f;
    return 2.0f / (1.0f + safe_sqrt(1.0f + kAlpha2 * (1.0f - cos_n * cos_n) / (cos_n * cos_n)));
  }
  // density() at half vector m, where D is d: D cos θm / (4 wo·m).
  static float density_at(const Vec3& wo, const Vec3& m, float d) {
    const float wo_m = dot(wo, m);
    return wo_m > 0.0f ? d * m.z / (4.0f * wo_m) : 0.0f;
  }
  float f(const Vec3& wo, const Vec3& wi) const {
    Vec3 m;
    if (!reflection_half_vector(wo, wi, &m)) return 0.0f;
    const float d = d_gtr1(m.z, alpha);
    const float g = g1_fixed(wo.z) * g1_fixed(wi.z);
    const float fresnel = microfacet::cycles_interpolate_fresnel(dot(wi, m), 1.5f, RGB(0.04f)).r;
    return 0.25f * fresnel * d * g / (4.0f * wo.z * wi.z);
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    Vec3 m;
    return reflection_half_vector(wo, wi, &m) ? density_at(wo, m, d_gtr1(m.z, alpha)) : 0.0f;
  }
  bool sample(const Vec3& wo, Point2 u, Vec3* wi) const {
    // Inverting the CDF of D cos θm: cos²θm = (1 − α^(2(1 − u)))/(1 − α²); α = 1 is cosine.
    const float a2 = alpha * alpha;
    const float cos2 = alpha >= 1.0f ? 1.0f - u.x
                                     : (1.0f - std::pow(a2, 1.0f - u.x)) / (1.0f - a2);
    const float cos_m = safe_sqrt(cos2), sin_m = safe_sqrt(1.0f - cos2);
    const float phi = 2.0f * kPi * u.y;
    const Vec3 m(sin_m * std::cos(phi), sin_m * std::sin(phi), cos_m);
    if (!(dot(wo, m) > 0.0f)) return false;
    *wi = reflect(wo, m);
    return wi->z > 0.0f;
  }
  // Cycles' draw (bsdf_microfacet_ggx_sample): a visible normal of GGX with this α.
  bool cycles_sample(const Vec3& wo, Point2 u, Vec3* wi) const {
    const Vec3 m = microfacet::GGX(alpha, alpha).sample_wh(wo, u);
    if (!(dot(wo, m) > 0.0f)) return false;
    *wi = reflect(wo, m);
    return wi->z > 0.0f;
  }
  // How much the pdf Cycles reports for it (in its sample and its eval alike: G1(wo), fixed
  // α² 0.0625, × D_GTR1 / (4 cos θo); not a density, its integral is not 1) exceeds density(),
  // from one half vector.
  float cycles_pdf_excess(const Vec3& wo, const Vec3& wi) const {
    Vec3 m;
    if (!reflection_half_vector(wo, wi, &m)) return 0.0f;
    const float d = d_gtr1(m.z, alpha);
    return g1_fixed(wo.z) * d / (4.0f * wo.z) - density_at(wo, m, d);
  }
  float fresnel_at_normal(const Vec3& wo) const {
    return 0.25f * microfacet::cycles_interpolate_fresnel(wo.z, 1.5f, RGB(0.04f)).r;
  }
};

// Cycles' GGX refraction (MICROFACET_GGX_REFRACTION), wo above, wi below, η = index below /
// index above: ht = −(η wi + wo), f |cos θi| = G1o G1i D η² |ht·wi ht·wo| / (cos θo |ht|²),
// with no check of which side the microfacet faces (pbrt-style code returns 0 there).
// Visible-normal sampling only produces facets that face wo, so it cannot reach the pairs whose
// half vector faces away, where this f is still > 0 (13% of the transmitted energy at θo 85°
// for α 0.16): a share of the samples, cover_share(), is drawn uniformly below the
// surface, so that the density covers every pair f does and a sampled estimate converges to
// ∫ f; the share that keeps its variance least depends on α, η and cos θo
// (microfacet/refraction_cover.h). That is the exact sampler; Cycles' own draws the facets
// alone, so the light of the uncovered pairs reaches its images only by light sampling, and
// the model's Cycles sample (CyclesPrincipled::sample) does the same.
struct GGXRefraction {
  microfacet::GGX ggx;
  float eta = 1.5f;

  float cover_share(float cos_o) const {
    return refraction_cover_share(CoverDistribution::kGGX, ggx.alpha_x, eta, cos_o);
  }
  float f(const Vec3& wo, const Vec3& wi) const {
    if (!(wo.z > 0.0f) || !(wi.z < 0.0f)) return 0.0f;
    const Vec3 ht = -(wi * eta + wo);
    const float ht2 = dot(ht, ht);
    if (!(ht2 > 0.0f)) return 0.0f;
    const Vec3 h = ht / std::sqrt(ht2);
    const float cos_ho = dot(h, wo), cos_hi = dot(h, wi);
    const Vec3 up = h.z < 0.0f ? -h : h;  // D depends on cos²θm only
    const float d = ggx.D(up);
    const float g = ggx.G1(wo) * ggx.G1(wi);
    return g * std::fabs(cos_hi * cos_ho) * d * eta * eta / (wo.z * ht2 * -wi.z);
  }
  // The density of the facet sampler alone (Cycles' own sampler): 0 on the pairs it never draws.
  float facet_density(const Vec3& wo, const Vec3& wi) const {
    if (!(wo.z > 0.0f) || !(wi.z < 0.0f)) return 0.0f;
    Vec3 h = wo + wi * eta;
    if (!normalize_direction(h)) return 0.0f;
    if (h.z < 0.0f) h = -h;
    const float wo_h = dot(wo, h), wi_h = dot(wi, h);
    if (!(wo_h > 0.0f) || !(wi_h < 0.0f)) return 0.0f;
    const float denom = wo_h + eta * wi_h;
    return ggx.pdf_wh(wo, h) * eta * eta * -wi_h / (denom * denom);
  }
  // The density of sample() with the cover: the facets' and the cover's, mixed by the share;
  // the facets' own density in *facet.
  float density(const Vec3& wo, const Vec3& wi, float* facet) const {
    *facet = 0.0f;
    if (!(wo.z > 0.0f) || !(wi.z < 0.0f)) return 0.0f;
    const float share = cover_share(wo.z);
    *facet = facet_density(wo, wi);
    return (1.0f - share) * *facet + share * refraction_cover_pdf(wi);
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    float facet;
    return density(wo, wi, &facet);
  }
  // With `cover`, a share of the samples is the cover's (density()); without, every sample
  // comes from the facets, as Cycles draws them (facet_density()).
  bool sample(const Vec3& wo, Point2 u, Vec3* wi, bool cover = true) const {
    if (cover) {
      const float share = cover_share(wo.z);
      if (u.x < share) {
        *wi = sample_refraction_cover(Point2(std::min(u.x / share, 0x1.fffffep-1f), u.y));
        return wi->z < 0.0f;
      }
      u.x = std::min((u.x - share) / (1.0f - share), 0x1.fffffep-1f);
    }
    const Vec3 m = ggx.sample_wh(wo, u);
    if (!(dot(wo, m) > 0.0f)) return false;
    if (!refract(wo, m, 1.0f / eta, wi)) return false;
    return wi->z < 0.0f;
  }
};

}  // namespace cycles
}  // namespace bxdf

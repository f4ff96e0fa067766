// cycles_principled's f for GGX (single scattering), written branch-free so that the batch
// loop vectorises: every closure is evaluated for every pair and a zero weight (a closure that
// is not built, or singular) or a select removes it. The same formulas as the closures of
// cycles_principled_lobes.h, sharing the half vector; CyclesPrincipled uses this kernel for
// scalar and batch f alike, so both give the same bits.
#pragma once

#include <cmath>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf {
namespace cycles {

// Max and min as value selects (std::max returns a reference, which GCC 12 leaves as a branch).
BXDF_KERNEL float max_of(float a, float b) { return a > b ? a : b; }
BXDF_KERNEL float min_of(float a, float b) { return a < b ? a : b; }

// Cycles' fresnel_dielectric_cos with selects.
BXDF_KERNEL float fresnel_dielectric_select(float cos_i, float eta) {
  const float c = std::fabs(cos_i);
  const float g2 = eta * eta - 1.0f + c * c;
  const float g = std::sqrt(max_of(g2, 0.0f));
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  const float f = 0.5f * a * a * (1.0f + b * b);
  return g2 > 0.0f ? f : 1.0f;
}

// interpolate_fresnel_color with F0 and 1/(1 − F0) precomputed.
struct InterpolatedFresnel {
  float eta = 1.5f, f0 = 0.04f, inv_one_minus_f0 = 1.0f / 0.96f;
  RGB cspec0{1.0f};
  InterpolatedFresnel() = default;
  InterpolatedFresnel(float eta_, const RGB& cspec0_) : eta(eta_), cspec0(cspec0_) {
    f0 = fresnel_dielectric_select(1.0f, eta);
    inv_one_minus_f0 = 1.0f / (1.0f - f0);
  }
  BXDF_KERNEL float factor(float cos_lh) const {
    return (fresnel_dielectric_select(cos_lh, eta) - f0) * inv_one_minus_f0;
  }
  BXDF_KERNEL RGB at(float cos_lh) const {
    const float fh = factor(cos_lh);
    return cspec0 * (1.0f - fh) + RGB(fh);
  }
};

// Smith G1 of GGX from α² tan² (Cycles' 2/(1 + sqrt(1 + α² tan²θ))).
BXDF_KERNEL float ggx_g1(float alpha2_tan2) {
  return 2.0f / (1.0f + std::sqrt(1.0f + alpha2_tan2));
}
BXDF_KERNEL float tan2_of(float cos_n) { return (1.0f - cos_n * cos_n) / (cos_n * cos_n); }

struct PrincipledEvalKernel {
  static constexpr float kCutoff = 1e-5f;
  // Diffuse and sheen: weights zero when not built.
  RGB diffuse_weight, sheen_weight;
  float roughness = 0.0f;
  // Specular: weight zero when not built or singular; α in the rotated tangent frame.
  float specular_weight = 0.0f, spec_ax = 0.1f, spec_ay = 0.1f, rot_cos = 1.0f, rot_sin = 0.0f;
  InterpolatedFresnel spec_fresnel;
  // Glass: final transmission (0 when absent), per side: index ratio and reflection Fresnel.
  float final_transmission = 0.0f;
  float eta_front = 1.45f, eta_back = 1.0f / 1.45f;
  InterpolatedFresnel glass_fresnel_front, glass_fresnel_back;
  float glass_reflection_on = 0.0f, glass_refraction_on = 0.0f;  // 1, or 0 when singular
  float refl_alpha = 0.1f, refr_alpha = 0.1f;
  RGB base;
  // Clearcoat: its amount (0 when absent or singular), GTR1 α and (α² − 1)/(π ln α²).
  float clearcoat = 0.0f, cc_alpha2 = 0.01f, cc_norm = 0.0f;
  InterpolatedFresnel cc_fresnel{1.5f, RGB(0.04f)};

  // Branch-free, for the batch loop.
  BXDF_KERNEL RGB eval(Vec3 wo, Vec3 wi) const { return eval_closures<false>(wo, wi); }
  // The same value for one pair, evaluating only the side wi is on and the closures that are
  // built: the renderer's scalar f.
  RGB eval_one(Vec3 wo, Vec3 wi) const { return eval_closures<true>(wo, wi); }

 private:
  // kSkip: leave out what the pair's side or an unbuilt closure makes zero (branches);
  // otherwise compute every term and select (vectorisable). Either way a closure of weight 0
  // adds exactly 0, even where its term is not finite (a near-zero cosine, or an IOR whose
  // normal-incidence Fresnel is 1), and the terms computed are the same expressions: both
  // give the same bits.
  template <bool kSkip>
  BXDF_KERNEL RGB eval_closures(Vec3 wo, Vec3 wi) const {
    // Back faces: mirror to the upper side, and the glass sees 1/ior.
    const bool back = wo.z < 0.0f;
    wo.z = back ? -wo.z : wo.z;
    wi.z = back ? -wi.z : wi.z;
    const float eta = back ? eta_back : eta_front;
    const float cos_o = wo.z, cos_i = wi.z;
    const bool reflected = cos_o > 0.0f && cos_i > 0.0f;
    const bool transmitted = cos_o > 0.0f && cos_i < 0.0f;
    if (kSkip && !reflected && !transmitted) return RGB(0.0f);

    const float tan2_o = tan2_of(cos_o), tan2_i = tan2_of(cos_i);
    // Glass: reflection weighted by F(cos θo), refraction by base · max(1e-4, 1 − F); each
    // dropped below the closure cut-off.
    const float fresnel = fresnel_dielectric_select(cos_o, eta);
    const RGB refr_w = base * (final_transmission * max_of(1e-4f, 1.0f - fresnel) *
                               glass_refraction_on);
    // Refraction (wi below): ht = −(η wi + wo), no check of the facet's side.
    const auto refraction = [&] {
      const Vec3 ht = -(wi * eta + wo);
      const float ht2 = max_of(dot(ht, ht), 1e-30f);
      const Vec3 m = ht * (1.0f / std::sqrt(ht2));
      const float a2 = refr_alpha * refr_alpha;
      const float c2 = m.z * m.z;
      const float t = a2 * c2 + (1.0f - c2);
      const float d = a2 / (kPi * t * t);
      const float g = ggx_g1(a2 * tan2_o) * ggx_g1(a2 * tan2_i);
      const float v = g * std::fabs(dot(m, wi) * dot(m, wo)) * d * eta * eta /
                      (cos_o * ht2 * -cos_i);
      const bool on = std::fabs(refr_w.average()) >= kCutoff;
      return refr_w * (on ? v : 0.0f);
    };
    if (kSkip && transmitted) return refraction();

    // Shared by the reflection closures: the half vector and G1 terms' tan².
    Vec3 h = wo + wi;
    const float h_len2 = max_of(dot(h, h), 1e-30f);
    h = h * (1.0f / std::sqrt(h_len2));
    const float inv_4cc = 1.0f / (4.0f * cos_o * cos_i);
    const float l_h = dot(wi, h);

    // Diffuse (Burley with retro-reflection) and sheen.
    RGB sum(0.0f);
    if (!kSkip || !diffuse_weight.is_black() || !sheen_weight.is_black()) {
      const float fv = schlick5(cos_o), fl = schlick5(cos_i);
      const float rr = roughness * (dot(wi, wo) + 1.0f);
      const float diffuse = ((1.0f - 0.5f * fv) * (1.0f - 0.5f * fl) +
                             rr * (fl + fv + fl * fv * (rr - 1.0f))) * kInvPi;
      const float sheen = schlick5(l_h);
      sum = diffuse_weight * diffuse + sheen_weight * sheen;
    }

    // Specular, anisotropic GGX in the rotated tangent frame.
    if (!kSkip || specular_weight != 0.0f) {
      const float hx = rot_cos * h.x + rot_sin * h.y, hy = -rot_sin * h.x + rot_cos * h.y;
      const float sx = hx / spec_ax, sy = hy / spec_ay;
      const float s = h.z * h.z + sx * sx + sy * sy;
      const float d = 1.0f / (kPi * spec_ax * spec_ay * s * s);
      const auto alpha2_tan2 = [&](const Vec3& w) {
        const float x = rot_cos * w.x + rot_sin * w.y, y = -rot_sin * w.x + rot_cos * w.y;
        return (spec_ax * spec_ax * x * x + spec_ay * spec_ay * y * y) / (w.z * w.z);
      };
      const float g = ggx_g1(alpha2_tan2(wo)) * ggx_g1(alpha2_tan2(wi));
      sum += kept(specular_weight != 0.0f, spec_fresnel.at(l_h) * (specular_weight * d * g * inv_4cc));
    }

    const float refl_w = final_transmission * fresnel * glass_reflection_on;
    const float w = refl_w >= kCutoff ? refl_w : 0.0f;
    if (!kSkip || w != 0.0f) {
      const float a2 = refl_alpha * refl_alpha;
      const float c2 = h.z * h.z;
      const float t = a2 * c2 + (1.0f - c2);
      const float d = a2 / (kPi * t * t);
      const float g = ggx_g1(a2 * tan2_o) * ggx_g1(a2 * tan2_i);
      // Per-field selects (a select of references would stop the loop vectorising).
      const float gf0 = back ? glass_fresnel_back.f0 : glass_fresnel_front.f0;
      const float ginv = back ? glass_fresnel_back.inv_one_minus_f0
                              : glass_fresnel_front.inv_one_minus_f0;
      const float fh = (fresnel_dielectric_select(l_h, eta) - gf0) * ginv;
      const RGB gf = glass_fresnel_front.cspec0 * (1.0f - fh) + RGB(fh);
      sum += kept(w != 0.0f, gf * (w * d * g * inv_4cc));
    }

    // Clearcoat: GTR1 D, G1 with α² 0.0625, Fresnel of η 1.5, × 0.25.
    if (!kSkip || clearcoat != 0.0f) {
      const float c2 = h.z * h.z;
      const float d = cc_norm / (1.0f + (cc_alpha2 - 1.0f) * c2);
      const float g = ggx_g1(0.0625f * tan2_o) * ggx_g1(0.0625f * tan2_i);
      const float fr = 0.04f + 0.96f * cc_fresnel.factor(l_h);
      sum += kept(clearcoat != 0.0f, RGB(clearcoat * 0.25f * fr * d * g * inv_4cc));
    }
    if (kSkip) return sum;  // reflected

    const RGB refracted = refraction();
    // Per-channel selects: a select of structs becomes a branch and stops vectorisation.
    return {pick(transmitted, refracted.r, reflected, sum.r),
            pick(transmitted, refracted.g, reflected, sum.g),
            pick(transmitted, refracted.b, reflected, sum.b)};
  }

  // `term` where `on`, else 0 (per-channel selects, which vectorise).
  BXDF_KERNEL static RGB kept(bool on, const RGB& term) {
    return {on ? term.r : 0.0f, on ? term.g : 0.0f, on ? term.b : 0.0f};
  }
  BXDF_KERNEL static float pick(bool transmitted, float t, bool reflected, float r) {
    const float rr = reflected ? r : 0.0f;
    return transmitted ? t : rr;
  }
  BXDF_KERNEL static float schlick5(float u) {
    const float m = min_of(max_of(1.0f - u, 0.0f), 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
  }
};

}  // namespace cycles
}  // namespace bxdf

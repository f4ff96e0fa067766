// Torrance–Sparrow microfacet reflection (the seed, pbrt's MicrofacetReflection), with an
// optional Lambertian term under the glossy lobe (pbrt's "plastic", Ngan et al. 2005's fits):
// f = Rd/π + R · D(ωh) · G(ωo, ωi) · F(ωi·ωh) / (4 cos θi cos θo), ωh = normalize(ωo + ωi).
// A class template over the distribution (microfacet/*.h), so that D, Λ and the sampling
// inline into the kernels. Two-sided: a pair of directions below the surface is mirrored
// above it first, as the seed's BRDFs do with |cos θ|.
#pragma once

#include <algorithm>
#include <limits>
#include <type_traits>

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

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    RGB f;
    with_eval_kernel([&](const auto& kernel) { f = kernel.eval(wo, wi); });
    return f;
  }

  // f specialised for this model's shadowing and Fresnel form: BxDFImpl picks it once per
  // batch, so the per-element loop has no branch on them (and the scalar eval uses the same
  // code, so both give the same bits).
  template <class Fn>
  void with_eval_kernel(Fn&& fn) const {
    using Form = Fresnel::Form;
    const auto pick_fresnel = [&](auto shadowing) {
      switch (fresnel_.form()) {
        case Form::None: return fn(EvalKernel<decltype(shadowing)::value, Form::None>{*this});
        case Form::Dielectric:
          return fn(EvalKernel<decltype(shadowing)::value, Form::Dielectric>{*this});
        case Form::ConductorSeed:
          return fn(EvalKernel<decltype(shadowing)::value, Form::ConductorSeed>{*this});
        case Form::ConductorExact:
          return fn(EvalKernel<decltype(shadowing)::value, Form::ConductorExact>{*this});
      }
    };
    if (shadowing_ == MicrofacetShadowing::VGroove)
      pick_fresnel(std::integral_constant<MicrofacetShadowing, MicrofacetShadowing::VGroove>());
    else
      pick_fresnel(std::integral_constant<MicrofacetShadowing, MicrofacetShadowing::Smith>());
  }

  // Picks the diffuse lobe with probability p_diffuse_ (u.x decides, then is stretched back to
  // [0, 1)), else the glossy lobe. Only the direction: sample() (and BxDFImpl's sample_f) take
  // f and pdf of the whole model from eval() and density(), so a sample always reports what
  // f() and pdf() give for its direction.
  DirectionSample sample_direction(Vec3 wo, Point2 u) const {
    DirectionSample s;
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
    if (below) wi.z = -wi.z;
    s.wi = wi;
    s.flags = lobe;
    s.ok = true;
    return s;
  }
  // f and pdf from the half vector of (wo, wi) as eval() and density() compute it, not the
  // sampled one: near grazing normalize(wo + wi) is ill-conditioned in float, and a sample
  // must report the same pdf as pdf(wo, wi) (pbrt-v3 does the same).
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    const DirectionSample d = sample_direction(wo, u);
    BxDFSample s;
    if (!d.ok) return s;
    s.wi = d.wi;
    s.f = eval(wo, d.wi);
    s.pdf = density(wo, d.wi);
    s.flags = d.flags;
    return s;
  }

  // Selects instead of early returns, so that the batch loop vectorises.
  BXDF_KERNEL float density(Vec3 wo, Vec3 wi) const {
    const bool same = same_hemisphere(wo, wi);
    const bool below = wo.z < 0.0f;
    wo.z = below ? -wo.z : wo.z;
    wi.z = below ? -wi.z : wi.z;
    const float specular = specular_density(wo, wi);
    const float mixed = p_diffuse_ * cosine_hemisphere_pdf(wi.z) + (1.0f - p_diffuse_) * specular;
    return !same ? 0.0f : (p_diffuse_ == 0.0f ? specular : mixed);
  }

  float G(const Vec3& wo, const Vec3& wi, const Vec3& wh) const {
    if (shadowing_ == MicrofacetShadowing::VGroove)
      return G_as<MicrofacetShadowing::VGroove>(wo, wi, wh);
    return G_as<MicrofacetShadowing::Smith>(wo, wi, wh);
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

  template <MicrofacetShadowing S>
  BXDF_KERNEL float G_as(const Vec3& wo, const Vec3& wi, const Vec3& wh) const {
    if constexpr (S == MicrofacetShadowing::VGroove) return microfacet::v_groove_G(wo, wi, wh);
    return microfacet::smith_G_correlated(distribution_.lambda(wo), distribution_.lambda(wi));
  }

  // f for one choice of shadowing and Fresnel form, branch-free. Two-sided: a pair below the
  // surface is mirrored above it.
  template <MicrofacetShadowing S, Fresnel::Form F>
  struct EvalKernel {
    const TorranceSparrow& m;
    BXDF_KERNEL RGB eval(Vec3 wo, Vec3 wi) const {
      const bool same = same_hemisphere(wo, wi);
      const bool below = wo.z < 0.0f;
      wo.z = below ? -wo.z : wo.z;
      wi.z = below ? -wi.z : wi.z;
      // The glossy lobe; diffuse_over_pi_ is black when there is no diffuse term.
      const RGB f = m.template specular_upper<S, F>(wo, wi) + m.diffuse_over_pi_;
      return {same ? f.r : 0.0f, same ? f.g : 0.0f, same ? f.b : 0.0f};
    }
  };

  // The glossy lobe for wo, wi above the surface; 0 where the half vector is degenerate, a
  // direction is at or below the horizon, or D vanishes.
  template <MicrofacetShadowing S, Fresnel::Form F>
  BXDF_KERNEL RGB specular_upper(const Vec3& wo, const Vec3& wi) const {
    const Vec3 h = wo + wi;
    const float l2 = length_squared(h);
    const Vec3 wh = half_vector(h, l2);
    const float cos_o = wo.z, cos_i = wi.z;
    const float d = distribution_.D(wh);
    const RGB fr = fresnel_.template evaluate_as<F>(dot(wi, wh));
    const RGB f = r_ * fr * (d * G_as<S>(wo, wi, wh) / (4.0f * cos_i * cos_o));
    // One condition per select (GCC 12 does not vectorise some && chains of mixed origin).
    const auto keep = [&](float v) {
      v = is_direction_length_squared(l2) ? v : 0.0f;
      v = cos_o > 0.0f ? v : 0.0f;
      v = cos_i > 0.0f ? v : 0.0f;
      return d != 0.0f ? v : 0.0f;
    };
    return {keep(f.r), keep(f.g), keep(f.b)};
  }
  BXDF_KERNEL float specular_density(const Vec3& wo, const Vec3& wi) const {
    const Vec3 h = wo + wi;
    const float l2 = length_squared(h);
    const Vec3 wh = half_vector(h, l2);
    const float wo_h = dot(wo, wh);
    // The Jacobian of ωi = reflect(ωo, ωh) is 1/(4 ωo·ωh).
    const float pdf = distribution_.pdf_wh(wo, wh) / (4.0f * wo_h);
    return is_direction_length_squared(l2) ? (wo_h > 0.0f ? pdf : 0.0f) : 0.0f;
  }
  // normalize(h = wo + wi) as normalize_direction() computes it, with a select instead of a
  // branch: +z where h is degenerate (is_direction_length_squared(l2) false).
  BXDF_KERNEL static Vec3 half_vector(const Vec3& h, float l2) {
    const bool ok = is_direction_length_squared(l2);
    const float inv = normalizing_scale(l2);
    return {ok ? h.x * inv : 0.0f, ok ? h.y * inv : 0.0f, ok ? h.z * inv : 1.0f};
  }

  RGB r_;
  Distribution distribution_;
  MicrofacetShadowing shadowing_;
  Fresnel fresnel_;
  RGB diffuse_over_pi_;
  float p_diffuse_;
};

}  // namespace bxdf

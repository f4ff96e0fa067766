// Cycles 3.4's multiscatter GGX closures as the Glossy and Glass nodes build them
// (MULTI_GGX and MULTI_GGX_GLASS: one closure, weight = colour, the walk's later bounces
// tinted by the same colour): a lobe of microfacet/multiscatter_ggx.h times the colour.
// f is a 16-walk estimate of Cycles' walk, deterministic in (wo, wi): relative RMS error 0.235
// (reflection, α 0.7) and 0.118 (glass, α 0.6) against the walk's expectation; the renderer
// salts the walks per sample so that its images converge to that expectation
// (multiscatter_ggx.h, Determinism).
//
// sample_f is Cycles' (bsdf_microfacet_multi_ggx[_glass]_sample): the sampling walk's exit
// direction, weight colour × the walk's throughput, and pdf Cycles' approximate pdf (density)
// for MIS, so f = weight·pdf/|cos θi| (sample_f_is_exact is false). Cycles' sampling and eval
// walks disagree (multiscatter_ggx.h, quirks): light found by BSDF sampling follows the walk,
// light found by light sampling the eval, as in Cycles. sample_f_exact samples density().
// cycles_refraction's lobe has no Cycles closure and no walk of its own: exact sampling.
#pragma once

#include <cmath>
#include <type_traits>

#include "bxdf/bxdf.h"
#include "bxdf/microfacet/multiscatter_ggx.h"

namespace bxdf {

template <class Lobe>
class CyclesMultiscatter final : public BxDFImpl<CyclesMultiscatter<Lobe>> {
 public:
  // setup.color is set to `color`; α as Cycles' setup clamps it ([1e-4, 1]).
  CyclesMultiscatter(uint32_t flags, const RGB& color, microfacet::MultiscatterSetup setup)
      : BxDFImpl<CyclesMultiscatter<Lobe>>(flags), color_(color), lobe_(with_color(setup, color)) {}

  RGB eval(const Vec3& wo, const Vec3& wi) const { return color_ * lobe_.eval(wo, wi); }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    if constexpr (kWalks) {
      const microfacet::WalkSample w = lobe_.sample_walk(wo, u);
      BxDFSample s;
      if (!w.ok) return s;
      s.wi = w.wi;
      s.pdf = lobe_.density(wo, w.wi);
      s.f = color_ * w.weight * (s.pdf / std::fabs(w.wi.z));
      s.flags = w.flags;
      return s;
    } else {
      return sample_exact(wo, u);
    }
  }
  BxDFSample sample_exact(const Vec3& wo, Point2 u) const {
    const DirectionSample d = lobe_.sample_direction(wo, u);
    BxDFSample s;
    if (!d.ok) return s;
    s.wi = d.wi;
    s.f = eval(wo, d.wi);
    s.pdf = lobe_.density(wo, d.wi);
    s.flags = d.flags;
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const { return lobe_.density(wo, wi); }
  bool sample_f_is_exact() const override { return !kWalks; }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  static microfacet::MultiscatterSetup with_color(microfacet::MultiscatterSetup s, const RGB& c) {
    s.color = c;
    return s;
  }
  // Lobes with a Cycles sampling walk (reflection, glass).
  static constexpr bool kWalks =
      !std::is_same_v<Lobe, microfacet::MultiscatterGGXRefraction>;
  RGB color_;
  Lobe lobe_;
};

// The Glossy node's (anisotropic) and the Glass node's (isotropic, eta = ior) forms, and
// cycles_refraction's multi_ggx: the glass walk's transmitted part (no Cycles node).
using CyclesMultiscatterGlossy = CyclesMultiscatter<microfacet::MultiscatterGGXReflection>;
using CyclesMultiscatterGlass = CyclesMultiscatter<microfacet::MultiscatterGGXGlass>;
using CyclesMultiscatterRefraction = CyclesMultiscatter<microfacet::MultiscatterGGXRefraction>;

}  // namespace bxdf

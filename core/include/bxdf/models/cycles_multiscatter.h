// Cycles 3.4's multiscatter GGX closures as the Glossy and Glass nodes build them
// (MULTI_GGX and MULTI_GGX_GLASS: one closure, weight = colour, the walk's later bounces
// tinted by the same colour): a lobe of microfacet/multiscatter_ggx.h times the colour.
// f is a 16-walk estimate of Cycles' walk, deterministic in (wo, wi): relative RMS error 0.235
// (reflection, α 0.7) and 0.118 (glass, α 0.6) against the walk's expectation; the renderer
// salts the walks per sample so that its images converge to that expectation
// (multiscatter_ggx.h, Determinism).
#pragma once

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
  DirectionSample sample_direction(const Vec3& wo, Point2 u) const {
    return lobe_.sample_direction(wo, u);
  }
  float density(const Vec3& wo, const Vec3& wi) const { return lobe_.density(wo, wi); }

 private:
  static microfacet::MultiscatterSetup with_color(microfacet::MultiscatterSetup s, const RGB& c) {
    s.color = c;
    return s;
  }
  RGB color_;
  Lobe lobe_;
};

// The Glossy node's (anisotropic) and the Glass node's (isotropic, eta = ior) forms, and
// cycles_refraction's multi_ggx: the glass walk's transmitted part (no Cycles node).
using CyclesMultiscatterGlossy = CyclesMultiscatter<microfacet::MultiscatterGGXReflection>;
using CyclesMultiscatterGlass = CyclesMultiscatter<microfacet::MultiscatterGGXGlass>;
using CyclesMultiscatterRefraction = CyclesMultiscatter<microfacet::MultiscatterGGXRefraction>;

}  // namespace bxdf

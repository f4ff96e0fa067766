// Cycles 3.4's Glossy / Anisotropic BSDF (GGX or Beckmann), so that a render can match Cycles
// exactly: F = 1 (colour is a plain factor), separable Smith G = G1(ωo) G1(ωi) (GGX's exact G1,
// Beckmann's rational fit), f = colour · D G / (4 cos θo cos θi).
// Cycles treats αx·αy <= 1e-7 as singular (its kernel returns 0 from eval and a mirror from
// sample; the node switches to Sharp already at roughness <= 1e-4); this model does the
// same: it becomes a delta mirror with weight = colour (f = colour/|cos θi|, pdf 1 when
// sampled; f = pdf = 0 otherwise), and its flags say specular.
// Two-sided like Cycles, which turns the shading normal towards the viewer.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/microfacet/cycles_lobes.h"

namespace bxdf {

// Cycles' singular threshold on αx·αy (bsdf_microfacet.h).
constexpr float kCyclesSingularAlpha2 = cycles::kSingularAlpha2;

template <class Distribution>
class CyclesGlossy final : public BxDFImpl<CyclesGlossy<Distribution>> {
 public:
  CyclesGlossy(const RGB& color, const Distribution& distribution, bool mirror)
      : BxDFImpl<CyclesGlossy<Distribution>>(kReflection | (mirror ? kSpecular : kGlossy)),
        color_(color),
        lobe_{distribution},
        mirror_(mirror) {}

  RGB eval(Vec3 wo, Vec3 wi) const {
    if (mirror_ || !same_hemisphere(wo, wi)) return RGB(0.0f);
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    return color_ * lobe_.f(wo, wi);
  }
  // eval and density at once (one half vector and D): the light sample's MIS and every BSDF
  // sample need both.
  RGB eval_density(Vec3 wo, Vec3 wi, float* pdf) const {
    *pdf = 0.0f;
    if (mirror_ || !same_hemisphere(wo, wi)) return RGB(0.0f);
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    return color_ * lobe_.f_pdf(wo, wi, pdf);
  }

  BxDFSample sample(Vec3 wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    const bool below = wo.z < 0.0f;
    if (below) wo.z = -wo.z;
    Vec3 wi;
    if (mirror_) {
      wi = Vec3(-wo.x, -wo.y, wo.z);
      s.pdf = 1.0f;
      s.f = color_ / wi.z;
      s.flags = kReflection | kSpecular;
    } else {
      if (!lobe_.sample(wo, u, &wi)) return s;
      // f and pdf from (wo, wi) exactly as eval() and density() compute them (see microfacet.h).
      s.f = eval_density(wo, wi, &s.pdf);
      s.flags = kReflection | kGlossy;
    }
    if (below) wi.z = -wi.z;
    s.wi = wi;
    return s;
  }

  float density(Vec3 wo, Vec3 wi) const {
    if (mirror_ || !same_hemisphere(wo, wi)) return 0.0f;
    if (wo.z < 0.0f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    return lobe_.pdf(wo, wi);
  }

  const Distribution& distribution() const { return lobe_.distribution; }
  bool is_mirror() const { return mirror_; }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  RGB color_;
  cycles::ReflectionLobe<Distribution> lobe_;
  bool mirror_;
};

}  // namespace bxdf

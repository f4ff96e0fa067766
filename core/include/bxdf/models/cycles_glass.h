// Cycles 3.4's Glass and Refraction BSDFs (svm/closure.h, closure/bsdf_microfacet.h,
// bsdf_reflection.h, bsdf_refraction.h), exactly as the nodes build them:
// - Glass: a reflection lobe weighted by the dielectric Fresnel F at N·V (Cycles'
//   fresnel_dielectric_cos) and a refraction lobe weighted by max(1e-4, 1 − F), a weight that
//   stays non-zero under total internal reflection; neither lobe has a Fresnel term inside.
// - Refraction: the refraction lobe alone, weight 1.
// Both times the node's colour, α = roughness² (isotropic). The lobes are those of
// microfacet/cycles_lobes.h (no facet side check in the rough refraction; a refraction that
// carries no radiance scaling). One sample picks a lobe in proportion to its weight, as Cycles
// picks a closure, so f = Σ wₖ fₖ and pdf = Σ (wₖ/Σw) pdfₖ.
// `ior` is the index below the surface (z < 0) over the index above; seen from below (wo.z <
// 0) the pair is turned over and the index inverted, as Cycles does on back faces.
// Cycles' f is not zero for transmitted pairs that no facet facing wo refracts into (it does
// not check sides), which visible-normal sampling never draws. So that the exact sampler
// (sample_f_exact) covers all of f, a share of its refraction samples is uniform on the
// transmitted side and the pdf is that mixture. Cycles' sampler draws the facets alone, so its
// images lose the light that only light sampling finds on those pairs (a finding of the
// comparison harness), and its indirect light through them: sample_f draws as Cycles does
// (sample_f_is_exact is false), its weight f·|cos θi| over the density of that draw. The
// exact sampler's share depends on α, η and cos θo (microfacet/refraction_cover.h): as small
// as 0.01 where the facets cover nearly all of f, up to 0.9 where they cover little of it.
// Cycles' singular cases become the delta form (CyclesSharpDielectric): the Sharp distribution,
// αx·αy <= 1e-7, and a refraction index within 1e-4 of 1 (Cycles then samples a delta
// pass-through; its eval stays a glossy lobe that its sampler never realises). A delta sample
// reports pdf 1 and folds the lobe choice into f, as every delta lobe here: the weight of
// either lobe is colour·(w_R + w_T).
#pragma once

#include <type_traits>

#include "bxdf/bxdf.h"
#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/cycles_lobes.h"
#include "bxdf/microfacet/multiscatter_ggx.h"  // cycles_fresnel_dielectric_cos
#include "bxdf/microfacet/refraction_cover.h"
#include "bxdf/sampling.h"
#include "bxdf/specular.h"

namespace bxdf {

// The Glass node's two closures, or the Refraction node's one.
enum class CyclesDielectricNode { kGlass, kRefraction };

// The closure weights (without the colour) for a wo above the surface with relative index eta.
struct CyclesDielectricWeights {
  float reflection, refraction;
  // The closures' sample weights as `pick` makes them (closure_pick.h).
  CyclesDielectricWeights sampling(ClosurePick pick) const {
    if (pick == ClosurePick::kByWeight) return *this;
    float w[2] = {reflection, refraction};
    raise_to_defensive_floor(w, 2);
    return {w[0], w[1]};
  }
  float reflection_probability() const { return reflection / (reflection + refraction); }
};
inline CyclesDielectricWeights cycles_dielectric_weights(CyclesDielectricNode node, float cos_o,
                                                         float eta) {
  if (node == CyclesDielectricNode::kRefraction) return {0.0f, 1.0f};
  const float fresnel = microfacet::cycles_fresnel_dielectric_cos(cos_o, eta);
  return {fresnel, std::max(1e-4f, 1.0f - fresnel)};
}

template <class Distribution>
class CyclesRoughDielectric final : public BxDFImpl<CyclesRoughDielectric<Distribution>> {
 public:
  CyclesRoughDielectric(CyclesDielectricNode node, const RGB& color,
                        const Distribution& distribution, float ior)
      : BxDFImpl<CyclesRoughDielectric<Distribution>>(
            kTransmission | kGlossy | (node == CyclesDielectricNode::kGlass ? kReflection : 0u)),
        node_(node),
        color_(color),
        reflection_{distribution},
        refraction_{distribution},
        ior_(ior) {}

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    const cycles::CanonicalPair c = cycles::canonical_pair(wo, wi, ior_);
    return lobe_f(c, cycles_dielectric_weights(node_, c.wo.z, c.eta));
  }
  // eval and density at once: the pair turned and its closure weights (a Fresnel) worked out
  // once, as the light sample's MIS and every BSDF sample need both.
  RGB eval_density(const Vec3& wo, const Vec3& wi, float* pdf,
                   ClosurePick pick = ClosurePick::kByWeight) const {
    const cycles::CanonicalPair c = cycles::canonical_pair(wo, wi, ior_);
    const CyclesDielectricWeights w = cycles_dielectric_weights(node_, c.wo.z, c.eta);
    float facet_refraction;
    return lobe_f_density(c, w, w.sampling(pick).reflection_probability(), pdf,
                          &facet_refraction);
  }

  // Cycles' sample: the refraction from its facets alone, so f·|cos θi|/pdf is f over the
  // density of what was drawn and pdf is density() (for MIS). sample_exact draws density().
  BxDFSample sample(const Vec3& wo, Point2 u, ClosurePick pick = ClosurePick::kByWeight) const {
    return sample_lobes(wo, u, false, pick);
  }
  BxDFSample sample_exact(const Vec3& wo, Point2 u) const {
    return sample_lobes(wo, u, true, ClosurePick::kByWeight);
  }
  bool sample_f_is_exact() const override { return false; }

  float density(const Vec3& wo, const Vec3& wi, ClosurePick pick = ClosurePick::kByWeight) const {
    const cycles::CanonicalPair c = cycles::canonical_pair(wo, wi, ior_);
    const float p_reflect =
        cycles_dielectric_weights(node_, c.wo.z, c.eta).sampling(pick).reflection_probability();
    float facet_refraction;
    return lobe_density(c, p_reflect, &facet_refraction);
  }

  // The share of refraction samples drawn as cover samples (see the file comment), for wo
  // above the surface with relative index eta.
  float cover_share(float cos_o, float eta) const {
    constexpr cycles::CoverDistribution kind = std::is_same_v<Distribution, microfacet::Beckmann>
                                                   ? cycles::CoverDistribution::kBeckmann
                                                   : cycles::CoverDistribution::kGGX;
    return cycles::refraction_cover_share(kind, refraction_.distribution.alpha_x, eta, cos_o);
  }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  // One lobe picked by its sample weight as `pick` makes it, the refraction with its cover
  // samples or without.
  BxDFSample sample_lobes(const Vec3& wo, Point2 u, bool cover_refraction,
                          ClosurePick pick) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    const cycles::CanonicalPair c = cycles::canonical_pair(wo, wo, ior_);
    const CyclesDielectricWeights w = cycles_dielectric_weights(node_, c.wo.z, c.eta);
    const float p_reflect = w.sampling(pick).reflection_probability();
    Vec3 wi;
    bool ok;
    if (u.x < p_reflect) {
      ok = reflection_.sample(c.wo, Point2(u.x / p_reflect, u.y), &wi);
      s.flags = kReflection | kGlossy;
    } else {
      const float v = std::min((u.x - p_reflect) / (1.0f - p_reflect), 0x1.fffffep-1f);
      const float cover = cover_refraction ? cover_share(c.wo.z, c.eta) : 0.0f;
      if (v < cover) {
        wi = cycles::sample_refraction_cover(Point2(v / cover, u.y));
        ok = wi.z < 0.0f;
      } else {
        const float v_facet = std::min((v - cover) / (1.0f - cover), 0x1.fffffep-1f);
        ok = refraction_.sample(c.wo, Point2(v_facet, u.y), c.eta, &wi);
      }
      s.flags = kTransmission | kGlossy;
    }
    s.wi = c.mirrored ? Vec3(wi.x, wi.y, -wi.z) : wi;
    // Grazing rough refraction is steep in float: return the bits f() will see.
    if (!ok || !snap_to_unit(s.wi)) return BxDFSample();
    // The snapped pair, turned as wo was: its closure weights and pick are those above.
    const cycles::CanonicalPair ci = cycles::canonical_pair(wo, s.wi, ior_);
    float drawn;
    s.f = lobe_f_density(ci, w, p_reflect, &s.pdf, &drawn);
    if (!cover_refraction && s.wi.z * wo.z < 0.0f) {
      // The refraction was drawn from the facets alone: f over the density of that draw.
      if (!(drawn > 0.0f)) return BxDFSample();
      s.f *= s.pdf / drawn;
    }
    return s;
  }

  // f of a turned pair whose closure weights are w.
  RGB lobe_f(const cycles::CanonicalPair& c, const CyclesDielectricWeights& w) const {
    const float f = c.wi.z > 0.0f ? w.reflection * reflection_.f(c.wo, c.wi)
                                  : w.refraction * refraction_.f(c.wo, c.wi, c.eta);
    return color_ * f;
  }
  // density() of a turned pair whose reflection is picked with p_reflect, and in
  // *facet_refraction the part of it the refraction's facets would give without the cover,
  // (1 − p_reflect) × their density (0 for a reflected pair).
  float lobe_density(const cycles::CanonicalPair& c, float p_reflect,
                     float* facet_refraction) const {
    *facet_refraction = 0.0f;
    if (c.wi.z > 0.0f) return p_reflect * reflection_.pdf(c.wo, c.wi);
    const float facet = refraction_.pdf(c.wo, c.wi, c.eta);
    *facet_refraction = (1.0f - p_reflect) * facet;
    return refraction_density(c, p_reflect, facet);
  }
  // lobe_f and lobe_density at once: each lobe's f and pdf share its half vector and D.
  RGB lobe_f_density(const cycles::CanonicalPair& c, const CyclesDielectricWeights& w,
                     float p_reflect, float* density, float* facet_refraction) const {
    *facet_refraction = 0.0f;
    float pdf;
    if (c.wi.z > 0.0f) {
      const float f = reflection_.f_pdf(c.wo, c.wi, &pdf);
      *density = p_reflect * pdf;
      return color_ * (w.reflection * f);
    }
    const float f = refraction_.f_pdf(c.wo, c.wi, c.eta, &pdf);
    *facet_refraction = (1.0f - p_reflect) * pdf;
    *density = refraction_density(c, p_reflect, pdf);
    return color_ * (w.refraction * f);
  }
  // A refracted pair's density, given its facets' density: the cover samples' and the
  // facets' mixture, times the chance of picking the refraction.
  float refraction_density(const cycles::CanonicalPair& c, float p_reflect, float facet) const {
    const float cover = cover_share(c.wo.z, c.eta);
    return (1.0f - p_reflect) * (cover * cycles::refraction_cover_pdf(c.wi) + (1.0f - cover) * facet);
  }

  CyclesDielectricNode node_;
  RGB color_;
  cycles::ReflectionLobe<Distribution> reflection_;
  cycles::RefractionLobe<Distribution> refraction_;
  float ior_;
};

class CyclesSharpDielectric final : public BxDFImpl<CyclesSharpDielectric> {
 public:
  CyclesSharpDielectric(CyclesDielectricNode node, const RGB& color, float ior)
      : BxDFImpl(kTransmission | kSpecular |
                 (node == CyclesDielectricNode::kGlass ? kReflection : 0u)),
        node_(node),
        color_(color),
        ior_(ior) {}

  RGB eval(const Vec3&, const Vec3&) const { return RGB(0.0f); }
  BxDFSample sample(const Vec3& wo, Point2 u, ClosurePick pick = ClosurePick::kByWeight) const {
    BxDFSample s;
    if (std::fabs(wo.z) < kMinSpecularCos) return s;
    const cycles::CanonicalPair c = cycles::canonical_pair(wo, wo, ior_);
    const CyclesDielectricWeights w = cycles_dielectric_weights(node_, c.wo.z, c.eta);
    const CyclesDielectricWeights sw = w.sampling(pick);
    // The picked closure's weight over the chance of picking it, as (sum of the sample
    // weights) x (weight / sample weight): the sum itself where the pick raised nothing.
    float weight_over_chance;
    Vec3 wi;
    if (u.x < sw.reflection_probability()) {
      wi = specular_reflect(c.wo);
      s.flags = kReflection | kSpecular;
      weight_over_chance = (sw.reflection + sw.refraction) * (w.reflection / sw.reflection);
    } else {
      weight_over_chance = (sw.reflection + sw.refraction) * (w.refraction / sw.refraction);
      // Cycles' refraction closure samples nothing under total internal reflection.
      if (!refract(c.wo, Vec3(0.0f, 0.0f, 1.0f), 1.0f / c.eta, &wi) ||
          !(wi.z < -kMinSpecularCos))
        return s;
      s.flags = kTransmission | kSpecular;
    }
    s.wi = c.mirrored ? Vec3(wi.x, wi.y, -wi.z) : wi;
    s.pdf = 1.0f;
    s.f = color_ * (weight_over_chance / std::fabs(wi.z));
    return s;
  }
  float density(const Vec3&, const Vec3&, ClosurePick = ClosurePick::kByWeight) const {
    return 0.0f;
  }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  CyclesDielectricNode node_;
  RGB color_;
  float ior_;
};

}  // namespace bxdf

namespace bxdf {

struct ModelInfo;  // bxdf/registry.h

// The node's inputs as the closures see them (svm/closure.h and the node's compile step):
// α = roughness², η = max(ior, 1e-5), and whether the closures are the delta form (the Sharp
// distribution, roughness <= 1e-4, αx·αy <= 1e-7, or |η − 1| < 1e-4).
struct CyclesDielectricInputs {
  float alpha;
  float ior;
  bool sharp;
};
CyclesDielectricInputs cycles_dielectric_inputs(const std::string& distribution, float roughness,
                                                float ior);

// The Glass and Refraction nodes' shared inputs after `color` and `distribution`: `roughness`
// and `ior`, declared once for both.
std::vector<ParamSpec> cycles_dielectric_surface_params();

// Builds the Glass or Refraction node's model from validated registry parameters (`color`,
// `distribution`, `roughness`, `ior`).
std::unique_ptr<BxDF> make_cycles_dielectric(CyclesDielectricNode node, const ParamSet& validated);
// Sets m.place and m.place_size for the Glass or Refraction node: the same builder as
// make_cycles_dielectric, from plain values (m.params must already be declared).
void set_cycles_dielectric_place(ModelInfo& m, CyclesDielectricNode node);

}  // namespace bxdf

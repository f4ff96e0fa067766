// Blender 3.4's Principled BSDF as Cycles builds it (svm/closure.h, the PRINCIPLED case): up to
// seven closures, each with Cycles' weight and cut-off, evaluated as Cycles' kernel does
// (cycles_principled_lobes.h, microfacet/multiscatter_ggx.h):
//   diffuse      base · (1 − metallic)(1 − transmission), Burley's diffuse with retro-reflection
//   sheen        sheen · lerp(1, base/luminance(base), sheen_tint) · diffuse weight
//   specular     1 − final transmission, GGX with Cycles' interpolated Fresnel towards
//                cspec0 = lerp(0.08 specular lerp(1, base/(0.3r + 0.6g + 0.1b), specular_tint),
//                base, metallic) at the IOR 2/(1 − √(0.08 specular)) − 1; α = (r²/a, r² a),
//                a = √(1 − 0.9 anisotropic), the tangent rotated by 2π anisotropic_rotation;
//                multiple-scattering GGX when distribution = multi_ggx and roughness > 0.075
//   glass        final transmission = transmission (1 − metallic): GGX reflection weighted by
//                the Fresnel F(cos θo) (cspec0 = lerp(1, base, specular_tint)) and GGX
//                refraction weighted base · max(1e-4, 1 − F) with roughness
//                1 − (1 − r)(1 − transmission_roughness); with multi_ggx and roughness > 0.05
//                one multiple-scattering glass closure instead (transmission roughness unused)
//   clearcoat    0.25 clearcoat (not scaled by metallic), GTR1 with α = clearcoat_roughness²
//                and a fixed masking α of 0.25, Fresnel of η 1.5
// Closures whose average weight is below 1e-5 are not built (Cycles' CLOSURE_WEIGHT_CUTOFF),
// as are the diffuse when average(base) ≤ 1e-5, the sheen when sheen ≤ 1e-5 and the specular
// when specular and metallic are both ≤ 1e-5. A GGX closure with αx αy ≤ 1e-7 is Cycles'
// singular case: a delta lobe (mirror, or straight refraction; also when |η − 1| < 1e-4), whose
// sample reports pdf 1 and weight/(choice probability · |cos θi|) as f, flagged specular.
//
// Subsurface: this library has no subsurface scattering, so the model applies Cycles' own
// rule for paths that already bounced off a diffuse surface (PATH_RAY_DIFFUSE_ANCESTOR):
// the base colour becomes lerp(base_color, subsurface_color, subsurface) everywhere and the
// diffuse closure replaces the BSSRDF. A camera-ray view of a subsurface material therefore
// differs from Cycles' (its pairing is labelled approximate when subsurface > 0).
//
// Back faces (wo below the surface): reflection is mirrored to the upper side, as Cycles
// turns the normal towards the viewer, and the glass sees 1/ior. The IOR is max(ior, 1e-5).
//
// Sampling picks a closure in proportion to Cycles' sample weights (|average(weight)|, times
// the Fresnel colour at the normal for the Fresnel closures and the sheen's average) and
// samples it; pdf is the mixture's density, so sample_f, f and pdf agree, except where Cycles'
// sampler differs from the exact one (sample_f_is_exact is then false; sample_exact samples
// the mixture's density): a multiscatter closure is sampled with its walk, a rough
// refraction draws no cover samples, and the clearcoat is drawn from GGX's visible normals
// (cycles_principled_lobes.h), so f·|cos θi|/pdf is Cycles' weight: eval over Cycles' mixture
// pdf (the density of what was drawn, with the clearcoat's reported pdf in it, as Cycles'
// bias has it), and pdf stays the mixture's density.
// Not reciprocal when there is transmission: the glass weights depend on F(cos θo).
#pragma once

#include <utility>

#include "bxdf/bxdf.h"
#include "bxdf/microfacet/multiscatter_ggx.h"
#include "bxdf/models/cycles_principled_kernel.h"
#include "bxdf/models/cycles_principled_lobes.h"
#include "bxdf/params.h"

namespace bxdf {

// The node's inputs, plain values (the registry's parameters, in Blender's ranges).
struct CyclesPrincipledInputs {
  RGB base_color{0.8f};
  float subsurface = 0.0f;
  RGB subsurface_color{0.8f};
  float metallic = 0.0f;
  float specular = 0.5f;
  float specular_tint = 0.0f;
  float roughness = 0.5f;
  float anisotropic = 0.0f;
  float anisotropic_rotation = 0.0f;
  float sheen = 0.0f;
  float sheen_tint = 0.5f;
  float clearcoat = 0.0f;
  float clearcoat_roughness = 0.03f;
  float ior = 1.45f;
  float transmission = 0.0f;
  float transmission_roughness = 0.0f;
  bool multiscatter = false;  // distribution = multi_ggx
};

// Maps validated registry parameters (make("cycles_principled", ...)) to the inputs.
CyclesPrincipledInputs cycles_principled_inputs(const ParamSet& validated);
// The same mapping from one plain value per declared parameter (ModelInfo::place): `params`
// is the model's declaration; no allocation.
struct PlainValue;  // bxdf/registry.h
CyclesPrincipledInputs cycles_principled_inputs(const std::vector<ParamSpec>& params,
                                                const PlainValue* values);

class CyclesPrincipled final : public BxDFImpl<CyclesPrincipled> {
 public:
  explicit CyclesPrincipled(const CyclesPrincipledInputs& inputs)
      : CyclesPrincipled(make_state(inputs)) {}

  RGB eval(Vec3 wo, Vec3 wi) const {
    return s_.single_scatter ? s_.kernel.eval_one(wo, wi) : eval_general(wo, wi);
  }
  // The batch loop runs the branch-free kernel when no closure scatters multiply.
  template <class Fn>
  void with_eval_kernel(Fn&& fn) const {
    if (s_.single_scatter)
      fn(s_.kernel);
    else
      fn(*this);
  }
  // Cycles' sample: a multiscatter closure is sampled with its walk (cycles_multiscatter.h),
  // a rough refraction from its facets alone, the clearcoat from GGX's visible normals with
  // Cycles' weight; sample_exact samples density() for exact importance sampling of f.
  BxDFSample sample(Vec3 wo, Point2 u, ClosurePick pick = ClosurePick::kByWeight) const {
    return sample_closures(wo, u, true, pick);
  }
  BxDFSample sample_exact(Vec3 wo, Point2 u) const {
    return sample_closures(wo, u, false, ClosurePick::kByWeight);
  }
  bool sample_f_is_exact() const override {
    return !(s_.specular_multi || s_.glass_multi || has_rough_refraction() ||
             (s_.has_clearcoat && !s_.clearcoat_singular));
  }
  float density(Vec3 wo, Vec3 wi, ClosurePick pick = ClosurePick::kByWeight) const;
  // eval and density with the closures built once (BxDF::f_pdf).
  RGB eval_density(Vec3 wo, Vec3 wi, float* density_out,
                   ClosurePick pick = ClosurePick::kByWeight) const;

  // The diffuse and sheen lobes (Cycles' PRINCIPLED_DIFFUSE and PRINCIPLED_SHEEN closures).
  bool has_diffuse_closure_lobes() const override { return s_.has_diffuse || s_.has_sheen; }
  RGB diffuse_closure_f(const Vec3& wo, const Vec3& wi) const override;

  enum Closure {
    kDiffuseClosure,
    kSheenClosure,
    kSpecularClosure,
    kGlassReflectionClosure,
    kGlassRefractionClosure,
    kClearcoatClosure,
    kClosureCount
  };
  // The closures built for this wo (in the upper hemisphere): weight and sample weight each,
  // zero for the ones not built; the sample weights as `pick` makes them.
  struct Closures {
    RGB weight[kClosureCount];
    float sample_weight[kClosureCount] = {};
    float sample_total = 0.0f;
    float eta = 1.0f;  // the glass's index ratio on this side
  };
  Closures closures(const Vec3& wo_upper, bool back_face,
                    ClosurePick pick = ClosurePick::kByWeight) const;

 private:
  RGB eval_general(Vec3 wo, Vec3 wi) const;  // any distribution, closure by closure
  // For wo in the upper hemisphere; back_face says which side it really is on.
  // `skip`: a closure left out of the sum (the one a walk sampled), or -1.
  RGB eval_upper(const Vec3& wo, const Vec3& wi, const Closures& c, bool back_face,
                 int skip = -1) const;
  BxDFSample sample_closures(Vec3 wo, Point2 u, bool as_cycles, ClosurePick pick) const;
  // A rough glass refraction closure is built, whose Cycles sample draws no cover samples.
  bool has_rough_refraction() const {
    return s_.has_glass && !s_.glass_multi && !s_.glass_refraction_singular;
  }
  // Closure k is a multiscatter closure, which Cycles samples with its walk.
  bool walks(int k) const {
    return (k == kSpecularClosure && s_.specular_multi) ||
           (k == kGlassReflectionClosure && s_.glass_multi);
  }
  // The closures' mixture density; with `refraction_excess`, also what the refraction lobe's
  // cover adds to its own density there (0 without a refraction), from the same evaluation.
  float density_upper(const Vec3& wo, const Vec3& wi, const Closures& c, bool back_face,
                      float* refraction_excess = nullptr) const;
  // Lobe values of closure k without the closure weight.
  RGB lobe_f(int k, const Vec3& wo, const Vec3& wi, float eta, bool back_face) const;
  float lobe_density(int k, const Vec3& wo, const Vec3& wi, float eta, bool back_face) const;
  // The glass's refraction lobe for the index ratio of wo's side.
  cycles::GGXRefraction refraction_lobe(float eta) const {
    cycles::GGXRefraction lobe = s_.glass_refraction;
    lobe.eta = eta;
    return lobe;
  }
  // `as_cycles`: Cycles' draw (the rough refraction without its cover samples, the clearcoat
  // from GGX's visible normals), else the exact one.
  bool lobe_sample(int k, const Vec3& wo, Point2 u, float eta, bool back_face, bool as_cycles,
                   Vec3* wi) const;
  Vec3 to_tangent(const Vec3& w) const;    // into the rotated tangent frame
  Vec3 from_tangent(const Vec3& w) const;

  // Everything the inputs decide, computed once (make_state).
  struct State {
    uint32_t flags = kReflection;
    RGB base;
    float roughness = 0.0f;
    float diffuse_weight = 0.0f, final_transmission = 0.0f, specular_weight = 0.0f;
    bool has_diffuse = false, has_sheen = false, has_specular = false, has_glass = false,
         has_clearcoat = false;
    RGB sheen_color;
    float sheen = 0.0f;
    float clearcoat = 0.0f;
    float ior = 1.0f;
    float rot_cos = 1.0f, rot_sin = 0.0f;  // the tangent's rotation
    bool specular_multi = false, glass_multi = false;
    bool specular_singular = false, glass_reflection_singular = false,
         glass_refraction_singular = false, clearcoat_singular = false;
    cycles::GGXFresnelReflection specular;
    microfacet::MultiscatterGGXReflection specular_ms{microfacet::MultiscatterSetup{}};
    cycles::GGXFresnelReflection glass_reflection;  // eta set per side
    cycles::GGXRefraction glass_refraction;         // eta set per side
    microfacet::MultiscatterGGXGlass glass_ms{microfacet::MultiscatterSetup{}};
    microfacet::MultiscatterGGXGlass glass_ms_back{microfacet::MultiscatterSetup{}};
    cycles::GTR1Clearcoat clearcoat_lobe;
    bool single_scatter = true;          // no multiple-scattering closure: f is `kernel`
    cycles::PrincipledEvalKernel kernel;
    bool singular(int k) const;  // closure k is Cycles' singular (delta) case
  };
  static State make_state(const CyclesPrincipledInputs& inputs);
  explicit CyclesPrincipled(State state)
      : BxDFImpl<CyclesPrincipled>(state.flags), s_(std::move(state)) {}

  State s_;
};

}  // namespace bxdf

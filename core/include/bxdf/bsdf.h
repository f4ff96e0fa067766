// The BSDF at one surface point (seed ch. 10, pbrt-v3's BSDF): a weighted sum of BxDFs, each
// in a shading frame (the point's, or its own when a material perturbs that closure's normal).
// It moves directions between world space and the local frames, uses the geometric normal to
// decide whether a pair of directions is a reflection or a transmission (so that shading
// normals cannot leak light through a surface), and picks one component to sample in
// proportion to its sample weight, the average of its RGB weight times the colour Cycles folds
// into a closure's weight (BxDF::closure_sample_weight): Cycles' sample_weight. At a path's
// first surface Cycles raises each closure's sample weight to at least an eighth of their sum
// before picking (closure_pick.h): use_defensive_sampling().
//
// A BSDF is built per hit, on the stack: it holds non-owning pointers to BxDFs that the scene
// owns (as shared BxDFPtrs) and never allocates.
#pragma once

#include <cstdint>

#include "bxdf/bxdf.h"
#include "bxdf/frame.h"
#include "bxdf/uninitialised.h"

namespace bxdf {

// What BSDF::sample_f returns; directions in world space.
struct BSDFSample {
  RGB f;
  RGB f_cos;  // f times |cos θi| about each component's own normal (the estimator's factor)
  Vec3 wi;
  float pdf = 0.0f;
  uint32_t flags = 0;  // the sampled lobe's flags (kSpecular set for a delta lobe)
  int component = -1;  // index of the sampled component (the integrator tells transparency by it)
  bool valid() const { return pdf > 0.0f; }
  bool is_delta() const { return (flags & kSpecular) != 0; }
};

class BSDF {
 public:
  static constexpr int kMaxComponents = 8;

  BSDF() = default;
  // `shading` is the shading frame (its n the shading normal), `geometric_normal` the
  // triangle's true normal; both world space, unit length.
  BSDF(const Frame& shading, const Vec3& geometric_normal)
      : frame_(shading), ng_(geometric_normal) {}

  // Adds weight · component, in `frame` (world space; null: the BSDF's shading frame). Throws
  // ParameterError past kMaxComponents, for a null pointer or a negative/non-finite weight.
  // `bump_shadowed`: the component is one of Cycles' diffuse closures, which Cycles darkens at
  // grazing light by bump_shadowing_term when its normal differs from the shading normal.
  // A component with such lobes inside (BxDF::has_diffuse_closure_lobes: the Principled
  // BSDF's diffuse and sheen) has just those lobes darkened so, whatever `bump_shadowed` says.
  void add(const BxDF* component, const RGB& weight = RGB(1.0f), const Frame* frame = nullptr,
           bool bump_shadowed = false);

  int num_components() const { return count_; }
  // Components whose every flag is in `mask` (BxDF::matches).
  int num_components(uint32_t mask) const;
  // True when some component is not a delta lobe, i.e. light sampling can find it.
  bool has_non_delta() const;
  // True when some component transmits.
  bool has_transmission() const;
  const BxDF* component(int i) const { return components_[i]; }
  const RGB& weight(int i) const { return weights_[i]; }

  // The true geometric normal (unit, on the viewer's side) of an opaque smooth-shaded surface:
  // its cosine-lobe components (BxDF::samples_cosine_lobe) then sample only directions above
  // the triangle's plane, where a reflection can leave it, and report that density as their
  // pdf (cosine_above_plane.h). Without it (or where the plane is the shading frame's)
  // they sample their whole lobe, part of which may be lost below the plane.
  void set_sampling_horizon(const Vec3& true_geometric_normal);

  // Cycles' defensive sampling (closure_pick.h), for the BSDF of a path's first surface, once
  // every component is added: each component's sample weight is raised to at least an eighth
  // of their sum; a BSDF of one component (a Principled BSDF, a Glass) has its closures inside
  // picked so instead (BxDF::sample_f_defensive). Sampling and pdfs use the raised weights.
  // Inside a mixture of several components a component's own closures are picked by their
  // weights (Cycles raises every closure of the material against the whole sum).
  void use_defensive_sampling();

  const Frame& frame() const { return frame_; }
  const Vec3& geometric_normal() const { return ng_; }
  // set_sampling_horizon's normal, where it clips the cosine lobes (else false).
  bool sampling_horizon(Vec3* normal) const {
    *normal = horizon_;
    return has_horizon_;
  }
  // True when component i is in the BSDF's own shading frame (its normal not perturbed).
  bool in_shading_frame(int i) const {
    const Frame& f = frames_[i];
    return f.n == frame_.n && f.s == frame_.s && f.t == frame_.t;
  }
  Vec3 to_local(const Vec3& v) const { return frame_.to_local(v); }
  Vec3 to_world(const Vec3& v) const { return frame_.to_world(v); }

  // Weighted sum of f over matching components that agree with the geometry: reflection
  // components when wo and wi are on the same side of the geometric normal, transmission ones
  // otherwise.
  RGB f(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask = kAll) const;
  // The same sum with each term times |cos θi| about its component's normal.
  RGB f_cos(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask = kAll) const;
  // Pdf of sample_f's mixture: the matching components' pdfs weighted by their sample weights
  // (with equal sample weights, the average).
  float pdf(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask = kAll) const;
  // f_cos(wo, wi) and pdf(wo, wi) (every component) in one pass over the components, each
  // evaluated once for both (f_f_cos_pdf): a light sample's pair. The same values as the two
  // calls.
  RGB f_cos_pdf(const Vec3& wo_world, const Vec3& wi_world, float* pdf_out) const;
  // Picks a matching component with u.x in proportion to its sample weight, remaps u.x to
  // [0, 1) and samples it. For a non-delta lobe f, f_cos and pdf are then those of the whole
  // mixture, so that f_cos/pdf is the estimator's weight; a delta lobe's f is its own times its
  // weight and its pdf is times the chance of picking it.
  BSDFSample sample_f(const Vec3& wo_world, Point2 u, uint32_t mask = kAll) const;

 private:
  Frame frame_;
  Vec3 ng_{0, 0, 1};
  Vec3 horizon_{0, 0, 1};  // set_sampling_horizon's normal, read where has_horizon_
  bool has_horizon_ = false;
  bool defensive_ = false;  // use_defensive_sampling() was called
  // use_defensive_sampling() on a BSDF of one component: its closures are picked defensively.
  bool component_picks_defensively_ = false;
  // A component model's own sample, pdf and f-with-pdf, its closures picked defensively where
  // component_picks_defensively_ says so: the one place that chooses between the two calls.
  BxDFSample model_sample(const BxDF& b, const Vec3& wo, Point2 u) const {
    return component_picks_defensively_ ? b.sample_f_defensive(wo, u) : b.sample_f(wo, u);
  }
  float model_pdf(const BxDF& b, const Vec3& wo, const Vec3& wi) const {
    return component_picks_defensively_ ? b.pdf_defensive(wo, wi) : b.pdf(wo, wi);
  }
  RGB model_f_pdf(const BxDF& b, const Vec3& wo, const Vec3& wi, float* pdf) const {
    return component_picks_defensively_ ? b.f_pdf_defensive(wo, wi, pdf) : b.f_pdf(wo, wi, pdf);
  }
  // Component i's local horizon normal when its cosine lobe is clipped at wo (local), else
  // false: no horizon, another kind of model, wo below its frame, or the plane below it.
  bool clipped_lobe(int i, const Vec3& wo, Vec3* g) const {
    if (!has_horizon_ || !(wo.z > 0.0f) || !components_[i]->samples_cosine_lobe()) return false;
    *g = frames_[i].to_local(horizon_);
    return g->z > 0.0f;
  }
  // Component i's pdf, its clipped lobe's where it has one.
  float component_pdf(int i, const Vec3& wo, const Vec3& wi) const;
  template <class Term>
  RGB weighted_sum(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask, Term term) const;
  // Component i's f at local wo, wi, with Cycles' bump shadowing where it applies.
  RGB component_f(int i, const Vec3& wo, const Vec3& wi, const Vec3& wi_world) const;
  // What f_f_cos_pdf needs of component i: its f as component_f gives it where `scatters`
  // (else 0), and its pdf as component_pdf gives it into *pdf where `weighs` (else *pdf is left
  // as it is); one call of the model where it needs both (BxDF::f_pdf).
  RGB component_f_pdf(int i, const Vec3& wo, const Vec3& wi, const Vec3& wi_world, bool scatters,
                      bool weighs, float* pdf) const;
  // f of component i with the bump-shadowing term its normal calls for. Most components have
  // none: that test is inline, so that the callers' loops do not spill around a call.
  RGB bump_shadowed(int i, RGB f, const Vec3& wo, const Vec3& wi, const Vec3& wi_world) const {
    if (bump_shadowing_[i] == BumpShadowing::None) return f;
    return apply_bump_shadowing(i, f, wo, wi, wi_world);
  }
  RGB apply_bump_shadowing(int i, RGB f, const Vec3& wo, const Vec3& wi, const Vec3& wi_world) const;
  // f(), f_cos() and pdf() of one direction pair in one pass (what sample_f needs).
  // `sampled`: a component whose f and pdf at this pair are already known (its own sample's),
  // so it is not evaluated again; nullptr when none.
  struct SampledComponent {
    int index;
    const Vec3& wo;  // local, in the component's frame
    const BxDFSample& sample;
  };
  void f_f_cos_pdf(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask, RGB* f,
                   RGB* f_cos, float* pdf, const SampledComponent* sampled = nullptr) const;

  // The components' slots: add() writes [0, count_), nothing reads past it. Left
  // uninitialised: a BSDF is built at every path vertex, and writing all eight slots (~500
  // bytes) cost more than the one or two components most hits add.
  Uninitialised<const BxDF*, kMaxComponents> components_;
  Uninitialised<RGB, kMaxComponents> weights_;
  Uninitialised<float, kMaxComponents> sample_weights_;
  Uninitialised<Frame, kMaxComponents> frames_;
  enum class BumpShadowing : uint8_t { None, Whole, DiffuseLobes };
  Uninitialised<BumpShadowing, kMaxComponents> bump_shadowing_;
  int count_ = 0;
};

}  // namespace bxdf

// The BxDF interface (the seed's f / Sample_f / Pdf / rho), its flags, and BxDFImpl, the
// CRTP layer that turns a model's three inline kernels into the robust scalar API and the
// batch (structure-of-arrays) API with one virtual call per batch.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "bxdf/closure_pick.h"
#include "bxdf/frame.h"
#include "bxdf/params.h"
#include "bxdf/spectrum.h"

namespace bxdf {

enum BxDFFlags : uint32_t {
  kReflection = 1u << 0,
  kTransmission = 1u << 1,
  kDiffuse = 1u << 2,
  kGlossy = 1u << 3,
  kSpecular = 1u << 4,
  kAllTypes = kDiffuse | kGlossy | kSpecular,
  kAll = kReflection | kTransmission | kAllTypes,
};

// What sample_f returns. pdf == 0 means no sample (f is then 0 and wi undefined).
struct BxDFSample {
  RGB f;
  Vec3 wi;
  float pdf = 0.0f;
  uint32_t flags = 0;  // the lobe that was sampled (e.g. reflection|specular)
  bool valid() const { return pdf > 0.0f; }
};

// Structure-of-arrays views over a batch of directions or colours.
struct DirectionsIn {
  const float* x;
  const float* y;
  const float* z;
};
struct DirectionsOut {
  float* x;
  float* y;
  float* z;
};
struct RGBOut {
  float* r;
  float* g;
  float* b;
};

class BxDF {
 public:
  explicit BxDF(uint32_t flags) : flags_(flags) {}
  virtual ~BxDF() = default;
  BxDF(const BxDF&) = delete;
  BxDF& operator=(const BxDF&) = delete;

  uint32_t flags() const { return flags_; }
  // True when every flag of this BxDF is in `mask` (pbrt's MatchesFlags).
  bool matches(uint32_t mask) const { return (flags_ & mask) == flags_; }
  bool is_delta() const { return (flags_ & (kDiffuse | kGlossy)) == 0 && (flags_ & kSpecular); }

  // Directions in the local frame, both pointing away from the surface, of any length;
  // a zero or non-finite direction gives 0. Never NaN, Inf or negative.
  virtual RGB f(const Vec3& wo, const Vec3& wi) const = 0;
  virtual BxDFSample sample_f(const Vec3& wo, Point2 u) const = 0;
  virtual float pdf(const Vec3& wo, const Vec3& wi) const = 0;
  // f(wo, wi) with pdf(wo, wi) in *pdf_out, the same values in one call: light sampling needs
  // both for each light point, and a model may share their work (the closures of a Principled).
  virtual RGB f_pdf(const Vec3& wo, const Vec3& wi, float* pdf_out) const {
    *pdf_out = pdf(wo, wi);
    return f(wo, wi);
  }

  // sample_f, pdf and f_pdf with the model's own closures picked by ClosurePick::kDefensive
  // (closure_pick.h): what Cycles does at a path's first surface. A model made of several of
  // Cycles' closures (the Principled BSDF, the Glass node) overrides them; for a model of one
  // closure they are sample_f, pdf and f_pdf.
  virtual BxDFSample sample_f_defensive(const Vec3& wo, Point2 u) const { return sample_f(wo, u); }
  virtual float pdf_defensive(const Vec3& wo, const Vec3& wi) const { return pdf(wo, wi); }
  virtual RGB f_pdf_defensive(const Vec3& wo, const Vec3& wi, float* pdf_out) const {
    return f_pdf(wo, wi, pdf_out);
  }

  // False for a model that samples as a Cycles closure does with its random walk (multiscatter
  // GGX): sample_f then draws wi from the walk and reports the walk's weight as f·|cos θi|/pdf,
  // with pdf = pdf(wo, wi), Cycles' approximate pdf for MIS, so its f is not f(wo, wi) and its
  // directions do not follow pdf. sample_f_exact is then the model's exact importance sampler
  // of f (f and pdf those of its direction, drawn from pdf); for every other model it is sample_f.
  virtual bool sample_f_is_exact() const { return true; }
  virtual BxDFSample sample_f_exact(const Vec3& wo, Point2 u) const { return sample_f(wo, u); }
  // True for a model that samples the cosine lobe on wo's side (cosine_reflection.h): a BSDF
  // with a sampling horizon then draws it above the triangle's plane (cosine_above_plane.h).
  virtual bool samples_cosine_lobe() const { return false; }
  // True for a model whose f is one constant, *f, on wo's side of the surface and 0 on the
  // other, sampled by that cosine lobe (a Lambertian; Cycles' Diffuse BSDF at roughness 0):
  // a BSDF of it alone is then a LoneDiffuse (lone_diffuse.h).
  virtual bool constant_cosine_lobe(RGB* /*f*/) const { return false; }

  // The part of f(wo, wi) that Cycles builds as diffuse closures (CLOSURE_IS_BSDF_DIFFUSE)
  // inside a model that also has other lobes: the Principled BSDF's diffuse and sheen. Cycles
  // darkens that part by bump_shadowing_term when the closure's normal is perturbed; the
  // BSDF asks for it only when has_diffuse_closure_lobes(). Same argument rules as f.
  virtual bool has_diffuse_closure_lobes() const { return false; }
  virtual RGB diffuse_closure_f(const Vec3& /*wo*/, const Vec3& /*wi*/) const { return RGB(0.0f); }

  // What Cycles folds into this closure's sample weight beyond the weight the closure is added
  // with: its Color input's average (svm_node_closure_bsdf makes the closure weight mix weight x
  // Color, and bsdf_alloc's sample_weight is that weight's average). A BSDF picks its
  // components by it, so a Mix of a dark Diffuse and a white Glossy samples the Glossy more,
  // as Cycles does. 1 where no Color is folded so (the other models).
  virtual float closure_sample_weight() const { return 1.0f; }

  // ρhd(wo) = ∫ f |cos θi| dωi and ρhh; Monte Carlo (stratified, seeded) unless a model knows better.
  virtual RGB rho_hd(const Vec3& wo, int n_samples, uint64_t seed = 0) const;
  virtual RGB rho_hh(int n_samples, uint64_t seed = 0) const;

  // Batch forms: n directions as separate x/y/z arrays. Same results as the scalar calls.
  virtual void f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const = 0;
  virtual void sample_f_batch(size_t n, DirectionsIn wo, const float* u1, const float* u2,
                              DirectionsOut wi, RGBOut f, float* pdf) const = 0;
  virtual void pdf_batch(size_t n, DirectionsIn wo, DirectionsIn wi, float* out) const = 0;

  // The registry name and validated parameters that rebuild this model (set by make(); empty
  // for a model built without them, as a material graph's closures are at every hit).
  const std::string& model_name() const;
  const ParamSet& params() const;
  void set_identity(std::string name, ParamSet params);

 private:
  struct Identity {
    std::string name;
    ParamSet params;
  };
  uint32_t flags_;
  // Held apart, so that a model built per hit (ClosureArena) makes and destroys one null
  // pointer instead of a string and two vectors.
  std::unique_ptr<const Identity> identity_;
};

std::string flags_to_string(uint32_t flags);  // "reflection|glossy"

// The direction half of a sample: wi (any length) and the sampled lobe; ok = false for none.
struct DirectionSample {
  Vec3 wi;
  uint32_t flags = 0;
  bool ok = false;
};

// Derived implements, inline and assuming unit-length directions:
//   RGB eval(const Vec3& wo, const Vec3& wi) const;
//   BxDFSample sample(const Vec3& wo, Point2 u) const;
//   float density(const Vec3& wo, const Vec3& wi) const;
// BxDFImpl normalises inputs, refuses degenerate ones and scrubs every output, so a kernel
// only has to be right for well-formed input.
//
// A model whose sample is not its exact importance sampler (sample_f_is_exact) also provides
//   BxDFSample sample_exact(const Vec3& wo, Point2 u) const;
// the one sample_f_exact wraps.
//
// A model whose sample's f and pdf are exactly eval(wo, wi) and density(wo, wi) of the drawn
// direction may also provide
//   DirectionSample sample_direction(const Vec3& wo, Point2 u) const;
// Then sample_f (scalar and batch) draws the direction with it and evaluates f and pdf with the
// eval and density kernels, which in a batch is a second pass that vectorises (the drawing,
// with its warps and trigonometry, rarely does).
template <class T, class = void>
struct has_sample_direction : std::false_type {};
template <class T>
struct has_sample_direction<
    T, std::void_t<decltype(std::declval<const T&>().sample_direction(Vec3(), Point2()))>>
    : std::true_type {};
template <class T, class = void>
struct has_sample_exact : std::false_type {};
template <class T>
struct has_sample_exact<
    T, std::void_t<decltype(std::declval<const T&>().sample_exact(Vec3(), Point2()))>>
    : std::true_type {};

// A model made of several of Cycles' closures picks one by a ClosurePick:
//   BxDFSample sample(const Vec3& wo, Point2 u, ClosurePick pick) const;
//   float density(const Vec3& wo, const Vec3& wi, ClosurePick pick) const;
// (sample(wo, u) and density(wo, wi) being the kByWeight ones), and the *_defensive calls use
// them with kDefensive.
template <class T, class = void>
struct has_closure_pick : std::false_type {};
template <class T>
struct has_closure_pick<T, std::void_t<decltype(std::declval<const T&>().density(
                               Vec3(), Vec3(), ClosurePick::kDefensive))>> : std::true_type {};

// A model whose eval and density share work gives both at once: eval_density(wo, wi, &pdf).
template <class T, class = void>
struct has_eval_density : std::false_type {};
template <class T>
struct has_eval_density<T, std::void_t<decltype(std::declval<const T&>().eval_density(
                               Vec3(), Vec3(), static_cast<float*>(nullptr)))>>
    : std::true_type {};

template <class Derived>
class BxDFImpl : public BxDF {
 public:
  using BxDF::BxDF;

  RGB f(const Vec3& wo, const Vec3& wi) const final { return f_one(wo, wi); }
  BxDFSample sample_f(const Vec3& wo, Point2 u) const final { return sample_one(wo, u); }
  float pdf(const Vec3& wo, const Vec3& wi) const final { return pdf_one(wo, wi); }
  // f_one and pdf_one with the directions normalised once.
  RGB f_pdf(const Vec3& wo, const Vec3& wi, float* pdf_out) const final {
    return f_pdf_picked<ClosurePick::kByWeight>(wo, wi, pdf_out);
  }
  BxDFSample sample_f_defensive(const Vec3& wo, Point2 u) const final {
    return sample_picked<defensive_pick()>(wo, u);
  }
  float pdf_defensive(const Vec3& wo, const Vec3& wi) const final {
    return pdf_picked<defensive_pick()>(wo, wi);
  }
  RGB f_pdf_defensive(const Vec3& wo, const Vec3& wi, float* pdf_out) const final {
    return f_pdf_picked<defensive_pick()>(wo, wi, pdf_out);
  }
  BxDFSample sample_f_exact(const Vec3& wo_in, Point2 u) const final {
    if constexpr (has_sample_exact<Derived>::value) {
      Vec3 wo = wo_in;
      if (!normalize_direction(wo)) return BxDFSample();
      return guard_sample(derived().sample_exact(wo, clamp_u(u)));
    } else {
      return sample_one(wo_in, u);
    }
  }

  // The batch forms work in blocks: a first pass normalises the directions with selects
  // instead of early returns (a refused direction becomes +z and a cleared `ok` flag), then a
  // kernel pass with no exits runs the model on every element and zeroes the refused ones.
  // Both passes are loops the compiler can vectorise when the model's kernel is branch-free;
  // the arithmetic is that of f_one/pdf_one/sample_one, so the results are the same bits.
  void f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const final {
    derived().with_eval_kernel([&](const auto& kernel) { f_loop(kernel, n, wo, wi, out); });
  }
  // A model whose f has loop-invariant choices (an enum parameter) hides this with one that
  // calls fn with a kernel specialised for them; by default the kernel is the model's eval.
  template <class Fn>
  void with_eval_kernel(Fn&& fn) const {
    fn(derived());
  }
  template <class Kernel>
  static void f_loop(const Kernel& kernel, size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) {
    Block a, b;
    for (size_t start = 0; start < n; start += kBlock) {
      const size_t m = std::min(kBlock, n - start);
      a.normalize(m, wo, start);
      b.normalize(m, wi, start);
      float* __restrict r = out.r + start;
      float* __restrict g = out.g + start;
      float* __restrict bl = out.b + start;
      for (size_t i = 0; i < m; ++i) {
        const RGB v = kernel.eval(a.at(i), b.at(i));
        const bool ok = (a.ok[i] & b.ok[i]) != 0;
        r[i] = ok ? sanitize_nonnegative(v.r) : 0.0f;
        g[i] = ok ? sanitize_nonnegative(v.g) : 0.0f;
        bl[i] = ok ? sanitize_nonnegative(v.b) : 0.0f;
      }
    }
  }
  void sample_f_batch(size_t n, DirectionsIn wo, const float* u1, const float* u2,
                      DirectionsOut wi, RGBOut f, float* pdf) const final {
    if constexpr (has_sample_direction<Derived>::value) {
      derived().with_eval_kernel([&](const auto& kernel) {
        sample_direction_loop(kernel, n, wo, u1, u2, wi, f, pdf);
      });
      return;
    }
    Block a;
    for (size_t start = 0; start < n; start += kBlock) {
      const size_t m = std::min(kBlock, n - start);
      a.normalize(m, wo, start);
      for (size_t i = 0; i < m; ++i) {
        const size_t k = start + i;
        const BxDFSample s = sample_kernel(a.at(i), clamp_u(Point2(u1[k], u2[k])));
        const bool ok = a.ok[i] & s.valid();
        wi.x[k] = ok ? s.wi.x : 0.0f;
        wi.y[k] = ok ? s.wi.y : 0.0f;
        wi.z[k] = ok ? s.wi.z : 0.0f;
        f.r[k] = ok ? s.f.r : 0.0f;
        f.g[k] = ok ? s.f.g : 0.0f;
        f.b[k] = ok ? s.f.b : 0.0f;
        pdf[k] = ok ? s.pdf : 0.0f;
      }
    }
  }
  void pdf_batch(size_t n, DirectionsIn wo, DirectionsIn wi, float* out) const final {
    Block a, b;
    for (size_t start = 0; start < n; start += kBlock) {
      const size_t m = std::min(kBlock, n - start);
      a.normalize(m, wo, start);
      b.normalize(m, wi, start);
      float* __restrict p = out + start;
      for (size_t i = 0; i < m; ++i) {
        const float v = derived().density(a.at(i), b.at(i));
        const bool ok = (a.ok[i] & b.ok[i]) != 0;
        p[i] = ok ? sanitize_nonnegative(v) : 0.0f;
      }
    }
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }

  static constexpr size_t kBlock = 64;

  // A block of directions normalised as normalize_direction() does it, written with selects:
  // ok[i] says whether it succeeded; where it did not, the direction is +z (any unit vector
  // would do: the kernels run on it, and the result is discarded).
  struct Block {
    alignas(64) float x[kBlock], y[kBlock], z[kBlock];
    alignas(64) int32_t ok[kBlock];  // 0 or 1, as wide as a float: mask and data vectorise together
    BXDF_KERNEL void normalize(size_t m, DirectionsIn d, size_t start) {
      const float* __restrict dx = d.x + start;
      const float* __restrict dy = d.y + start;
      const float* __restrict dz = d.z + start;
      for (size_t i = 0; i < m; ++i) {
        const float vx = dx[i], vy = dy[i], vz = dz[i];
        const float l2 = vx * vx + vy * vy + vz * vz;
        const bool good = is_direction_length_squared(l2);
        const float inv = normalizing_scale(l2);
        x[i] = good ? vx * inv : 0.0f;
        y[i] = good ? vy * inv : 0.0f;
        z[i] = good ? vz * inv : 1.0f;
        ok[i] = good;
      }
    }
    Vec3 at(size_t i) const { return {x[i], y[i], z[i]}; }
  };

  // Keeps u in [0, 1): NaN or out-of-range numbers would otherwise leak into the warps.
  BXDF_KERNEL static Point2 clamp_u(Point2 u) {
    constexpr float kOneBelowOne = 0x1.fffffep-1f;
    const auto c = [](float v) {
      return v >= 0.0f && v < 1.0f ? v : (v >= 1.0f ? kOneBelowOne : 0.0f);
    };
    return {c(u.x), c(u.y)};
  }

  // sample_f_batch for a model with sample_direction: per block, the directions are drawn in
  // one loop and f and pdf evaluated in a second, branch-free one.
  template <class Kernel>
  void sample_direction_loop(const Kernel& kernel, size_t n, DirectionsIn wo, const float* u1,
                             const float* u2, DirectionsOut wi, RGBOut f, float* pdf) const {
    Block a, b;
    for (size_t start = 0; start < n; start += kBlock) {
      const size_t m = std::min(kBlock, n - start);
      a.normalize(m, wo, start);
      for (size_t i = 0; i < m; ++i) {
        const DirectionSample d =
            derived().sample_direction(a.at(i), clamp_u(Point2(u1[start + i], u2[start + i])));
        b.x[i] = d.wi.x;
        b.y[i] = d.wi.y;
        b.z[i] = d.wi.z;
        b.ok[i] = a.ok[i] & d.ok;
      }
      for (size_t i = 0; i < m; ++i) {
        const size_t k = start + i;
        const Vec3 o = a.at(i), w = b.at(i);
        BxDFSample s;
        s.wi = w;
        s.f = kernel.eval(o, w);
        const float density = derived().density(o, w);
        s.pdf = b.ok[i] != 0 ? density : 0.0f;
        s = guard_sample(s);
        wi.x[k] = s.wi.x;
        wi.y[k] = s.wi.y;
        wi.z[k] = s.wi.z;
        f.r[k] = s.f.r;
        f.g[k] = s.f.g;
        f.b[k] = s.f.b;
        pdf[k] = s.pdf;
      }
    }
  }

  // The model's sample for a unit wo and u in [0, 1), with the guards of the scalar API.
  BxDFSample sample_kernel(const Vec3& wo, Point2 u) const {
    if constexpr (has_sample_direction<Derived>::value) {
      const DirectionSample d = derived().sample_direction(wo, u);
      BxDFSample s;
      s.wi = d.wi;
      s.f = derived().eval(wo, d.wi);
      s.pdf = d.ok ? derived().density(wo, d.wi) : 0.0f;
      s.flags = d.flags;
      return guard_sample(s);
    } else {
      return guard_sample(derived().sample(wo, u));
    }
  }
  // A sample is kept only if its pdf and f are finite and non-negative and wi normalises
  // (pdf = 0 marks a refused one, with all of it zero); wi is returned normalised.
  BXDF_KERNEL static BxDFSample guard_sample(const BxDFSample& s) {
    const float l2 = length_squared(s.wi);
    const bool wi_ok = is_direction_length_squared(l2);
    // Normalised as normalize_direction() does it, so that f and pdf see the direction
    // returned.
    const float inv = normalizing_scale(l2);
    // One condition per select (GCC 12 does not if-convert this as one && chain).
    float pdf = finite_nonnegative(s.pdf) ? s.pdf : 0.0f;
    pdf = wi_ok ? pdf : 0.0f;
    pdf = finite_nonnegative(s.f.r) ? pdf : 0.0f;
    pdf = finite_nonnegative(s.f.g) ? pdf : 0.0f;
    pdf = finite_nonnegative(s.f.b) ? pdf : 0.0f;
    const bool ok = pdf > 0.0f;
    BxDFSample out;
    out.wi = Vec3(ok ? s.wi.x * inv : 0.0f, ok ? s.wi.y * inv : 0.0f, ok ? s.wi.z * inv : 0.0f);
    out.f = RGB(ok ? s.f.r : 0.0f, ok ? s.f.g : 0.0f, ok ? s.f.b : 0.0f);
    out.pdf = ok ? s.pdf : 0.0f;
    out.flags = ok ? s.flags : 0u;
    return out;
  }

  inline RGB f_one(Vec3 wo, Vec3 wi) const {
    if (!normalize_direction(wo) || !normalize_direction(wi)) return RGB(0.0f);
    return sanitize_nonnegative(derived().eval(wo, wi));
  }
  inline float pdf_one(Vec3 wo, Vec3 wi) const { return pdf_picked<ClosurePick::kByWeight>(wo, wi); }
  inline BxDFSample sample_one(Vec3 wo, Point2 u) const {
    return sample_picked<ClosurePick::kByWeight>(wo, u);
  }

  // The pick the *_defensive calls make: kDefensive where the model picks among closures.
  static constexpr ClosurePick defensive_pick() {
    return has_closure_pick<Derived>::value ? ClosurePick::kDefensive : ClosurePick::kByWeight;
  }
  // The model's density and sample with its closures picked by kPick (kByWeight: the calls
  // every model has).
  template <ClosurePick kPick>
  float density_of(const Vec3& wo, const Vec3& wi) const {
    if constexpr (kPick == ClosurePick::kByWeight) return derived().density(wo, wi);
    else return derived().density(wo, wi, kPick);
  }
  template <ClosurePick kPick>
  float pdf_picked(Vec3 wo, Vec3 wi) const {
    if (!normalize_direction(wo) || !normalize_direction(wi)) return 0.0f;
    return sanitize_nonnegative(density_of<kPick>(wo, wi));
  }
  template <ClosurePick kPick>
  BxDFSample sample_picked(Vec3 wo, Point2 u) const {
    if (!normalize_direction(wo)) return BxDFSample();
    if constexpr (kPick == ClosurePick::kByWeight) return sample_kernel(wo, clamp_u(u));
    else return guard_sample(derived().sample(wo, clamp_u(u), kPick));
  }
  template <ClosurePick kPick>
  RGB f_pdf_picked(Vec3 wo, Vec3 wi, float* pdf_out) const {
    if (!normalize_direction(wo) || !normalize_direction(wi)) {
      *pdf_out = 0.0f;
      return RGB(0.0f);
    }
    if constexpr (has_eval_density<Derived>::value) {
      float density = 0.0f;
      RGB f;
      if constexpr (kPick == ClosurePick::kByWeight) f = derived().eval_density(wo, wi, &density);
      else f = derived().eval_density(wo, wi, &density, kPick);
      *pdf_out = sanitize_nonnegative(density);
      return sanitize_nonnegative(f);
    } else {
      *pdf_out = sanitize_nonnegative(density_of<kPick>(wo, wi));
      return sanitize_nonnegative(derived().eval(wo, wi));
    }
  }
};

// Result type of make(): models are immutable once built, so they are shared freely.
using BxDFPtr = std::shared_ptr<const BxDF>;

}  // namespace bxdf

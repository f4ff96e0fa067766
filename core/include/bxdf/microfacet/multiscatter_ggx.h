// Multiple-scattering GGX (Heitz et al. 2016, "Multiple-Scattering Microfacet BSDFs with the
// Smith Model") as Cycles 3.4 implements it (closure/bsdf_microfacet_multi*.h): a random walk
// over the Smith microsurface (uniform height distribution, GGX visible normals) of up to 10
// bounces, whose first bounce is evaluated analytically. Two lobes: reflection (a conductor-
// like surface: colour, or Cycles' interpolated Fresnel of the Principled specular) and glass
// (reflection + refraction through a dielectric microsurface).
//
// Determinism. Cycles evaluates one walk per shading point with an LCG seeded per hit, so its
// eval is a random variable whose expectation is the BSDF. Here f(wo, wi) averages
// kMultiscatterWalks walks whose generator is seeded from a hash of the bits of the walked
// pair, so f is a fixed function of (wo, wi): the same inputs give the same bits in the scalar
// and batch paths, and f(wo, wi) and f(wi, wo) walk the same pair (Cycles walks from the
// shallower direction and rescales; the seed follows that order), so reflection is
// reciprocal bit for bit. The first bounce is exact; the higher orders carry the walk's noise.
// Error of f against a 20000-walk average (tests/core/test_multiscatter_ggx.cpp): relative RMS
// 0.235 for reflection at α 0.7 (single walks are heavy-tailed) and 0.118 for glass at α 0.6,
// every pair within 4 standard errors of the long average.
//
// That error is fixed per direction pair, so a render whose samples share a pair (a pixel-centre
// filter under a point light: every sample of a pixel has the same wo and wi) would keep it:
// 2.4% of a multiscatter sphere's pixels were past 4σ of Cycles' noise although the totals
// agreed to 0.1%. The renderer therefore evaluates f inside a MultiscatterWalkSalt scope: the
// camera sample's number is mixed into the walks' seed, so a 4-walk estimator is used with
// independent walks per sample, and a pixel converges to the expectation as Cycles' one walk
// per sample does (its own error shrinks as 1/√samples and is part of the image noise).
// Inside a MultiscatterWalkNumbers scope too (the renderer opens one per path vertex) the
// first of those walks draws from the vertex's numbers, as Cycles' eval walk draws from the
// shading point's LCG (walk_numbers.h), so that the vertex's sampling walk starts where
// Cycles' does. Outside a scope (salt 0) f is the fixed function above. Making f itself exact
// (tabulating the walk's expectation) was measured out of reach: 16 → 64 → 256 walks give
// relative RMS 0.164 → 0.072 → 0.042 (reflection α 0.7) at 4 → 16 times the cost, and
// scrambled Sobol walks only 0.139 → 0.059 → 0.033; a table needs the per-order expectations
// over α, the colour's and the interpolated Fresnel's (η, cspec0) powers, and η for glass.
//
// Cycles' quirks kept: its eval walks from the shallower direction, but its walk is not
// reciprocal (mf_sample_height puts an upward ray that does not escape at the top height,
// where Heitz samples one), so its eval and its sampling walk disagree: white reflection at
// α 0.64 reflects 0.922 of the light by eval and 1.000 by the walk at θo 20° (0.974 at 55°,
// 0.9995 at 75°); the glossy eval applies the throughput twice to orders ≥ 2 (colour^2k); the
// glass eval of a transmitted pair has no η² in its phase function and, for the Fresnel
// closure, leaves the first order untinted. These lobes reproduce the eval.
//
// Sampling. Cycles samples with the walk itself and reports an approximate pdf (an albedo-
// weighted blend of single-scattering and cosine pdfs), so its sample and pdf disagree.
// sample_walk is that sampling walk (its weight bounded by the colours, as Cycles' is); the
// Cycles models' sample_f uses it, with density() as the reported pdf. sample_direction and
// density are a consistent pair for exact importance sampling of f (ρ, the χ² tests, and the
// lobe without a Cycles closure): reflection picks, with probability a = Cycles' mf_ggx_albedo
// fit, a GGX visible normal and reflects, else a cosine direction; glass picks a visible normal
// and reflects or refracts by the Fresnel term, else a cosine direction on the reflected side
// (probability F(cos θo)) or the transmitted side. (Cycles' glass pdf, mf_glass_pdf, weighs
// its reflection by the Fresnel term at the half vector and uses the transmission albedo fit;
// it does not integrate to one, so density() keeps the normalised blend.)
//
// Conventions: local shading frame, wo and wi unit vectors pointing away from the surface,
// f without the cosine. Reflection is two-sided (a wo below the surface mirrors both
// directions, as Cycles turns the normal to the viewer). Glass: eta = index inside (z < 0) /
// index outside; a wo below the surface sees 1/eta (Cycles' back-face IOR).
#pragma once

#include <cstdint>

#include "bxdf/bxdf.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/rng.h"
#include "bxdf/spectrum.h"

namespace bxdf {
namespace microfacet {

// Walks averaged per evaluation of f. 16 keeps the relative RMS error of f below a few per cent
// of the multiple-scattering part (see the test) at ~16 walks' cost.
constexpr int kMultiscatterWalks = 16;
// Walks per evaluation inside a MultiscatterWalkSalt scope (the renderer): there every sample
// walks anew, so a pixel converges to the expectation whatever the count, and the count only
// trades the walks' share of the image noise (half of Cycles' one walk per sample at 4)
// against their cost (16 walks were 15% of sweep_principled_multiscatter's instructions).
constexpr int kSaltedMultiscatterWalks = 4;

// How the walk colours its bounces (Cycles' use_fresnel flag of the closure).
enum class MultiscatterFresnel {
  // Every bounce after the first multiplies the throughput by `color` (the closure's weight
  // carries the first one): Cycles' Glossy / Glass nodes.
  kColor,
  // Every reflection multiplies it by Cycles' interpolate_fresnel_color(cspec0, eta) and every
  // refraction by `color`: the Principled specular and the Principled glass.
  kInterpolated,
};

struct MultiscatterSetup {
  float alpha_x = 0.25f, alpha_y = 0.25f;  // clamped to [1e-4, 1] as Cycles' setup does
  float eta = 1.5f;  // reflection: the IOR of the interpolated Fresnel; glass: inside/outside
  RGB color{1.0f};   // clamped to [0, 1]
  RGB cspec0{1.0f};  // clamped to [0, 1]; kInterpolated only
  MultiscatterFresnel fresnel = MultiscatterFresnel::kColor;
};

// f hashes the bits of its directions, so a sampled direction must be snapped (math.h).
using bxdf::snap_to_unit;

// While alive, mixes `salt` into the seed of every multiscatter walk this thread evaluates
// (see Determinism): the renderer opens one per camera sample. Scopes nest; salt 0 is the
// unsalted f. No allocation: a thread-local number.
class MultiscatterWalkSalt {
 public:
  explicit MultiscatterWalkSalt(uint64_t salt);
  ~MultiscatterWalkSalt();
  MultiscatterWalkSalt(const MultiscatterWalkSalt&) = delete;
  MultiscatterWalkSalt& operator=(const MultiscatterWalkSalt&) = delete;

  // This thread's salt (0 outside any scope).
  static uint64_t current();
  // This thread's salt variable itself, for a loop that sets it per sample (the renderer's
  // path batches) and restores it afterwards: in a shared object every thread_local access is
  // a call, which a scope per path vertex paid three times.
  static uint64_t* thread_slot();

 private:
  uint64_t previous_;
};

// A draw of Cycles' sampling walk (mf_sample): the exit direction (snapped, snap_to_unit) and
// the walk's weight f·|cos θi|/p, which Cycles' closures return from their sample in place of
// eval/pdf. ok = false when the walk does not leave within 10 bounces (Cycles: weight 0).
struct WalkSample {
  Vec3 wi;
  RGB weight;
  uint32_t flags = 0;
  bool ok = false;
};

// Cycles' helpers (bsdf_util.h, bsdf_microfacet_multi.h), exposed for the models and tests.
float cycles_fresnel_dielectric_cos(float cos_i, float eta);
// cspec0 (1 − FH) + FH with FH = (F(cos_lh) − F0)/(1 − F0), F0 = F(1).
RGB cycles_interpolate_fresnel(float cos_lh, float eta, const RGB& cspec0);
// The same from F(cos_lh) and F0 already at hand.
RGB cycles_interpolate_fresnel_of(float fresnel, float f0, const RGB& cspec0);
float cycles_ggx_albedo(float roughness);
float cycles_ggx_transmission_albedo(float alpha, float ior);

class MultiscatterGGXReflection {
 public:
  explicit MultiscatterGGXReflection(const MultiscatterSetup& setup);

  RGB eval(Vec3 wo, Vec3 wi) const;
  DirectionSample sample_direction(Vec3 wo, Point2 u) const;
  float density(Vec3 wo, Vec3 wi) const;

  // One walk of Cycles' mf_eval, drawing from rng: an unbiased estimate of f(wo, wi).
  RGB walk_f(Vec3 wo, Vec3 wi, PCG32& rng) const;
  // Cycles' mf_sample: the exit direction of one walk from wo (into *wi) and its weight
  // f cos θi / p (0 when the walk does not leave within 10 bounces).
  RGB walk_sample(Vec3 wo, PCG32& rng, Vec3* wi) const;
  // Cycles' sampling walk from wo: its first facet is the visible normal that u picks (the
  // walk's own first draw, stratified by the caller's u); the rest come from the thread's
  // MultiscatterWalkNumbers where the renderer opened a scope (Cycles' LCG per path vertex,
  // walk_numbers.h, where u is the facet of the path's first walk only), else from a
  // generator seeded by the bits of wo and u and the thread's walk salt.
  WalkSample sample_walk(Vec3 wo, Point2 u) const;

  const MultiscatterSetup& setup() const { return setup_; }

 private:
  MultiscatterSetup setup_;
  GGX ggx_;
  float single_probability_;  // a: the share of visible-normal samples
};

class MultiscatterGGXGlass {
 public:
  // Isotropic (Cycles' glass uses alpha_x only).
  explicit MultiscatterGGXGlass(const MultiscatterSetup& setup);

  RGB eval(Vec3 wo, Vec3 wi) const;
  DirectionSample sample_direction(Vec3 wo, Point2 u) const;
  float density(Vec3 wo, Vec3 wi) const;

  RGB walk_f(Vec3 wo, Vec3 wi, PCG32& rng) const;
  RGB walk_sample(Vec3 wo, PCG32& rng, Vec3* wi) const;
  WalkSample sample_walk(Vec3 wo, Point2 u) const;  // as the reflection's

  const MultiscatterSetup& setup() const { return setup_; }

 private:
  MultiscatterSetup setup_;
  GGX ggx_;
  float single_probability_;
};

// The glass walk's transmitted part alone: Cycles' multiscatter glass (microfacet_multi_ggx_
// glass) restricted to transmission, which is what cycles_refraction's multi_ggx means (Blender
// 3.4's Refraction node has no multiscatter option and Cycles no such closure). f is the glass
// eval where wi lies on the other side of the surface from wo and 0 on wo's side: the light the
// walk reflects back is lost, with the Fresnel term at every facet as in the glass. Sampling:
// with probability a (Cycles' mf_ggx_albedo fit) a GGX visible normal refracts wo (nothing
// under total internal reflection), else a cosine direction on the transmitted side.
class MultiscatterGGXRefraction {
 public:
  explicit MultiscatterGGXRefraction(const MultiscatterSetup& setup);

  RGB eval(Vec3 wo, Vec3 wi) const;
  DirectionSample sample_direction(Vec3 wo, Point2 u) const;
  float density(Vec3 wo, Vec3 wi) const;

  const MultiscatterSetup& setup() const { return glass_.setup(); }

 private:
  MultiscatterGGXGlass glass_;
  GGX ggx_;
  float single_probability_;
};

}  // namespace microfacet
}  // namespace bxdf

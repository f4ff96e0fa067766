// How many of a Cycles rough refraction lobe's samples to draw uniformly on the transmitted side,
// and how they are drawn.
//
// Cycles' rough refraction f checks no facet side (cycles_lobes.h), so it is not zero on pairs
// that visible-normal sampling never draws. Cycles' own sampler (and the models' sample_f,
// which the renderer uses) leaves them to light sampling; the exact importance sampler
// (sample_f_exact) covers them with a share s of its samples drawn uniformly over the
// transmitted hemisphere: f |cos θi| / pdf is unbiased for every s in (0, 1),
// and its second moment is about A/(1 − s) + B/s, with A the facet sampler's own second moment
// and B = ∫ over the uncovered pairs of (f |cos θi|)² / p_cover. The share that minimises it,
// s* = √B / (√A + √B), runs from ~0 (smooth lobes near normal incidence, where the facets cover
// nearly all of f; kept at 0.01 or more) to 0.9 (rough, grazing, η near 1, where most of f is
// on uncovered pairs).
// Uniform, not cosine-weighted: f grows without bound towards grazing exits, where a cosine
// density's weight π f / s reached ~1000 (Principled, η 1.1, α 0.09, from inside at
// cos θo 0.48); the uniform density's weight 2π f |cos θi| / s has the cosine to temper it
// (largest seen 86, second moment 7.8x smaller there).
// A fixed share of 1/4 cost the harness's glass room 1.3x the variance per rough refraction
// (measured with the cosine cover, when the renderer still drew the cover).
//
// refraction_cover_table.inc holds s* over √α, ln η and cos θo for GGX and Beckmann, made by
// `bxdf-refraction-cover-table` (core/tools/refraction_cover_table.cpp) from the lobes
// themselves; refraction_cover_share interpolates it trilinearly. sample() and density() of a
// lobe call it with the same (α, η, cos θo), so they always agree on the mixture.
#pragma once

#include <cstdint>

#include "bxdf/sampling.h"

namespace bxdf {
namespace cycles {

// A cover sample: uniform over the hemisphere below the surface (z < 0), and its density.
inline Vec3 sample_refraction_cover(Point2 u) {
  Vec3 wi = sample_uniform_hemisphere(u);
  wi.z = -wi.z;
  return wi;
}
inline float refraction_cover_pdf(const Vec3& wi) {
  return wi.z < 0.0f ? uniform_hemisphere_pdf() : 0.0f;
}

enum class CoverDistribution : int { kGGX = 0, kBeckmann = 1 };

// The table's axes: √α at i / (kCoverRoughnessSteps − 1); ln η from −kCoverLogEtaMax to
// +kCoverLogEtaMax in kCoverLogEtaSteps steps (η = 1 in the middle); cos θo at cell centres
// (k + 1/2) / kCoverCosSteps. Values outside are clamped to the edge.
constexpr int kCoverRoughnessSteps = 16;
constexpr int kCoverLogEtaSteps = 17;
constexpr int kCoverCosSteps = 16;
constexpr float kCoverLogEtaMax = 1.0986123f;  // ln 3
// The share never drops to 0 (f is positive on some uncovered pairs for every α > 0) nor
// takes every sample from the facets' sampler.
constexpr float kCoverShareMin = 1e-2f;
constexpr float kCoverShareMax = 0.9f;

// s* for a lobe of roughness α (GGX or Beckmann, isotropic), relative index η (index on wi's
// side over wo's), at cos θo = wo.z > 0. Always in [kCoverShareMin, kCoverShareMax], also for
// non-finite arguments.
float refraction_cover_share(CoverDistribution distribution, float alpha, float eta,
                             float cos_o);

// s* estimated afresh from strata² jittered samples of each kind (seeded, so repeatable): A
// from the facet sampler of cycles_lobes.h's RefractionLobe, B from cover samples
// (sample_refraction_cover) below where that sampler has no density. What the table was made with
// (bxdf-refraction-cover-table, 128 strata), clamped to the same range.
float estimate_cover_share(CoverDistribution distribution, float alpha, float eta, float cos_o,
                           int strata, uint64_t seed);

// The table entry's (α, η, cos θo), for the generator and the tests.
float cover_table_alpha(int roughness_index);
float cover_table_eta(int log_eta_index);
float cover_table_cos(int cos_index);
// The stored value at an entry.
float cover_table_value(CoverDistribution distribution, int roughness_index, int log_eta_index,
                        int cos_index);

}  // namespace cycles
}  // namespace bxdf

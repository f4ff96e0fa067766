// The numbers of a path's multiscatter sampling walks, drawn as Cycles 3.4 draws them.
//
// Cycles draws every number of a shading point's multiscatter walks from one LCG
// (sd->lcg_state, sample/lcg.h), started at lcg_state_init(rng_hash, rng_offset, sample,
// 0xb4bc3953): the pixel's hash plus the sample number times a constant plus rng_offset, which
// grows by PRNG_BOUNCE_NUM = 16 at every bounce (transparent ones too). An LCG started 16
// higher draws the same numbers, each shifted by a constant (x_n(s + 16) = x_n(s) + 16·a^(n+1)
// mod 2^32), so the walks at two vertices of one path are correlated, and Cycles' image
// converges to what such correlated walks give. Where a multiscatter surface reflects another
// (the bottom row of sweep_principled_multiscatter, where each sphere's limb mirrors its
// neighbour) that differs from independent walks: at such a limb the pixel converges to 0.20
// with correlated walks and 0.42 with independent ones, and Cycles' 4096-sample render reads
// 0.21 there.
//
// WalkNumbers reproduces that: the renderer starts one per path vertex at its seed plus 16 per
// bounce so far, and every sampling walk there draws from it in Cycles' order (per order: the
// height, the visible normal's y and x, and for glass the phase). One thing differs, for less
// noise: the first facet of the path's first sampling walk is the caller's stratified 2D sample
// (the BSDF's Sobol numbers) instead of the LCG's two numbers. The path's WalkAnchor then
// remembers how far those two numbers lie from the LCG's, and every later vertex's draws at the
// same positions are shifted by as much, so that every pair of vertices keeps Cycles' constant
// shift between them. (Dropping the stratified facet instead raises the variance of the
// multiscatter row by 45% at 64 samples.)
//
// Cycles' eval walks (its light samples' BSDF evaluation) draw from the same LCG before the
// vertex's sampling walk, which moves the sampling walk's numbers along the sequence by as many
// as the eval walk took. Here f averages several walks (multiscatter_ggx.h); inside a scope the
// first of them draws from the vertex's WalkNumbers, so the sampling walk starts where Cycles'
// does. Under a light that unties a path's walks again, in Cycles as here (the limb above reads
// 0.50-0.53 in Cycles with a point light added, and 0.20 here before the eval drew from it).
#pragma once

#include <cstdint>

#include "bxdf/math.h"

namespace bxdf {
namespace microfacet {

// What a path keeps from its first sampling walk: where in a vertex's sequence that walk's
// first facet was drawn and how far the stratified numbers that replaced it lay from the
// LCG's. No anchor while position is 0.
struct WalkAnchor {
  uint32_t position = 0;  // the draw number (from 1) of the facet's y; x is the next
  uint32_t shift_y = 0, shift_x = 0;
};

class WalkNumbers {
 public:
  // Cycles' lcg_init(seed): the generator of a vertex whose seed is `seed`; `anchor` is the
  // path's (kept across its vertices, set by its first sampling walk).
  WalkNumbers(uint32_t seed, WalkAnchor* anchor) : state_(step(seed)), anchor_(anchor) {}

  // Cycles' lcg_step_float: in [0, 1] (a draw near 2^32 rounds to 1, as Cycles' does).
  float uniform() {
    const uint32_t x = next();
    return static_cast<float>(x) * (1.0f / 4294967296.0f);
  }
  // A walk's first visible-normal draw (Cycles draws y, then x): `u` itself at the path's first
  // sampling walk (which anchors it), else the sequence's two numbers.
  Point2 first_facet(Point2 u);

 private:
  static uint32_t step(uint32_t x) { return 1103515245u * x + 12345u; }
  // The next draw as a 32-bit integer, shifted where the anchor says.
  uint32_t next() {
    state_ = step(state_);
    ++drawn_;
    const uint32_t p = anchor_->position;
    if (p == 0 || (drawn_ != p && drawn_ != p + 1)) return state_;
    return state_ + (drawn_ == p ? anchor_->shift_y : anchor_->shift_x);
  }

  uint32_t state_;
  uint32_t drawn_ = 0;  // draws so far
  WalkAnchor* anchor_;
};

// While alive, this thread's multiscatter sampling walks draw from `numbers` (the renderer opens
// one per path vertex); outside any scope they draw from a generator seeded by their wo and u.
// Scopes nest. No allocation: a thread-local pointer.
class MultiscatterWalkNumbers {
 public:
  explicit MultiscatterWalkNumbers(WalkNumbers* numbers);
  ~MultiscatterWalkNumbers();
  MultiscatterWalkNumbers(const MultiscatterWalkNumbers&) = delete;
  MultiscatterWalkNumbers& operator=(const MultiscatterWalkNumbers&) = delete;

  // This thread's numbers (null outside any scope).
  static WalkNumbers* current();
  // This thread's pointer itself, for a loop that sets it per path vertex and restores it
  // afterwards (a thread_local in a shared object costs a call per access).
  static WalkNumbers** thread_slot();

 private:
  WalkNumbers* previous_;
};

}  // namespace microfacet
}  // namespace bxdf

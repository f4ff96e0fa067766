// The multiscatter walks' numbers (microfacet/walk_numbers.h): Cycles' LCG draw for draw, the
// path's first facet replaced by the stratified sample, every later vertex shifted from it by
// Cycles' constant, the scope restored, and the walks inside a scope still Cycles' walks (their
// eval draws one walk from the numbers, in Cycles' pattern, and still averages to f).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "bxdf/microfacet/multiscatter_ggx.h"
#include "bxdf/microfacet/walk_numbers.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;
using namespace bxdf::microfacet;

namespace {

// Cycles 3.4, kernel/sample/lcg.h, written out: lcg_state_init(hash, offset, sample, scramble)
// = lcg_init(hash + offset + sample * scramble); lcg_init steps once; lcg_step_float steps and
// returns the state times 1 / 0xFFFFFFFF (as a float, 2^-32).
struct CyclesLcg {
  uint32_t state;
  explicit CyclesLcg(uint32_t seed) : state(1103515245u * seed + 12345u) {}
  uint32_t step() { return state = 1103515245u * state + 12345u; }
  float step_float() {
    return static_cast<float>(step()) * (1.0f / static_cast<float>(0xFFFFFFFFu));
  }
};

// The Cycles integer x whose float x · 2^-32 is u.
uint32_t integer_of(float u) {
  return static_cast<uint32_t>(static_cast<double>(u) * 4294967296.0);
}

}  // namespace

TEST(WalkNumbers, DrawCyclesLcgForEveryDraw) {
  for (uint32_t seed : {0u, 1u, 16u, 0x9e3779b9u, 0xffffffffu}) {
    WalkAnchor anchor;
    WalkNumbers numbers(seed, &anchor);
    CyclesLcg cycles(seed);
    for (int i = 0; i < 64; ++i)
      EXPECT_EQ(numbers.uniform(), cycles.step_float()) << seed << " " << i;
  }
}

TEST(WalkNumbers, FirstFacetOfAPathIsTheStratifiedSample) {
  WalkAnchor anchor;
  WalkNumbers numbers(1234u, &anchor);
  CyclesLcg cycles(1234u);
  EXPECT_EQ(numbers.uniform(), cycles.step_float());  // the walk's first height
  const Point2 u(0.3125f, 0.71875f);
  const Point2 facet = numbers.first_facet(u);
  EXPECT_EQ(facet.x, u.x);
  EXPECT_EQ(facet.y, u.y);
  EXPECT_EQ(anchor.position, 2u);  // y is the vertex's second draw, x its third
  cycles.step();
  cycles.step();
  // Past the facet the vertex draws Cycles' numbers again.
  for (int i = 0; i < 8; ++i) EXPECT_EQ(numbers.uniform(), cycles.step_float());
}

// Cycles seeds a path's later vertex 16 higher per bounce, so its draw n is the first vertex's
// shifted by a constant. With the first vertex's facet replaced by u, a later vertex's draws at
// those positions are u shifted by the same constant; its other draws are its own Cycles draws.
TEST(WalkNumbers, LaterVerticesKeepCyclesShiftFromTheFirstFacet) {
  const uint32_t seed = 0xb4bc3953u * 7u + 99u;
  for (uint32_t bounces : {1u, 2u, 5u}) {
    WalkAnchor anchor;
    WalkNumbers first(seed, &anchor);
    first.uniform();
    const Point2 u(0.123f, 0.877f);
    first.first_facet(u);

    WalkNumbers later(seed + 16u * bounces, &anchor);
    CyclesLcg cycles_first(seed), cycles_later(seed + 16u * bounces);
    uint32_t x_first[6], x_later[6];
    for (int i = 0; i < 6; ++i) {
      x_first[i] = cycles_first.step();
      x_later[i] = cycles_later.step();
    }
    EXPECT_EQ(later.uniform(), static_cast<float>(x_later[0]) * 0x1p-32f);  // draw 1: its own
    const Point2 facet = later.first_facet(Point2(0.5f, 0.5f));  // draws 2 (y) and 3 (x)
    const uint32_t want_y = integer_of(u.y) + (x_later[1] - x_first[1]);
    const uint32_t want_x = integer_of(u.x) + (x_later[2] - x_first[2]);
    EXPECT_EQ(facet.y, static_cast<float>(want_y) * 0x1p-32f);
    EXPECT_EQ(facet.x, static_cast<float>(want_x) * 0x1p-32f);
    for (int i = 3; i < 6; ++i)
      EXPECT_EQ(later.uniform(), static_cast<float>(x_later[i]) * 0x1p-32f);
  }
}

TEST(WalkNumbers, ScopesNestAndRestore) {
  EXPECT_EQ(MultiscatterWalkNumbers::current(), nullptr);
  WalkAnchor anchor;
  WalkNumbers a(1u, &anchor), b(2u, &anchor);
  {
    const MultiscatterWalkNumbers outer(&a);
    EXPECT_EQ(MultiscatterWalkNumbers::current(), &a);
    {
      const MultiscatterWalkNumbers inner(&b);
      EXPECT_EQ(MultiscatterWalkNumbers::current(), &b);
    }
    EXPECT_EQ(MultiscatterWalkNumbers::current(), &a);
  }
  EXPECT_EQ(MultiscatterWalkNumbers::current(), nullptr);
  EXPECT_EQ(*MultiscatterWalkNumbers::thread_slot(), nullptr);
}

// Inside a scope f's first walk draws from the vertex's numbers as Cycles' one eval walk does
// (a height, then a visible normal's two numbers per bounce: 1 + 3k draws, or none where the
// pair is refused), the same numbers give the same bits, and over many vertices (seeds) f
// still averages to the walk's expectation.
TEST(WalkNumbers, EvalInsideAScopeDrawsOneWalkFromTheNumbers) {
  MultiscatterSetup setup;
  setup.alpha_x = setup.alpha_y = 0.6f;
  setup.color = RGB(0.9f);
  const MultiscatterGGXReflection refl(setup);
  const Vec3 wo = normalize(Vec3(0.4f, 0.1f, 0.8f)), wi = normalize(Vec3(-0.6f, 0.3f, 0.5f));
  constexpr int kSeeds = 4000;
  double sum = 0.0;
  for (uint32_t seed = 1; seed <= kSeeds; ++seed) {
    WalkAnchor anchor;
    WalkNumbers numbers(seed * 0xb4bc3953u, &anchor);
    RGB f;
    {
      const MultiscatterWalkSalt salt(seed);
      const MultiscatterWalkNumbers scope(&numbers);
      f = refl.eval(wo, wi);
    }
    sum += f.r;
    if (seed <= 50) {
      WalkNumbers again(seed * 0xb4bc3953u, &anchor);
      RGB f_again;
      {
        const MultiscatterWalkSalt salt(seed);
        const MultiscatterWalkNumbers scope(&again);
        f_again = refl.eval(wo, wi);
      }
      EXPECT_EQ(f.r, f_again.r);
      // How many draws the walk took: the first count whose next draw is the one that follows.
      const float next = numbers.uniform();
      CyclesLcg cycles(seed * 0xb4bc3953u);
      int taken = -1;
      for (int k = 0; k <= 31 && taken < 0; ++k)
        if (cycles.step_float() == next) taken = k;
      ASSERT_GE(taken, 1);
      EXPECT_EQ(taken % 3, 1) << "seed " << seed;
    }
  }
  double long_sum = 0.0;
  PCG32 rng(77);
  constexpr int kLong = 200000;
  for (int k = 0; k < kLong; ++k) long_sum += refl.walk_f(wo, wi, rng).r;
  const double expectation = long_sum / kLong;
  EXPECT_NEAR(sum / kSeeds, expectation, 0.03 * expectation);
}

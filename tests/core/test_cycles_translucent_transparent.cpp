// cycles_translucent (Cycles' bsdf_translucent_eval: max(−N·L, 0)/π with N turned to the
// viewer) and cycles_transparent (a pass-through with weight = colour), against those formulas.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

TEST(CyclesTranslucent, MatchesCyclesFormulaOnBothFaces) {
  ParamSet p;
  p.set("color", RGBValue{0.9, 0.5, 0.1});
  const BxDFPtr m = make("cycles_translucent", p);
  PCG32 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 wo = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const Vec3 wi = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    // N turned towards the viewer: N = sign(wo.z) z; eval = max(−N·L, 0)/π = f cos θi.
    const double n_dot_l = (wo.z >= 0 ? 1.0 : -1.0) * wi.z;
    const double eval = std::max(-n_dot_l, 0.0) / M_PI;
    const double expected = eval > 0 ? 0.5 * eval / std::fabs(wi.z) : 0.0;
    EXPECT_NEAR(m->f(wo, wi).g, expected, 1e-6 * expected + 1e-9);
    EXPECT_NEAR(m->pdf(wo, wi), eval, 1e-6 * eval + 1e-9);  // Cycles' pdf = eval
  }
  EXPECT_TRUE(m->flags() & kTransmission);
  EXPECT_TRUE(m->flags() & kDiffuse);
}

TEST(CyclesTransparent, PassesStraightThroughWithTheColour) {
  ParamSet p;
  p.set("color", RGBValue{0.2, 0.6, 1.0});
  const BxDFPtr m = make("cycles_transparent", p);
  EXPECT_TRUE(m->is_delta());
  PCG32 rng(4);
  for (int i = 0; i < 100; ++i) {
    const Vec3 wo = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s.flags, uint32_t(kTransmission | kSpecular));
    EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(s.wi.y, -wo.y, 1e-6f);
    EXPECT_NEAR(s.wi.z, -wo.z, 1e-6f);
    const RGB weight = s.f * (std::fabs(s.wi.z) / s.pdf);
    EXPECT_NEAR(weight.r, 0.2f, 1e-6f);
    EXPECT_NEAR(weight.g, 0.6f, 1e-6f);
    EXPECT_NEAR(weight.b, 1.0f, 1e-6f);
    EXPECT_TRUE(m->f(wo, s.wi).is_black());
    EXPECT_EQ(m->pdf(wo, s.wi), 0.0f);
  }
}

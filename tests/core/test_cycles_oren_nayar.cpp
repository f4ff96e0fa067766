// cycles_oren_nayar against Cycles 3.4's definition, evaluated in double in the test:
// A = 1/(π + (π/2 − 2/3)σ), B = σA, s = ωi·ωo − cosθi cosθo, t = max(cosθi, cosθo) if s > 0
// else 1, f = color (A + B s/t).
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/cycles_oren_nayar.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

double cycles_oren_nayar_reference(double color, double roughness, const Vec3& wo, const Vec3& wi) {
  const double sigma = roughness;
  const double a = 1.0 / (M_PI + (M_PI / 2.0 - 2.0 / 3.0) * sigma);
  const double b = sigma * a;
  const double cos_i = wi.z, cos_o = wo.z;
  const double dot_io = static_cast<double>(wi.x) * wo.x + static_cast<double>(wi.y) * wo.y +
                        static_cast<double>(wi.z) * wo.z;
  const double s = dot_io - cos_i * cos_o;
  const double t = s > 0.0 ? std::max(cos_i, cos_o) : 1.0;
  return color * (a + b * s / t);
}

BxDFPtr make_con(double color, double roughness) {
  ParamSet p;
  p.set("color", color);
  p.set("roughness", roughness);
  return make("cycles_oren_nayar", p);
}

Vec3 random_upper(PCG32& rng) {
  for (;;) {
    const Vec3 w = sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
    if (w.z > 1e-3f) return w;
  }
}

}  // namespace

TEST(CyclesOrenNayar, MatchesCyclesDefinition) {
  PCG32 rng(17);
  for (double roughness : {0.0, 0.25, 0.5, 1.0}) {
    BxDFPtr m = make_con(0.8, roughness);
    int negative_s = 0;
    for (int i = 0; i < 300; ++i) {
      const Vec3 wo = random_upper(rng), wi = random_upper(rng);
      negative_s += (wo.x * wi.x + wo.y * wi.y) < 0.0f;
      const double expected = cycles_oren_nayar_reference(0.8, roughness, wo, wi);
      EXPECT_NEAR(m->f(wo, wi).g, expected, 1e-5 * expected + 1e-7)
          << "roughness " << roughness << " wo.z " << wo.z << " wi.z " << wi.z;
    }
    EXPECT_GT(negative_s, 50);  // both branches of t were exercised
  }
}

TEST(CyclesOrenNayar, KnownValues) {
  // Roughness 0 is Lambert.
  EXPECT_NEAR(make_con(0.5, 0.0)->f(Vec3(0.3f, 0.2f, 0.9f), Vec3(-0.5f, 0.1f, 0.4f)).r, 0.5 / M_PI,
              1e-7);
  // Roughness 1, both at the normal: s = 0, f = A = 1/(π + π/2 − 2/3) ≈ 0.247174.
  EXPECT_NEAR(make_con(1.0, 1.0)->f(Vec3(0, 0, 1), Vec3(0, 0, 1)).r, 0.247174, 1e-6);
  // Roughness 1, opposite azimuths at grazing: s → −1 and f → A − B = 0, never negative.
  const RGB f = make_con(1.0, 1.0)->f(Vec3(1.0f, 0.0f, 1e-4f), Vec3(-1.0f, 0.0f, 1e-4f));
  EXPECT_GE(f.r, 0.0f);
  EXPECT_LT(f.r, 1e-4f);
}

TEST(CyclesOrenNayar, IsTwoSidedAndReflectionOnly) {
  BxDFPtr m = make_con(0.9, 0.7);
  PCG32 rng(23);
  for (int i = 0; i < 50; ++i) {
    const Vec3 wo = random_upper(rng), wi = random_upper(rng);
    const float f = m->f(wo, wi).r;
    EXPECT_NEAR(m->f(-wo, -wi).r, f, 1e-7f);
    EXPECT_NEAR(m->f(wi, wo).r, f, 1e-6f * f);
    EXPECT_EQ(m->f(wo, -wi).r, 0.0f);
  }
}

TEST(CyclesOrenNayar, CosineSamplingAgreesWithPdfAndF) {
  BxDFPtr m = make_con(0.8, 0.6);
  const Vec3 wo(-0.3f, 0.6f, 0.5f);
  PCG32 rng(29);
  for (int i = 0; i < 100; ++i) {
    const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    ASSERT_TRUE(s.valid());
    EXPECT_GT(s.wi.z, 0.0f);
    EXPECT_NEAR(s.pdf, s.wi.z / M_PI, 1e-6);
    EXPECT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-6);
    EXPECT_NEAR(s.f.r, m->f(wo, s.wi).r, 1e-6);
  }
}

TEST(CyclesOrenNayar, RefusesRoughnessAboveOne) {
  try {
    make_con(0.5, 1.5);
    FAIL() << "accepted roughness 1.5";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'roughness'"), std::string::npos) << e.what();
  }
}

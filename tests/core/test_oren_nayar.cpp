// Oren–Nayar (the seed's form) against an evaluation written with explicit angles:
// θ = acos(z), φ = atan2(y, x), α = max(θi, θo), β = min(θi, θo), in double precision.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/oren_nayar.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

double oren_nayar_by_angles(double r, double sigma_deg, const Vec3& wo, const Vec3& wi) {
  const double sigma = sigma_deg * M_PI / 180.0, s2 = sigma * sigma;
  const double a = 1.0 - s2 / (2.0 * (s2 + 0.33));
  const double b = 0.45 * s2 / (s2 + 0.09);
  const double theta_i = std::acos(static_cast<double>(wi.z)),
               theta_o = std::acos(static_cast<double>(wo.z));
  const double phi_i = std::atan2(wi.y, wi.x), phi_o = std::atan2(wo.y, wo.x);
  const double alpha = std::max(theta_i, theta_o), beta = std::min(theta_i, theta_o);
  const double max_cos = std::max(0.0, std::cos(phi_i - phi_o));
  return r / M_PI * (a + b * max_cos * std::sin(alpha) * std::tan(beta));
}

BxDFPtr make_on(double r, double sigma) {
  ParamSet p;
  p.set("reflectance", r);
  p.set("sigma", sigma);
  return make("oren_nayar", p);
}

// Uniform direction on the upper hemisphere, kept away from the pole (where φ is undefined and
// the model deliberately drops the cos(φi − φo) term).
Vec3 random_upper(PCG32& rng) {
  for (;;) {
    const Vec3 w = sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
    if (w.z < 0.999f && w.z > 1e-3f) return w;
  }
}

}  // namespace

TEST(OrenNayar, MatchesTheFormulaWrittenWithAngles) {
  PCG32 rng(7);
  for (double sigma : {5.0, 20.0, 45.0, 90.0}) {
    BxDFPtr m = make_on(0.7, sigma);
    for (int i = 0; i < 200; ++i) {
      const Vec3 wo = random_upper(rng), wi = random_upper(rng);
      const double expected = oren_nayar_by_angles(0.7, sigma, wo, wi);
      const RGB f = m->f(wo, wi);
      EXPECT_NEAR(f.r, expected, 2e-5 * expected) << sigma << " wo.z " << wo.z << " wi.z " << wi.z;
      EXPECT_EQ(f.r, f.b);
    }
  }
}

TEST(OrenNayar, BackScatteringIsBrighterThanForwardScattering) {
  BxDFPtr m = make_on(0.5, 30.0);
  const Vec3 wo(std::sin(1.0f), 0.0f, std::cos(1.0f));
  const Vec3 back(std::sin(0.8f), 0.0f, std::cos(0.8f));      // same azimuth
  const Vec3 forward(-std::sin(0.8f), 0.0f, std::cos(0.8f));  // opposite azimuth
  EXPECT_GT(m->f(wo, back).r, 1.2f * m->f(wo, forward).r);
  // Opposite azimuths: max(0, cos(φi − φo)) = 0, leaving A R/π.
  const float a =
      1.0f - (radians(30.0f) * radians(30.0f)) / (2.0f * (radians(30.0f) * radians(30.0f) + 0.33f));
  EXPECT_NEAR(m->f(wo, forward).r, a * 0.5 / M_PI, 1e-6);
}

TEST(OrenNayar, SigmaZeroIsLambertian) {
  BxDFPtr m = make_on(0.6, 0.0);
  PCG32 rng(3);
  for (int i = 0; i < 20; ++i)
    EXPECT_NEAR(m->f(random_upper(rng), random_upper(rng)).g, 0.6 / M_PI, 1e-7);
}

TEST(OrenNayar, IsTwoSidedReciprocalAndReflectionOnly) {
  BxDFPtr m = make_on(0.8, 25.0);
  PCG32 rng(11);
  for (int i = 0; i < 50; ++i) {
    const Vec3 wo = random_upper(rng), wi = random_upper(rng);
    const float f = m->f(wo, wi).r;
    EXPECT_EQ(m->f(-wo, -wi).r, f);
    EXPECT_NEAR(m->f(wi, wo).r, f, 1e-6f * f);
    EXPECT_EQ(m->f(wo, -wi).r, 0.0f);
    EXPECT_EQ(m->pdf(wo, -wi), 0.0f);
  }
}

TEST(OrenNayar, PoleAndGrazingStayFinite) {
  BxDFPtr m = make_on(0.8, 90.0);
  const float a = static_cast<const OrenNayar&>(*m).a();
  // At the pole sin α tan β = 0 (β = 0), whatever φ: f = A R/π.
  EXPECT_NEAR(m->f(Vec3(0, 0, 1), Vec3(0.6f, 0.0f, 0.8f)).r, a * 0.8 / M_PI, 1e-7);
  EXPECT_NEAR(m->f(Vec3(0, 0, 1), Vec3(0, 0, 1)).r, a * 0.8 / M_PI, 1e-7);
  // Both near grazing in the same azimuth: tan β is large but finite.
  const Vec3 g1(1.0f, 0.0f, 1e-6f), g2(1.0f, 1e-3f, 2e-6f);
  const RGB f = m->f(g1, g2);
  EXPECT_TRUE(std::isfinite(f.r));
  EXPECT_GT(f.r, 0.0f);
  EXPECT_TRUE(m->f(Vec3(1, 0, 0), Vec3(0, 0, 1)).is_black());  // exactly grazing wo
}

TEST(OrenNayar, CosineSamplingAgreesWithPdfAndF) {
  BxDFPtr m = make_on(0.8, 30.0);
  const Vec3 wo(0.5f, -0.2f, -0.7f);  // from below: samples stay below
  PCG32 rng(5);
  for (int i = 0; i < 100; ++i) {
    const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    ASSERT_TRUE(s.valid());
    EXPECT_LT(s.wi.z, 0.0f);
    EXPECT_NEAR(s.pdf, std::fabs(s.wi.z) / M_PI, 1e-6);
    EXPECT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-6);
    EXPECT_NEAR(s.f.r, m->f(wo, s.wi).r, 1e-6);
  }
}

TEST(OrenNayar, RefusesSigmaOutsideZeroToNinetyDegrees) {
  for (double bad : {-1.0, 90.5}) {
    try {
      make_on(0.5, bad);
      FAIL() << "accepted sigma " << bad;
    } catch (const ParameterError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("'sigma'"), std::string::npos) << msg;
      EXPECT_NE(msg.find("[0, 90] degrees"), std::string::npos) << msg;
    }
  }
}

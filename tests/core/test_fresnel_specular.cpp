// fresnel_specular (smooth glass): reflects with probability F and pdf F, refracts with
// probability 1 − F and pdf 1 − F; directions by mirror and Snell's law; total internal
// reflection always reflects. F and the expected weights are computed in the test.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/fresnel_specular.h"
#include "bxdf/registry.h"

using namespace bxdf;

namespace {

double fresnel_reference(double cos_i, double eta_from, double eta_to) {
  const double sin_t = eta_from / eta_to * std::sqrt(1.0 - cos_i * cos_i);
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double r_par = (eta_to * cos_i - eta_from * cos_t) / (eta_to * cos_i + eta_from * cos_t);
  const double r_perp = (eta_from * cos_i - eta_to * cos_t) / (eta_from * cos_i + eta_to * cos_t);
  return 0.5 * (r_par * r_par + r_perp * r_perp);
}

const RGBValue kR = {0.9, 0.8, 0.7}, kT = {0.6, 0.5, 0.4};

BxDFPtr make_glass(double eta_i, double eta_t) {
  ParamSet p;
  p.set("reflectance", kR);
  p.set("transmittance", kT);
  p.set("eta_i", eta_i);
  p.set("eta_t", eta_t);
  return make("fresnel_specular", p);
}

Vec3 direction(double theta, double phi, double sign) {
  return Vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
              static_cast<float>(std::sin(theta) * std::sin(phi)),
              static_cast<float>(sign * std::cos(theta)));
}

}  // namespace

TEST(FresnelSpecular, ChoosesReflectionWithProbabilityF) {
  BxDFPtr m = make_glass(1.0, 1.5);
  EXPECT_EQ(flags_to_string(m->flags()), "reflection|transmission|specular");
  for (double sign : {+1.0, -1.0}) {
    const double eta_from = sign > 0 ? 1.0 : 1.5, eta_to = sign > 0 ? 1.5 : 1.0;
    for (double theta : {0.0, 0.4, 0.7, 1.3}) {
      const Vec3 wo = direction(theta, 1.1, sign);
      const double fresnel = fresnel_reference(std::cos(theta), eta_from, eta_to);
      if (fresnel >= 1.0) continue;  // TIR: tested below
      // Just below F: reflection.
      BxDFSample s = m->sample_f(wo, Point2(static_cast<float>(fresnel) * 0.999f, 0.5f));
      ASSERT_TRUE(s.valid());
      EXPECT_EQ(s.flags, static_cast<uint32_t>(kReflection | kSpecular));
      EXPECT_EQ(s.pdf, 1.0f);  // delta lobe: choice probability folded into f
      EXPECT_NEAR(s.wi.x, -wo.x, 1e-6);
      EXPECT_NEAR(s.wi.y, -wo.y, 1e-6);
      EXPECT_NEAR(s.wi.z, wo.z, 1e-6);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(s.f[c], kR[c] / std::cos(theta), 2e-6 * s.f[c] + 1e-7);
      // Just above F: refraction by Snell's law, weighted T (1 − F)(η_wo/η_wi)²/|cos θi|.
      s = m->sample_f(wo, Point2(static_cast<float>(fresnel) * 1.001f + 1e-6f, 0.5f));
      ASSERT_TRUE(s.valid());
      EXPECT_EQ(s.flags, static_cast<uint32_t>(kTransmission | kSpecular));
      EXPECT_EQ(s.pdf, 1.0f);
      const double theta_t = std::asin(eta_from / eta_to * std::sin(theta));
      const Vec3 expected_wi = direction(theta_t, 1.1 + M_PI, -sign);
      EXPECT_NEAR(s.wi.x, expected_wi.x, 1e-6);
      EXPECT_NEAR(s.wi.y, expected_wi.y, 1e-6);
      EXPECT_NEAR(s.wi.z, expected_wi.z, 1e-6);
      const double scale = (eta_from / eta_to) * (eta_from / eta_to);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(s.f[c], kT[c] * scale / std::cos(theta_t), 2e-6 * s.f[c]);
    }
  }
}

TEST(FresnelSpecular, ReflectedFractionOverUniformUIsF) {
  BxDFPtr m = make_glass(1.0, 1.5);
  const double theta = 1.2;
  const double fresnel = fresnel_reference(std::cos(theta), 1.0, 1.5);
  const int n = 1000;
  int reflected = 0;
  for (int i = 0; i < n; ++i) {
    const BxDFSample s = m->sample_f(direction(theta, 0.0, 1.0), Point2((i + 0.5f) / n, 0.5f));
    reflected += s.wi.z > 0.0f;
  }
  EXPECT_NEAR(reflected / static_cast<double>(n), fresnel, 1.0 / n);
  // Normal incidence on 1.5 reflects 4 %.
  EXPECT_FALSE(m->sample_f(Vec3(0, 0, 1), Point2(0.041f, 0.5f)).wi.z > 0.0f);
  EXPECT_TRUE(m->sample_f(Vec3(0, 0, 1), Point2(0.039f, 0.5f)).wi.z > 0.0f);
}

TEST(FresnelSpecular, TotalInternalReflectionAlwaysReflects) {
  BxDFPtr m = make_glass(1.0, 1.5);
  const double critical = std::asin(1.0 / 1.5);
  for (double theta : {critical + 0.01, 1.0, 1.5}) {
    const Vec3 wo = direction(theta, 0.4, -1.0);  // inside the glass
    for (float u : {0.0f, 0.5f, 0.9999f}) {
      const BxDFSample s = m->sample_f(wo, Point2(u, 0.5f));
      ASSERT_TRUE(s.valid());
      EXPECT_EQ(s.flags, static_cast<uint32_t>(kReflection | kSpecular));
      EXPECT_EQ(s.pdf, 1.0f);
      EXPECT_LT(s.wi.z, 0.0f);
      EXPECT_NEAR(s.f.g * std::fabs(s.wi.z), kR[1], 1e-6);
    }
  }
}

TEST(FresnelSpecular, ExpectedWeightIsFRPlusOneMinusFScaledT) {
  // E[f |cos θi| / pdf] over u = F R + (1 − F) T (η_wo/η_wi)²: each branch's weight is exact, so
  // the stratified estimate only carries the noise of the one column of strata that straddles F.
  BxDFPtr m = make_glass(1.0, 1.0);  // matched indices: F = 0, everything passes
  EXPECT_NEAR(m->rho_hd(direction(0.5, 0.0, 1.0), 256).r, kT[0], 1e-6);
  BxDFPtr glass = make_glass(1.0, 1.5);
  const double theta = 1.0, fresnel = fresnel_reference(std::cos(theta), 1.0, 1.5);
  const RGB rho = glass->rho_hd(direction(theta, 0.0, 1.0), 4096);
  EXPECT_NEAR(rho.r, fresnel * kR[0] + (1.0 - fresnel) * kT[0] / 2.25, 2e-3);
}

TEST(FresnelSpecular, DeltaLobesHaveNoValueOrDensity) {
  BxDFPtr m = make_glass(1.0, 1.5);
  const Vec3 wo = direction(0.5, 0.0, 1.0);
  const BxDFSample s = m->sample_f(wo, Point2(0.9f, 0.5f));
  EXPECT_TRUE(m->f(wo, s.wi).is_black());
  EXPECT_EQ(m->pdf(wo, s.wi), 0.0f);
  EXPECT_FALSE(m->sample_f(Vec3(1, 0, 0), Point2(0.9f, 0.5f)).valid());
}

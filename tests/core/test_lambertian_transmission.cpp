// Lambertian transmission: f = T/π across the surface only, cosine sampling on the far side,
// and ρ = T both analytically and by Monte Carlo.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/lambertian_transmission.h"
#include "bxdf/registry.h"

using namespace bxdf;

namespace {

BxDFPtr make_lt(const RGB& t) {
  ParamSet p;
  p.set("transmittance", RGBValue{t.r, t.g, t.b});
  return make("lambertian_transmission", p);
}

}  // namespace

TEST(LambertianTransmission, IsTOverPiAcrossTheSurfaceAndZeroOnTheSameSide) {
  const RGB t(0.2f, 0.5f, 0.9f);
  BxDFPtr m = make_lt(t);
  EXPECT_EQ(flags_to_string(m->flags()), "transmission|diffuse");
  const Vec3 up(0.3f, -0.2f, 0.9f), down(-0.5f, 0.1f, -0.4f);
  for (const auto& [wo, wi] : {std::pair{up, down}, std::pair{down, up}}) {
    const RGB f = m->f(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], t[c] / M_PI, 1e-7);
  }
  EXPECT_TRUE(m->f(up, up).is_black());
  EXPECT_TRUE(m->f(down, down).is_black());
  EXPECT_TRUE(m->f(up, Vec3(1, 0, 0)).is_black());  // grazing wi: on neither side
  EXPECT_EQ(m->pdf(up, up), 0.0f);
}

TEST(LambertianTransmission, SamplesTheCosineLobeOnTheFarSide) {
  BxDFPtr m = make_lt(RGB(0.7f));
  for (const Vec3& wo : {Vec3(0.2f, 0.1f, 0.8f), Vec3(0.4f, -0.3f, -0.5f)}) {
    for (float u : {0.05f, 0.3f, 0.55f, 0.95f}) {
      const BxDFSample s = m->sample_f(wo, Point2(u, 1.0f - u));
      ASSERT_TRUE(s.valid());
      EXPECT_LT(s.wi.z * wo.z, 0.0f);
      EXPECT_NEAR(s.pdf, std::fabs(s.wi.z) / M_PI, 1e-6);
      EXPECT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-6);
      EXPECT_NEAR(s.f.g, 0.7 / M_PI, 1e-7);
      EXPECT_EQ(s.flags, static_cast<uint32_t>(kTransmission | kDiffuse));
    }
  }
  EXPECT_FALSE(m->sample_f(Vec3(1, 0, 0), Point2(0.5f, 0.5f)).valid());
}

TEST(LambertianTransmission, RhoIsTheTransmittance) {
  const RGB t(0.1f, 0.6f, 1.0f);
  BxDFPtr m = make_lt(t);
  const Vec3 wo(0.3f, 0.4f, 0.5f);
  const RGB exact_hd = m->rho_hd(wo, 16), exact_hh = m->rho_hh(16);
  // The generic Monte Carlo estimators (bypassing the analytic overrides) agree.
  const RGB mc_hd = m->BxDF::rho_hd(wo, 1024), mc_hh = m->BxDF::rho_hh(4096);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(exact_hd[c], t[c]);
    EXPECT_EQ(exact_hh[c], t[c]);
    EXPECT_NEAR(mc_hd[c], t[c], 1e-5);
    EXPECT_NEAR(mc_hh[c], t[c], 0.02 * t[c]);
  }
}

TEST(LambertianTransmission, RefusesTransmittanceAboveOne) {
  ParamSet p;
  p.set("transmittance", 1.2);
  try {
    make("lambertian_transmission", p);
    FAIL() << "accepted transmittance 1.2";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'transmittance'"), std::string::npos) << e.what();
  }
}

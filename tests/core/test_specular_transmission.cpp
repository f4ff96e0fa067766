// specular_transmission: Snell's-law directions, the weight T (1 − F)(η_wo/η_wi)²/|cos θi| on
// both sides of the interface, no sample under total internal reflection. F, directions and
// weights are computed independently in the test.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/specular_transmission.h"
#include "bxdf/registry.h"

using namespace bxdf;

namespace {

// Unpolarised Fresnel reflectance from the angle forms (0 < θi < critical angle).
double fresnel_by_angles(double theta_i, double eta_from, double eta_to) {
  const double theta_t = std::asin(eta_from / eta_to * std::sin(theta_i));
  const double r_perp = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
  const double r_par = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
  return 0.5 * (r_perp * r_perp + r_par * r_par);
}

BxDFPtr make_st(const RGBValue& t, double eta_i, double eta_t) {
  ParamSet p;
  p.set("transmittance", t);
  p.set("eta_i", eta_i);
  p.set("eta_t", eta_t);
  return make("specular_transmission", p);
}

// wo at polar angle theta and azimuth phi, on the side given by sign.
Vec3 direction(double theta, double phi, double sign) {
  return Vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
              static_cast<float>(std::sin(theta) * std::sin(phi)),
              static_cast<float>(sign * std::cos(theta)));
}

// Expects the refracted direction and weight for wo (theta, phi) on side `sign` with indices
// eta_from on wo's side and eta_to on the other.
void expect_refraction(const BxDF& m, const RGBValue& t, double theta, double phi, double sign,
                       double eta_from, double eta_to) {
  const Vec3 wo = direction(theta, phi, sign);
  const double theta_t = std::asin(eta_from / eta_to * std::sin(theta));
  const Vec3 expected_wi = direction(theta_t, phi + M_PI, -sign);  // across, on the far azimuth
  const BxDFSample s = m.sample_f(wo, Point2(0.5f, 0.5f));
  ASSERT_TRUE(s.valid()) << theta;
  EXPECT_NEAR(s.wi.x, expected_wi.x, 1e-6);
  EXPECT_NEAR(s.wi.y, expected_wi.y, 1e-6);
  EXPECT_NEAR(s.wi.z, expected_wi.z, 1e-6);
  EXPECT_EQ(s.pdf, 1.0f);
  EXPECT_EQ(s.flags, static_cast<uint32_t>(kTransmission | kSpecular));
  const double fresnel = theta == 0.0 ? std::pow((eta_to - eta_from) / (eta_to + eta_from), 2)
                                      : fresnel_by_angles(theta, eta_from, eta_to);
  const double scale = (eta_from / eta_to) * (eta_from / eta_to);
  for (int c = 0; c < 3; ++c) {
    const double expected = t[c] * (1.0 - fresnel) * scale / std::cos(theta_t);
    EXPECT_NEAR(s.f[c], expected, 2e-6 * expected) << "theta " << theta << " channel " << c;
  }
  EXPECT_TRUE(m.f(wo, s.wi).is_black());
  EXPECT_EQ(m.pdf(wo, s.wi), 0.0f);
}

}  // namespace

TEST(SpecularTransmission, EntersFromAboveBySnellsLaw) {
  const RGBValue t = {1.0, 0.7, 0.4};
  BxDFPtr m = make_st(t, 1.0, 1.5);
  for (double theta : {0.0, 0.3, 0.9, 1.4}) expect_refraction(*m, t, theta, 0.7, +1.0, 1.0, 1.5);
}

TEST(SpecularTransmission, ExitsFromBelowWithTheIndicesSwapped) {
  const RGBValue t = {1.0, 0.7, 0.4};
  BxDFPtr m = make_st(t, 1.0, 1.5);
  for (double theta : {0.0, 0.3, 0.7}) expect_refraction(*m, t, theta, -2.0, -1.0, 1.5, 1.0);
  // Radiance leaving the glass into air grows by 1.5² (beam widens): weight > 1 near normal.
  const BxDFSample s = m->sample_f(Vec3(0, 0, -1), Point2(0.5f, 0.5f));
  EXPECT_NEAR(s.f.r, (1.0 - 0.04) * 2.25, 1e-5);
}

TEST(SpecularTransmission, TotalInternalReflectionGivesNoSample) {
  BxDFPtr m = make_st({1, 1, 1}, 1.0, 1.5);
  const double critical = std::asin(1.0 / 1.5);
  for (double theta : {critical + 0.01, 1.0, 1.5})
    EXPECT_FALSE(m->sample_f(direction(theta, 0.3, -1.0), Point2(0.5f, 0.5f)).valid()) << theta;
  EXPECT_TRUE(m->sample_f(direction(critical - 0.01, 0.3, -1.0), Point2(0.5f, 0.5f)).valid());
  EXPECT_FALSE(m->sample_f(Vec3(1, 0, 0), Point2(0.5f, 0.5f)).valid());  // grazing
}

TEST(SpecularTransmission, MatchedIndicesPassStraightThrough) {
  BxDFPtr m = make_st({0.5, 0.5, 0.5}, 1.33, 1.33);
  const Vec3 wo = normalize(Vec3(0.4f, -0.2f, 0.7f));
  const BxDFSample s = m->sample_f(wo, Point2(0.1f, 0.9f));
  ASSERT_TRUE(s.valid());
  EXPECT_NEAR(s.wi.x, -wo.x, 1e-6);
  EXPECT_NEAR(s.wi.y, -wo.y, 1e-6);
  EXPECT_NEAR(s.wi.z, -wo.z, 1e-6);
  EXPECT_NEAR(s.f.r * std::fabs(s.wi.z), 0.5, 1e-6);  // F = 0, scale 1
}

TEST(SpecularTransmission, RefusesNonPositiveIndex) {
  try {
    make_st({1, 1, 1}, 1.0, 0.0);
    FAIL() << "accepted eta_t 0";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'eta_t'"), std::string::npos) << e.what();
  }
}

// The weight near the critical angle: wo grazing on the side of lower index refracts to just
// inside the critical angle, where cos θ of the far side from sqrt(1 − sin²θ) has lost digits.
// The reproducer (found against pbrt-v3, 3.5e-4 relative) and a sweep of grazing wo,
// against the weight computed in double from wo's own cosine.
TEST(SpecularTransmission, WeightIsAccurateForGrazingIncidenceFromTheLowerIndex) {
  BxDFPtr m = make_st({1, 1, 1}, 1.5, 1.0);  // glass above, air below: wo below is in air
  auto expect_accurate = [&](const Vec3& wo_in) {
    const double len = std::sqrt(double(wo_in.x) * wo_in.x + double(wo_in.y) * wo_in.y +
                                 double(wo_in.z) * wo_in.z);
    const double cos_o = std::fabs(wo_in.z) / len;  // in air, index 1
    const double sin_t = std::sqrt(1.0 - cos_o * cos_o) / 1.5;
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);  // in glass: well conditioned
    const double r_perp = (cos_o - 1.5 * cos_t) / (cos_o + 1.5 * cos_t);
    const double r_par = (1.5 * cos_o - cos_t) / (1.5 * cos_o + cos_t);
    const double fresnel = 0.5 * (r_perp * r_perp + r_par * r_par);
    const double expected = (1.0 - fresnel) / (1.5 * 1.5) / cos_t;
    const BxDFSample s = m->sample_f(wo_in, Point2(0.2770817f, 0.6741343f));
    ASSERT_TRUE(s.valid());
    EXPECT_NEAR(s.f.r, expected, 2e-6 * expected) << "cos θo " << cos_o;
  };
  expect_accurate(Vec3(-0.6069942f, 0.7946025f, -0.01284335f));
  for (double cos_o : {1e-2, 3e-3, 1e-3, 3e-4})
    expect_accurate(direction(std::acos(cos_o), 0.4, -1.0));
}

// microfacet_transmission (rough dielectric, Walter 2007 in radiance form): Walter's formula
// evaluated here, the generalised reciprocity f(ωo, ωi)/ηo² = f(ωi, ωo)/ηi², refraction of the
// sampled directions, the smooth limit's (ηo/ηi)² (1 − F) throughput, and the parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bxdf/fresnel.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;

BxDFPtr make_rough_glass(const std::string& distribution, double ax, double ay, double eta_i,
                         double eta_t, double transmittance = 1.0) {
  ParamSet p;
  p.set("transmittance", transmittance);
  p.set("distribution", distribution);
  p.set("alpha_x", ax);
  p.set("alpha_y", ay);
  p.set("eta_i", eta_i);
  p.set("eta_t", eta_t);
  return make("microfacet_transmission", p);
}

Vec3 random_direction(PCG32& rng, bool upper) {
  const double z = 0.02 + 0.98 * rng.uniform_double();
  const double r = std::sqrt(1.0 - z * z), phi = 2.0 * kPiD * rng.uniform_double();
  return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(upper ? z : -z));
}

struct Case {
  std::string distribution;
  double ax, ay, eta_i, eta_t;
};
const Case kCases[] = {{"ggx", 0.3, 0.3, 1.0, 1.5},
                       {"ggx", 0.1, 0.6, 1.0, 1.33},
                       {"beckmann", 0.4, 0.4, 1.0, 1.5},
                       {"beckmann", 0.5, 0.15, 1.5, 1.0},
                       {"ggx", 0.25, 0.25, 2.4, 1.2}};

// Walter et al. 2007, eq. 21 with the radiance factor ηo², GGX D and height-correlated Smith G,
// all in double. eta_o is the index on wo's side.
double walter_ggx(const Vec3& wo_f, const Vec3& wi_f, double alpha, double eta_o, double eta_i) {
  const double wo[3] = {wo_f.x, wo_f.y, wo_f.z}, wi[3] = {wi_f.x, wi_f.y, wi_f.z};
  double h[3];
  for (int c = 0; c < 3; ++c) h[c] = -(eta_o * wo[c] + eta_i * wi[c]);
  const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  for (double& c : h) c /= len;
  if (h[2] < 0)  // microfacet normals point out of the surface
    for (double& c : h) c = -c;
  const double o_h = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
  const double i_h = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
  // Walter's χ⁺(v·m / v·n): each direction sees the facet from its own side of the surface.
  if (o_h * wo[2] <= 0 || i_h * wi[2] <= 0) return 0;
  const double cos_h = std::fabs(h[2]), tan2_h = (1 - cos_h * cos_h) / (cos_h * cos_h);
  const double a2 = alpha * alpha;
  const double D = a2 / (kPiD * std::pow(cos_h, 4) * (a2 + tan2_h) * (a2 + tan2_h));
  auto lambda = [&](const double* w) {
    const double t2 = (1 - w[2] * w[2]) / (w[2] * w[2]);
    return (-1 + std::sqrt(1 + a2 * t2)) / 2;
  };
  const double G = 1 / (1 + lambda(wo) + lambda(wi));
  const double F = fresnel_dielectric(float(std::fabs(o_h)), float(eta_o), float(eta_i));
  const double denom = eta_o * o_h + eta_i * i_h;
  return (1 - F) * D * G * std::fabs(o_h * i_h) * eta_o * eta_o /
         (std::fabs(wo[2] * wi[2]) * denom * denom);
}

}  // namespace

TEST(MicrofacetTransmission, MatchesWaltersFormula) {
  PCG32 rng(21);
  for (const double eta_t : {1.5, 0.7}) {
    const BxDFPtr m = make_rough_glass("ggx", 0.35, 0.35, 1.0, eta_t, 0.8);
    int nonzero = 0;
    for (int i = 0; i < 2000; ++i) {
      const bool up = i % 2;
      const Vec3 wo = random_direction(rng, up), wi = random_direction(rng, !up);
      const double eta_o = up ? 1.0 : eta_t, eta_i = up ? eta_t : 1.0;
      const double expected = 0.8 * walter_ggx(wo, wi, 0.35, eta_o, eta_i);
      nonzero += expected > 1e-3;
      EXPECT_NEAR(m->f(wo, wi).b, expected, 2e-4 * expected + 1e-6)
          << eta_t << " " << wo.z << " " << wi.z;
    }
    EXPECT_GT(nonzero, 300);
  }
}

TEST(MicrofacetTransmission, GeneralisedReciprocity) {
  // Radiance BTDF: f(ωo, ωi)/η(ωo)² = f(ωi, ωo)/η(ωi)², with η(ω) the index on ω's side
  // (eta_i above the surface, eta_t below).
  PCG32 rng(23);
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.distribution + " " + std::to_string(c.eta_i) + " " + std::to_string(c.eta_t));
    const BxDFPtr m = make_rough_glass(c.distribution, c.ax, c.ay, c.eta_i, c.eta_t);
    int nonzero = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 wo = random_direction(rng, true), wi = random_direction(rng, false);
      const double forward = m->f(wo, wi).r / (c.eta_i * c.eta_i);
      const double backward = m->f(wi, wo).r / (c.eta_t * c.eta_t);
      nonzero += forward > 1e-4;
      EXPECT_NEAR(forward, backward, 1e-4 * forward + 1e-7);
      // Transmission only.
      EXPECT_EQ(m->f(wo, Vec3(wi.x, wi.y, -wi.z)).r, 0.0f);
      EXPECT_EQ(m->pdf(wo, Vec3(wi.x, wi.y, -wi.z)), 0.0f);
    }
    EXPECT_GT(nonzero, 100);
    // The importance (adjoint) form would have the ratio of the indices squared instead.
    if (c.eta_i != c.eta_t) {
      const Vec3 wo(0.2f, 0.1f, 0.9746794f), wi(-0.15f, -0.05f, -0.9874209f);
      EXPECT_GT(std::fabs(m->f(wo, wi).r - m->f(wi, wo).r), 1e-3 * m->f(wo, wi).r);
    }
  }
}

TEST(MicrofacetTransmission, SampledDirectionsRefract) {
  PCG32 rng(29);
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.distribution + " " + std::to_string(c.eta_i) + " " + std::to_string(c.eta_t));
    const BxDFPtr m = make_rough_glass(c.distribution, c.ax, c.ay, c.eta_i, c.eta_t);
    int valid = 0;
    for (int i = 0; i < 2000; ++i) {
      const bool up = i % 2;
      const Vec3 wo = random_direction(rng, up);
      const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
      if (!s.valid()) continue;
      ++valid;
      EXPECT_LT(s.wi.z * wo.z, 0.0f);  // through the surface
      // wi is wo refracted about the microfacet normal m ∝ ηo ωo + ηi ωi: Snell's law holds
      // about m, and wo and wi lie on opposite sides of the facet.
      const float eta_o = float(up ? c.eta_i : c.eta_t), eta_i = float(up ? c.eta_t : c.eta_i);
      const Vec3 mh = normalize(wo * eta_o + s.wi * eta_i);
      const float cos_o = dot(wo, mh), cos_i = dot(s.wi, mh);
      EXPECT_LT(cos_o * cos_i, 0.0f);
      const float sin_o = std::sqrt(std::max(0.0f, 1 - cos_o * cos_o));
      const float sin_i = std::sqrt(std::max(0.0f, 1 - cos_i * cos_i));
      EXPECT_NEAR(eta_o * sin_o, eta_i * sin_i, 2e-3f);
      // ... and cos θ about m follows from Snell too (the other root would be a reflection).
      EXPECT_NEAR(std::fabs(cos_i),
                  std::sqrt(std::max(0.0f, 1 - (eta_o / eta_i) * (eta_o / eta_i) * sin_o * sin_o)),
                  2e-3f);
      // The returned pdf and f are those of pdf() and f() at the sampled direction.
      EXPECT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-3f * s.pdf);
      EXPECT_NEAR(s.f.r, m->f(wo, s.wi).r, 1e-3f * s.f.r);
    }
    EXPECT_GT(valid, 1000);
  }
}

TEST(MicrofacetTransmission, SmoothLimitIsSnellsLaw) {
  // α at its floor (1e-4): samples are the Snell refraction about the geometric normal. All of
  // them for Beckmann; GGX's heavy tail (P(slope > kα) = 1/(1 + k²)) lets ~1% stray further.
  PCG32 rng(31);
  for (const std::string distribution : {"beckmann", "ggx"}) {
    const BxDFPtr m = make_rough_glass(distribution, 1e-4, 1e-4, 1.0, 1.5);
    for (const bool up : {true, false}) {
      const double theta_o = 0.6, phi_o = 0.8;
      const double eta_o = up ? 1.0 : 1.5, eta_i = up ? 1.5 : 1.0;
      const Vec3 wo(float(std::sin(theta_o) * std::cos(phi_o)),
                    float(std::sin(theta_o) * std::sin(phi_o)),
                    float((up ? 1 : -1) * std::cos(theta_o)));
      const double sin_i = eta_o / eta_i * std::sin(theta_o);
      const double cos_i = std::sqrt(1 - sin_i * sin_i);
      const Vec3 expected(float(-sin_i * std::cos(phi_o)), float(-sin_i * std::sin(phi_o)),
                          float((up ? -1 : 1) * cos_i));
      int close = 0;
      const int n = 400;
      for (int i = 0; i < n; ++i) {
        const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
        ASSERT_TRUE(s.valid());
        close += length(s.wi - expected) < 1e-3f;
      }
      if (distribution == "beckmann") {
        EXPECT_EQ(close, n) << up;
      } else {
        EXPECT_GT(close, 0.95 * n) << up;
      }
    }
  }
  const BxDFPtr m = make_rough_glass("beckmann", 1e-4, 1e-4, 1.0, 1.5);
  // Beyond the critical angle inside the glass nothing gets out.
  const Vec3 grazing_inside(float(std::sin(1.0)), 0.0f, float(-std::cos(1.0)));
  EXPECT_FALSE(m->sample_f(grazing_inside, Point2(0.3f, 0.3f)).valid());
}

TEST(MicrofacetTransmission, NearlySmoothThroughputIsRadianceScaled) {
  // For a nearly smooth interface, ∫ f |cos θi| dωi → T (1 − F(θo)) (ηo/ηi)²: radiance is
  // compressed into the smaller solid angle on the denser side.
  for (const bool up : {true, false}) {
    const double eta_o = up ? 1.0 : 1.5, eta_i = up ? 1.5 : 1.0;
    const BxDFPtr m = make_rough_glass("ggx", 0.01, 0.01, 1.0, 1.5, 0.9);
    const double theta_o = 0.5;
    const Vec3 wo(float(std::sin(theta_o)), 0.0f, float((up ? 1 : -1) * std::cos(theta_o)));
    const double F = fresnel_dielectric(float(std::cos(theta_o)), float(eta_o), float(eta_i));
    const double expected = 0.9 * (1 - F) * (eta_o / eta_i) * (eta_o / eta_i);
    EXPECT_NEAR(m->rho_hd(wo, 4096).g, expected, 0.01 * expected) << up;
  }
}

TEST(MicrofacetTransmission, ParametersAreRefused) {
  auto error_of = [](const ParamSet& p) -> std::string {
    try {
      make("microfacet_transmission", p);
    } catch (const ParameterError& e) {
      return e.what();
    }
    return "";
  };
  ParamSet p;
  p.set("eta_i", 1.5);
  p.set("eta_t", 1.5);
  std::string msg = error_of(p);
  EXPECT_NE(msg.find("'eta_t'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1.5"), std::string::npos) << msg;
  p = ParamSet();
  p.set("alpha_y", -0.1);
  EXPECT_NE(error_of(p).find("'alpha_y'"), std::string::npos);
  p = ParamSet();
  p.set("distribution", "blinn");
  EXPECT_NE(error_of(p).find("'distribution'"), std::string::npos);
}

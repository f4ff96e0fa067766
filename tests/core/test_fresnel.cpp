// Fresnel reflectance (fresnel.h) against independent double-precision evaluations: the
// dielectric through Snell's law and the angle forms r⊥ = −sin(θi − θt)/sin(θi + θt),
// r∥ = tan(θi − θt)/tan(θi + θt); the exact conductor through complex Snell's law; the seed's
// conductor through its own r∥², r⊥² formula; and the seed's F0 inversions.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "bxdf/fresnel.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;
double deg(double d) { return d * kPiD / 180.0; }

// Dielectric F from the angle forms (θi strictly between 0 and the critical angle, θi + θt ≠ 90°).
double dielectric_by_angles(double theta_i, double eta_i, double eta_t) {
  const double theta_t = std::asin(eta_i / eta_t * std::sin(theta_i));
  const double r_perp = -std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
  const double r_par = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
  return 0.5 * (r_perp * r_perp + r_par * r_par);
}

// Conductor (complex index n = (η + ik)/η_i) by complex Snell's law and the Fresnel amplitudes.
double conductor_by_complex_snell(double theta_i, double eta_i, double eta, double k) {
  const std::complex<double> n(eta / eta_i, k / eta_i);
  const double c = std::cos(theta_i), s = std::sin(theta_i);
  const std::complex<double> cos_t = std::sqrt(1.0 - (s / n) * (s / n));
  const std::complex<double> rs = (c - n * cos_t) / (c + n * cos_t);
  const std::complex<double> rp = (n * c - cos_t) / (n * c + cos_t);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

// The seed's conductor formula, in double.
double conductor_seed_formula(double cos_i, double eta, double k) {
  const double ek = eta * eta + k * k, c2 = cos_i * cos_i;
  const double r_par2 = (ek * c2 - 2 * eta * cos_i + 1) / (ek * c2 + 2 * eta * cos_i + 1);
  const double r_perp2 = (ek - 2 * eta * cos_i + c2) / (ek + 2 * eta * cos_i + c2);
  return 0.5 * (r_par2 + r_perp2);
}

struct Metal {
  const char* name;
  double eta, k;
};
// The seed's table.
const Metal kMetals[] = {{"gold", 0.370, 2.820},
                         {"silver", 0.177, 3.638},
                         {"copper", 0.617, 2.630},
                         {"steel", 2.485, 3.433}};

}  // namespace

TEST(FresnelDielectric, NormalIncidenceIsSquaredIndexContrast) {
  for (double eta_t : {1.333, 1.5, 2.42}) {
    const double expected = std::pow((eta_t - 1.0) / (eta_t + 1.0), 2.0);
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, static_cast<float>(eta_t)), expected, 1e-6) << eta_t;
  }
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, 1.5f), 0.04, 1e-6);
}

TEST(FresnelDielectric, MatchesTheAngleFormsAt45And89Degrees) {
  for (double eta_t : {1.31, 1.5, 2.42}) {
    for (double theta : {deg(45.0), deg(89.0)}) {
      const double expected = dielectric_by_angles(theta, 1.0, eta_t);
      EXPECT_NEAR(
          fresnel_dielectric(static_cast<float>(std::cos(theta)), 1.0f, static_cast<float>(eta_t)),
          expected, 2e-5)
          << "eta_t " << eta_t << " theta " << theta;
    }
  }
  // A sanity anchor for the angle forms themselves: glass at 45° reflects about 5.0 %.
  EXPECT_NEAR(dielectric_by_angles(deg(45.0), 1.0, 1.5), 0.0502, 1e-4);
}

TEST(FresnelDielectric, BrewsterAngleHasNoParallelReflection) {
  for (double eta_t : {1.333, 1.5, 2.42}) {
    const double theta_b = std::atan(eta_t);  // tan θB = ηt/ηi
    const double theta_t = std::asin(std::sin(theta_b) / eta_t);
    ASSERT_NEAR(theta_b + theta_t, kPiD / 2, 1e-12);     // so r∥ = tan(θi − θt)/tan(90°) = 0
    const double r_perp = -std::sin(theta_b - theta_t);  // sin(θi + θt) = 1
    EXPECT_NEAR(
        fresnel_dielectric(static_cast<float>(std::cos(theta_b)), 1.0f, static_cast<float>(eta_t)),
        0.5 * r_perp * r_perp, 2e-6)
        << eta_t;
  }
}

TEST(FresnelDielectric, FromInsideSwapsIndicesAndTotallyReflects) {
  const double critical = std::asin(1.0 / 1.5);  // 41.8°
  // Below the critical angle: the indices swap (light goes 1.5 → 1).
  for (double theta : {deg(20.0), deg(40.0)}) {
    EXPECT_NEAR(fresnel_dielectric(-static_cast<float>(std::cos(theta)), 1.0f, 1.5f),
                dielectric_by_angles(theta, 1.5, 1.0), 2e-5)
        << theta;
  }
  // Beyond it: total internal reflection.
  for (double theta : {critical + 1e-3, deg(45.0), deg(60.0), deg(89.0)})
    EXPECT_EQ(fresnel_dielectric(-static_cast<float>(std::cos(theta)), 1.0f, 1.5f), 1.0f) << theta;
  // Reflectance is the same from both ends of a refracted pair (Stokes): F(θi; 1→1.5) =
  // F(θt; 1.5→1).
  const double theta_i = deg(50.0), theta_t = std::asin(std::sin(theta_i) / 1.5);
  EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(theta_i)), 1.0f, 1.5f),
              fresnel_dielectric(-static_cast<float>(std::cos(theta_t)), 1.0f, 1.5f), 1e-6);
}

TEST(FresnelDielectric, GrazingAndBadInputStayInRange) {
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.0f, 1.5f), 1.0f, 1e-6);
  EXPECT_EQ(fresnel_dielectric(std::nanf(""), 1.0f, 1.5f), 0.0f);
  const float f = fresnel_dielectric(1.5f, 1.0f, 1.5f);  // |cos| > 1 is clamped
  EXPECT_NEAR(f, 0.04f, 1e-6);
}

TEST(FresnelConductor, SeedFormulaMatchesItsDefinition) {
  for (const Metal& m : kMetals) {
    for (double theta : {0.0, deg(30.0), deg(60.0), deg(80.0), deg(89.0)}) {
      const double c = std::cos(theta);
      EXPECT_NEAR(fresnel_conductor_seed(static_cast<float>(c), static_cast<float>(m.eta),
                                         static_cast<float>(m.k)),
                  conductor_seed_formula(c, m.eta, m.k), 1e-5)
          << m.name << " " << theta;
      // Evaluated at |cos θ|: the same from below.
      EXPECT_EQ(fresnel_conductor_seed(static_cast<float>(-c), static_cast<float>(m.eta),
                                       static_cast<float>(m.k)),
                fresnel_conductor_seed(static_cast<float>(c), static_cast<float>(m.eta),
                                       static_cast<float>(m.k)));
    }
  }
}

TEST(FresnelConductor, ExactFormulaMatchesComplexSnellsLaw) {
  for (double eta_i : {1.0, 1.33}) {
    for (const Metal& m : kMetals) {
      for (double theta : {0.0, deg(30.0), deg(60.0), deg(80.0), deg(89.0)}) {
        EXPECT_NEAR(
            fresnel_conductor_exact(static_cast<float>(std::cos(theta)), static_cast<float>(eta_i),
                                    static_cast<float>(m.eta), static_cast<float>(m.k)),
            conductor_by_complex_snell(theta, eta_i, m.eta, m.k), 2e-5)
            << m.name << " eta_i " << eta_i << " theta " << theta;
      }
    }
  }
}

TEST(FresnelConductor, SeedAndExactAgreeAtNormalIncidenceAndDifferAt60Degrees) {
  for (const Metal& m : kMetals) {
    const double f0 =
        ((m.eta - 1) * (m.eta - 1) + m.k * m.k) / ((m.eta + 1) * (m.eta + 1) + m.k * m.k);
    EXPECT_NEAR(fresnel_conductor_seed(1.0f, static_cast<float>(m.eta), static_cast<float>(m.k)),
                f0, 1e-6);
    EXPECT_NEAR(
        fresnel_conductor_exact(1.0f, 1.0f, static_cast<float>(m.eta), static_cast<float>(m.k)), f0,
        1e-6);
  }
  // Copper at 60°: seed 0.7451, exact 0.7393 (from the two independent evaluations above).
  const double seed = conductor_seed_formula(std::cos(deg(60.0)), 0.617, 2.630);
  const double exact = conductor_by_complex_snell(deg(60.0), 1.0, 0.617, 2.630);
  EXPECT_GT(seed - exact, 5e-3);
  EXPECT_NEAR(fresnel_conductor_seed(0.5f, 0.617f, 2.630f) -
                  fresnel_conductor_exact(0.5f, 1.0f, 0.617f, 2.630f),
              seed - exact, 1e-5);
}

TEST(FresnelConductor, RGBOverloadsWorkPerChannel) {
  const RGB eta(0.370f, 0.177f, 0.617f), k(2.820f, 3.638f, 2.630f);
  const RGB seed = fresnel_conductor_seed(0.6f, eta, k);
  const RGB exact = fresnel_conductor_exact(0.6f, 1.0f, eta, k);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(seed[c], fresnel_conductor_seed(0.6f, eta[c], k[c]));
    EXPECT_EQ(exact[c], fresnel_conductor_exact(0.6f, 1.0f, eta[c], k[c]));
  }
}

TEST(FresnelFromF0, InversionsReproduceF0AtNormalIncidence) {
  for (float f0 : {0.0f, 0.02f, 0.04f, 0.25f, 0.5f, 0.9f, 0.99f}) {
    const float eta = eta_from_f0(f0);  // a dielectric (k = 0) with this F0
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, eta), f0, 1e-5) << f0;
    EXPECT_NEAR(fresnel_conductor_seed(1.0f, eta, 0.0f), f0, 1e-5) << f0;
    const float k = k_from_f0(f0);  // a conductor with η = 1 and this F0
    EXPECT_NEAR(fresnel_conductor_seed(1.0f, 1.0f, k), f0, 1e-5) << f0;
    EXPECT_NEAR(conductor_by_complex_snell(0.0, 1.0, 1.0, k), f0, 1e-5) << f0;
  }
  EXPECT_NEAR(eta_from_f0(0.04f), 1.5f, 1e-5);
  // F0 = 1 is clamped so that the inversions stay finite.
  EXPECT_TRUE(std::isfinite(eta_from_f0(1.0f)));
  EXPECT_TRUE(std::isfinite(k_from_f0(1.0f)));
}

TEST(Fresnel, DielectricTransmittanceIsOneMinusReflectance) {
  for (float eta_t : {1.0f, 1.33f, 1.5f, 2.4f})
    for (float c = -1.0f; c <= 1.0f; c += 0.01f) {
      const float t = fresnel_dielectric_transmittance(c, 1.0f, eta_t);
      EXPECT_NEAR(t, 1.0f - fresnel_dielectric(c, 1.0f, eta_t), 2e-6f) << c << " " << eta_t;
      EXPECT_GE(t, 0.0f);
      EXPECT_LE(t, 1.0f);
    }
  // Total internal reflection, grazing and non-finite input transmit nothing.
  EXPECT_EQ(fresnel_dielectric_transmittance(-0.1f, 1.0f, 1.5f), 0.0f);
  EXPECT_EQ(fresnel_dielectric_transmittance(0.0f, 1.0f, 1.5f), 0.0f);
  EXPECT_EQ(fresnel_dielectric_transmittance(std::nanf(""), 1.0f, 1.5f), 0.0f);
}

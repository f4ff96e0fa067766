// The regularised incomplete gamma function against closed forms, an independent quadrature
// and tabulated χ² quantiles: the χ² tests' verdicts are only as good as this p-value.
#include <gtest/gtest.h>

#include <cmath>

#include "incomplete_gamma.h"

using namespace bxdf::test;

namespace {

// Q(k, x) for integer k is the Poisson tail: e^-x Σ_{n<k} x^n / n!.
double poisson_q(int k, double x) {
  long double term = std::exp(static_cast<long double>(-x)), sum = 0;
  for (int n = 0; n < k; ++n) {
    sum += term;
    term *= x / (n + 1);
  }
  return static_cast<double>(sum);
}

// P(a, x) by composite Simpson on t^(a-1) e^-t over [0, x]. For a < 1 the substitution
// t = s^(1/a) first removes the t^(a-1) singularity: γ(a, x) = (1/a) ∫_0^(x^a) e^(-s^(1/a)) ds.
double quadrature_p(double a, double x) {
  const int n = 200000;
  const bool substitute = a < 1.0;
  const long double upper = substitute ? std::pow(static_cast<long double>(x), a) : x;
  const long double h = upper / n;
  long double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const long double s = i * h;
    const long double v = substitute ? std::exp(-std::pow(s, 1.0L / a))
                                     : std::pow(s, a - 1.0L) * std::exp(-s);
    sum += v * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
  }
  const long double gamma = std::exp(std::lgamma(static_cast<long double>(a)));
  return static_cast<double>(sum * h / 3 / (substitute ? a : 1.0L) / gamma);
}

}  // namespace

TEST(IncompleteGamma, ExponentialCase) {
  for (double x : {1e-8, 0.5, 3.0, 20.0, 200.0}) {
    EXPECT_NEAR(regularized_gamma_p(1.0, x), -std::expm1(-x), 1e-14) << x;
    EXPECT_NEAR(regularized_gamma_q(1.0, x) / std::exp(-x), 1.0, 1e-12) << x;
  }
}

TEST(IncompleteGamma, HalfIntegerIsErf) {
  for (double x : {1e-6, 0.1, 2.0, 10.0, 50.0}) {
    EXPECT_NEAR(regularized_gamma_p(0.5, x), std::erf(std::sqrt(x)), 1e-13) << x;
    EXPECT_NEAR(regularized_gamma_q(0.5, x) / std::erfc(std::sqrt(x)), 1.0, 1e-10) << x;
  }
}

TEST(IncompleteGamma, IntegerIsPoissonTail) {
  const std::pair<int, double> cases[] = {{2, 0.3}, {5, 3.0}, {5, 9.0}, {50, 40.0}, {50, 60.0},
                                          {300, 250.0}, {300, 380.0}};
  for (auto [k, x] : cases) {
    const double expect = poisson_q(k, x);
    EXPECT_NEAR(regularized_gamma_q(k, x) / expect, 1.0, 1e-9) << k << " " << x;
    EXPECT_NEAR(regularized_gamma_p(k, x) + regularized_gamma_q(k, x), 1.0, 1e-13);
  }
}

TEST(IncompleteGamma, MatchesIndependentQuadrature) {
  const std::pair<double, double> cases[] = {{0.7, 0.4}, {3.7, 2.2}, {3.7, 9.0}, {12.5, 10.0}};
  for (auto [a, x] : cases) EXPECT_NEAR(regularized_gamma_p(a, x), quadrature_p(a, x), 1e-9);
}

TEST(IncompleteGamma, ChiSquareQuantilesFromTables) {
  // (dof, quantile, upper-tail probability) from standard χ² tables.
  EXPECT_NEAR(chi2_survival(3.841459, 1), 0.05, 1e-7);
  EXPECT_NEAR(chi2_survival(6.634897, 1), 0.01, 1e-7);
  EXPECT_NEAR(chi2_survival(23.209251, 10), 0.01, 1e-7);
  EXPECT_NEAR(chi2_survival(18.307038, 10), 0.05, 1e-7);
  EXPECT_NEAR(chi2_survival(135.806723, 100), 0.01, 1e-7);
  // dof = 2 is exactly exponential: Q = e^(-χ²/2).
  EXPECT_NEAR(chi2_survival(30.0, 2) / std::exp(-15.0), 1.0, 1e-12);
  EXPECT_EQ(chi2_survival(5.0, 0), 1.0);
}

TEST(IncompleteGamma, DomainAndLimits) {
  EXPECT_TRUE(std::isnan(regularized_gamma_p(-1.0, 1.0)));
  EXPECT_TRUE(std::isnan(regularized_gamma_q(1.0, -1.0)));
  EXPECT_EQ(regularized_gamma_p(2.0, 0.0), 0.0);
  EXPECT_EQ(regularized_gamma_q(2.0, INFINITY), 0.0);
}

TEST(IncompleteGamma, SidakCorrection) {
  EXPECT_NEAR(sidak_alpha(0.01, 1), 0.01, 1e-15);
  // (1 - a')^runs == 1 - a
  const double a = sidak_alpha(0.01, 500);
  EXPECT_NEAR(std::pow(1.0 - a, 500), 0.99, 1e-12);
  EXPECT_LT(a, 0.01 / 500 * 1.01);
}

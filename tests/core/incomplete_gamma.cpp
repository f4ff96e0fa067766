#include "incomplete_gamma.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bxdf::test {

namespace {

constexpr double kEps = 1e-15;
constexpr int kMaxIterations = 100000;

// x^a e^-x / Γ(a), the common prefactor of both expansions, in logs to avoid overflow.
double prefactor(double a, double x) { return std::exp(a * std::log(x) - x - std::lgamma(a)); }

// Power series γ(a, x)/Γ(a) = x^a e^-x / Γ(a) · Σ x^n / (a (a+1) ... (a+n)); converges
// quickly for x < a + 1.
double p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < kMaxIterations; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * kEps) break;
  }
  return sum * prefactor(a, x);
}

// Continued fraction for Γ(a, x)/Γ(a) (modified Lentz), good for x ≥ a + 1:
// Γ(a,x) = e^-x x^a · 1/(x+1−a− 1·(1−a)/(x+3−a− 2·(2−a)/(x+5−a− ...))).
double q_continued_fraction(double a, double x) {
  const double tiny = std::numeric_limits<double>::min() / kEps;
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < kEps) break;
  }
  return h * prefactor(a, x);
}

bool valid(double a, double x) { return a > 0.0 && x >= 0.0 && std::isfinite(a); }

}  // namespace

double regularized_gamma_p(double a, double x) {
  if (!valid(a, x)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return 0.0;
  if (std::isinf(x)) return 1.0;
  return x < a + 1.0 ? p_series(a, x) : 1.0 - q_continued_fraction(a, x);
}

double regularized_gamma_q(double a, double x) {
  if (!valid(a, x)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return 1.0;
  if (std::isinf(x)) return 0.0;
  return x < a + 1.0 ? 1.0 - p_series(a, x) : q_continued_fraction(a, x);
}

double chi2_survival(double statistic, double dof) {
  if (!(dof > 0.0)) return 1.0;  // no degrees of freedom: nothing can be rejected
  return regularized_gamma_q(0.5 * dof, 0.5 * std::max(0.0, statistic));
}

double sidak_alpha(double alpha, int runs) {
  // expm1/log1p keep precision when alpha/runs is tiny.
  return -std::expm1(std::log1p(-alpha) / std::max(1, runs));
}

}  // namespace bxdf::test

// The regularised incomplete gamma functions P(a, x) and Q(a, x) = 1 − P(a, x), and the
// χ² survival function built on them (the p-value of a goodness-of-fit statistic).
#pragma once

namespace bxdf::test {

// P(a, x) = γ(a, x) / Γ(a), for a > 0, x ≥ 0. NaN outside that domain.
double regularized_gamma_p(double a, double x);
// Q(a, x) = Γ(a, x) / Γ(a), computed directly (no 1 − P cancellation in the tail).
double regularized_gamma_q(double a, double x);

// Probability that a χ² variable with `dof` degrees of freedom exceeds `statistic`.
double chi2_survival(double statistic, double dof);

// Šidák-corrected per-test significance so that `runs` independent tests at level alpha'
// together have family-wise level alpha: alpha' = 1 − (1 − alpha)^(1/runs).
double sidak_alpha(double alpha, int runs);

}  // namespace bxdf::test

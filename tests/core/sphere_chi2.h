// χ² goodness of fit of a model's sample_f (sample_f_exact for a model whose sample_f runs
// Cycles' sampling walk, BxDF::sample_f_is_exact) against its own pdf, the way pbrt-v3
// (src/tests/bsdfs.cpp) and Mitsuba (chi2.py) test BSDFs: sampled directions are binned on an
// area-preserving (φ, cosθ) grid over the whole sphere, the expected count of each cell is
// N × the integral of pdf over the cell (adaptive Simpson), low-expectation cells are pooled,
// and the statistic's p-value comes from the regularised incomplete gamma function.
#pragma once

#include <cstdint>
#include <string>

#include "bxdf/bxdf.h"

namespace bxdf::test {

struct Chi2Config {
  int phi_bins = 50;
  int cos_bins = 101;         // odd: the horizon falls inside a cell, never on an edge
  int integration_res = 4;    // initial Simpson sub-intervals per cell and axis (even)
  double integration_abs_tol = 1e-7;  // per cell, in probability (× samples = counts)
  double integration_rel_tol = 1e-4;
  // Halvings of a panel: 2^-10 of a 3.6° panel resolves the ~0.2° wide lobes of grazing
  // incidence, while every jump of a tabulated pdf costs only ~2·10 evaluations per line.
  int integration_max_depth = 10;
  int64_t samples = 1000000;
  uint64_t seed = 1;
  double min_expected = 5.0;  // cells are pooled until each group expects this many
};

struct Chi2Result {
  // Set when the run fails outright, whatever the statistic: a sample off the unit sphere,
  // a sample in a cell where pdf integrates to 0, or a pdf integrating to more than 1.1.
  std::string hard_failure;
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  int64_t valid_samples = 0;   // samples with pdf > 0
  double pdf_integral = 0.0;   // ∫ pdf over the sphere
  std::string worst_cells;     // the cells that contribute most to the statistic
};

Chi2Result run_chi2(const BxDF& model, const Vec3& wo, const Chi2Config& config = {});

// ∫ f(wo, wi) |cos θi| dωi per channel, by the same Simpson quadrature: an estimate of ρhd
// that does not depend on the model's sampling, split into the part reflected to wo's side
// and the part transmitted to the other. Good for lobes the (φ, cosθ) grid resolves (the
// curated grid's), not for near-delta ones.
struct Albedo {
  RGB reflected, transmitted;
  RGB total() const { return reflected + transmitted; }
};
Albedo quadrature_albedo(const BxDF& model, const Vec3& wo, const Chi2Config& config = {});

}  // namespace bxdf::test

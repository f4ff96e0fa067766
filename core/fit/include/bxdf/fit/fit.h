// Fitting analytic reflection models to measured BRDFs (Ceres Solver; this target is the only
// part of core that links Ceres and Eigen).
//
// Error (Ngan, Durand & Matusik 2005): the cosine-weighted L2 distance over the measurements,
// Σ_samples Σ_channels [(f_c(wo, wi) − f_ref,c) cos θi]², with the three RGB channels weighted
// equally (per channel, not luminance). FitReport::error is its RMS,
// sqrt(Σ / (3 · samples)), so it does not grow with the number of samples.
//
// Models:
//   lambertian          f = ρ/π                                         → lambertian
//   lafortune (1–3)     f = ρd/π + Σ max(0, Cxy(xo xi + yo yi) + Cz zo zi)^n, all RGB
//                                                                        → lafortune (one model)
//   blinn               ρd/π + ρs D_blinn(e) G_vgroove F(η) / (4 cos θi cos θo)  → microfacet
//   ashikhmin_shirley   ρd/π + ρs D_AS(ex, ey) G_vgroove F(η) / (4 cos θi cos θo) → microfacet
//   cook_torrance       ρd/π + ρs D_beckmann(α) G_vgroove F(η) / (4 cos θi cos θo) → microfacet
//   ggx                 ρd/π + ρs D_ggx(α) G_smith F(η) / (4 cos θi cos θo)    → microfacet
// F is the exact dielectric Fresnel term from air into a fitted η ∈ [1.01, 4]: all four are
// Torrance–Sparrow models that differ only in D (and GGX in G), as in Ngan et al.'s comparison,
// and each is one `microfacet` registry model (ρd is its `diffuse`, ρs its `reflectance`).
// Each fit starts from several points and keeps the best.
#pragma once

#include <string>
#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/measured/measured_data.h"
#include "bxdf/params.h"

namespace bxdf::fit {

struct FitOptions {
  std::string model = "lafortune";  // one of fit_model_names()
  int lobes = 2;                    // lafortune only, 1..3
  int max_iterations = 200;         // per start
  int max_starts = 0;               // 0: all of the model's starting points
  int merl_stride = 4;              // MERL: every θh, every n-th θd and φd cell
  bool verbose = false;             // Ceres progress to stderr
};

struct FitReport {
  std::string model;
  double error = 0.0;          // RMS cosine-weighted error (see above)
  double sum_squares = 0.0;    // Σ [(f − f_ref) cos θi]² over samples and channels
  double baseline_error = 0.0; // the same error of f = 0, for scale
  int iterations = 0;          // Ceres iterations of the best start
  int total_iterations = 0;    // over all starts
  int starts = 0;
  size_t samples = 0;
  double seconds = 0.0;        // wall time of the whole fit
  std::vector<double> start_errors;  // error reached from each start
};

// The fitted model is one registry model.
struct FitResult {
  std::string model;  // registry name: lambertian, lafortune or microfacet
  ParamSet params;    // validated by the registry
  FitReport report;   // report.model names the fit (e.g. "lafortune2", "ggx")
  BxDFPtr build() const;  // bxdf::make(model, params)
};

std::vector<std::string> fit_model_names();

// Throws ParameterError for an unknown model, a bad lobe count or no usable samples.
FitResult fit(const std::vector<MeasuredSample>& samples, const FitOptions& options);
FitResult fit(const MeasuredData& data, const FitOptions& options);
// The same for a `measured` registry model (what bxdf.load_measured returns); any other model
// is refused with a ParameterError.
FitResult fit(const BxDF& measured_model, const FitOptions& options);

// The error above for any model (e.g. a fitted one rebuilt from the registry), so that
// fits and registry models can be compared on the same footing.
double fit_error(const std::vector<MeasuredSample>& samples, const BxDF& model,
                 double* sum_squares = nullptr);

}  // namespace bxdf::fit

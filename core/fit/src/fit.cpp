#include "bxdf/fit/fit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <ceres/ceres.h>

#include "bxdf/models/measured.h"
#include "bxdf/registry.h"
#include "fit_geometry.h"
#include "fit_kernels.h"

namespace bxdf::fit {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = kPiD / 180.0;

struct Bound {
  double lo = -kInf, hi = kInf;
};

struct Solution {
  std::vector<double> p;
  double sum_squares = kInf;
  int iterations = 0;
};

// One Ceres run from p0 (clamped into the bounds) on a single cost block over all samples.
template <int N, class Functor>
Solution solve(Functor* functor, int residuals, std::vector<double> p0,
               const std::vector<Bound>& bounds, const FitOptions& options) {
  ceres::Problem problem;
  auto* cost = new ceres::AutoDiffCostFunction<Functor, ceres::DYNAMIC, N>(functor, residuals);
  for (int i = 0; i < N; ++i) p0[size_t(i)] = std::clamp(p0[size_t(i)], bounds[size_t(i)].lo, bounds[size_t(i)].hi);
  problem.AddResidualBlock(cost, nullptr, p0.data());
  for (int i = 0; i < N; ++i) {
    if (std::isfinite(bounds[size_t(i)].lo)) problem.SetParameterLowerBound(p0.data(), i, bounds[size_t(i)].lo);
    if (std::isfinite(bounds[size_t(i)].hi)) problem.SetParameterUpperBound(p0.data(), i, bounds[size_t(i)].hi);
  }
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = options.max_iterations;
  o.function_tolerance = 1e-10;
  o.gradient_tolerance = 1e-12;
  o.parameter_tolerance = 1e-10;
  o.num_threads = 1;
  o.minimizer_progress_to_stdout = options.verbose;
  o.logging_type = options.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  Solution s;
  s.p = p0;
  s.sum_squares = std::isfinite(summary.final_cost) ? 2.0 * summary.final_cost : kInf;
  s.iterations = static_cast<int>(summary.iterations.size()) - 1;
  return s;
}

// Per-channel statistics that seed the starting points.
struct ChannelStats {
  double low;   // 20th percentile of the measured BRDF
  double peak;  // its maximum
};
ChannelStats channel_stats(const std::vector<FitSample>& s, int c) {
  std::vector<double> v;
  v.reserve(s.size());
  for (const auto& x : s) v.push_back(x.ref[c]);
  std::sort(v.begin(), v.end());
  return {v[v.size() / 5], v.back()};
}

double rms(double sum_squares, size_t samples) {
  return std::sqrt(sum_squares / (3.0 * static_cast<double>(samples)));
}

// ---- Lambertian: the weighted least-squares optimum is closed-form --------------------------

FitResult fit_lambertian(const std::vector<FitSample>& s) {
  FitResult r;
  RGBValue rho{};
  double ss = 0.0;
  for (int c = 0; c < 3; ++c) {
    double num = 0.0, den = 0.0;
    for (const auto& x : s) {
      num += x.ref[c] * x.cos_i * x.cos_i;
      den += x.cos_i * x.cos_i;
    }
    rho[size_t(c)] = std::clamp(kPiD * num / den, 0.0, 1.0);
    for (const auto& x : s) {
      const double e = (rho[size_t(c)] / kPiD - x.ref[c]) * x.cos_i;
      ss += e * e;
    }
  }
  ParamSet p;
  p.set("reflectance", rho);
  r.model = "lambertian";
  r.params = p;
  r.report.sum_squares = ss;
  r.report.starts = 1;
  r.report.start_errors = {rms(ss, s.size())};
  return r;
}

// ---- Lafortune: channels are independent, so each is fitted on its own -----------------------

// The registry refuses a lobe whose max(|Cx|, |Cy|, |Cz|)^n exceeds Lafortune::kMaxPeak (1e20):
// in log form log K + n log(√2 max(|cos ψ|, |sin ψ|)) ≤ 46. One extra residual per lobe
// penalises crossing a slightly lower limit, so fitted lobes stay buildable.
constexpr double kLobeLogPeakLimit = 44.0;
constexpr double kLobePenaltyWeight = 10.0;

template <int L>
struct LafortuneCost {
  const std::vector<FitSample>* samples;
  int channel;
  template <class T>
  bool operator()(const T* p, T* r) const {
    using std::abs;
    using std::cos;
    using std::exp;
    using std::log;
    using std::sin;
    const LafortuneChannel<T, L> model(p);
    const auto& s = *samples;
    for (size_t i = 0; i < s.size(); ++i) r[i] = (model(s[i]) - s[i].ref[channel]) * s[i].cos_i;
    for (int l = 0; l < L; ++l) {
      const T* q = p + 1 + 3 * l;
      const T c = abs(cos(q[1])), sn = abs(sin(q[1]));
      const T log_peak = q[0] + exp(q[2]) * log(std::sqrt(2.0) * (c > sn ? c : sn));
      r[s.size() + size_t(l)] =
          log_peak > T(kLobeLogPeakLimit) ? kLobePenaltyWeight * (log_peak - kLobeLogPeakLimit) : T(0.0);
    }
    return true;
  }
};

template <int L>
double lafortune_sum_squares(const std::vector<FitSample>& s, int channel, const std::vector<double>& p) {
  const LafortuneChannel<double, L> model(p.data());
  double ss = 0.0;
  for (const auto& x : s) {
    const double e = (model(x) - x.ref[channel]) * x.cos_i;
    ss += e * e;
  }
  return std::isfinite(ss) ? ss : kInf;
}

template <int L>
FitResult fit_lafortune(const std::vector<FitSample>& s, const FitOptions& options,
                        std::vector<double> best_channel_params[3] = nullptr);

// With L lobes, one extra start is the best (L − 1)-lobe fit plus a weak broad lobe, so adding
// a lobe never makes the fit worse.
template <int L>
void nested_starts(const std::vector<FitSample>& s, const FitOptions& options,
                   std::vector<double> out[3]) {
  if constexpr (L >= 2) {
    FitOptions inner = options;
    inner.max_starts = 0;
    std::vector<double> fewer[3];
    fit_lafortune<L - 1>(s, inner, fewer);
    for (int c = 0; c < 3; ++c) {
      out[c] = fewer[c];
      out[c].push_back(std::log(1e-4));
      out[c].push_back(L == 2 ? 45.0 * kDeg : 90.0 * kDeg);
      out[c].push_back(std::log(2.0));
    }
  } else {
    (void)s;
    (void)options;
    (void)out;
  }
}

template <int L>
FitResult fit_lafortune(const std::vector<FitSample>& s, const FitOptions& options,
                        std::vector<double> best_channel_params[3]) {
  constexpr int N = 1 + 3 * L;
  std::vector<double> nested[3];
  nested_starts<L>(s, options, nested);
  std::vector<Bound> bounds(N);
  bounds[0] = {0.0, 1.0};
  for (int l = 0; l < L; ++l) {
    bounds[size_t(1 + 3 * l)] = {-40.0, 20.0};                          // log K
    bounds[size_t(3 + 3 * l)] = {std::log(0.5), std::log(9999.0)};  // log n, registry max 1e4
  }
  FitResult result;
  std::vector<double> best_p[3];
  double total_ss = 0.0;
  std::vector<double> start_ss;
  for (int c = 0; c < 3; ++c) {
    const ChannelStats st = channel_stats(s, c);
    const double diffuse = std::clamp(kPiD * st.low, 0.0, 1.0);
    const double k1 = std::max(st.peak - st.low, 1e-4);
    // Starting points: a mirror or off-specular main lobe of three widths; with two lobes, a
    // broad forward or retro-reflective second lobe; with three, a broad (cos θo cos θi)^n lobe.
    std::vector<std::vector<double>> starts;
    for (double n1 : {8.0, 40.0, 200.0})
      for (double psi1 : {135.0, 155.0})
        for (double psi2 : L >= 2 ? std::vector<double>{135.0, 45.0} : std::vector<double>{0.0}) {
          std::vector<double> p(N);
          p[0] = diffuse * (L >= 2 ? 0.7 : 1.0);
          p[1] = std::log(k1);
          p[2] = psi1 * kDeg;
          p[3] = std::log(n1);
          if (L >= 2) {
            p[4] = std::log(std::max(0.3 * st.low, 1e-4));
            p[5] = psi2 * kDeg;
            p[6] = std::log(3.0);
          }
          if (L >= 3) {
            p[7] = std::log(std::max(0.1 * st.low, 1e-4));
            p[8] = 90.0 * kDeg;
            p[9] = std::log(1.5);
          }
          starts.push_back(p);
        }
    if (options.max_starts > 0 && starts.size() > size_t(options.max_starts))
      starts.resize(size_t(options.max_starts));
    if (!nested[c].empty()) starts.insert(starts.begin(), nested[c]);
    Solution best;
    for (size_t k = 0; k < starts.size(); ++k) {
      auto* cost = new LafortuneCost<L>{&s, c};
      Solution sol = solve<N>(cost, static_cast<int>(s.size()) + L, starts[k], bounds, options);
      sol.sum_squares = lafortune_sum_squares<L>(s, c, sol.p);  // without the penalty terms
      // A solution the registry would refuse (a lobe still past the peak limit) cannot win.
      for (int l = 0; l < L; ++l) {
        const double* q = &sol.p[size_t(1 + 3 * l)];
        const double m = std::max(std::fabs(std::cos(q[1])), std::fabs(std::sin(q[1])));
        if (q[0] + std::exp(q[2]) * std::log(std::sqrt(2.0) * m) > std::log(1e20)) sol.sum_squares = kInf;
      }
      result.report.total_iterations += sol.iterations;
      if (start_ss.size() <= k) start_ss.resize(k + 1, 0.0);
      start_ss[k] += sol.sum_squares;
      if (sol.sum_squares < best.sum_squares) best = sol;
    }
    result.report.iterations += best.iterations;
    total_ss += best.sum_squares;
    best_p[c] = best.p;
    if (best_channel_params) best_channel_params[c] = best.p;
  }
  // Back to the registry's parameters.
  ParamSet params;
  params.set("diffuse", RGBValue{best_p[0][0], best_p[1][0], best_p[2][0]});
  std::vector<ParamSet> lobes;
  for (int l = 0; l < L; ++l) {
    RGBValue cxy{}, cz{}, n{};
    for (int c = 0; c < 3; ++c) {
      const double* q = &best_p[c][size_t(1 + 3 * l)];
      // exp(log n) can round just past the bound, which the registry would refuse.
      const double exponent = std::min(std::exp(q[2]), std::exp(bounds[size_t(3 + 3 * l)].hi));
      const double scale = std::sqrt(2.0) * std::exp(q[0] / exponent);  // √2 K^(1/n)
      cxy[size_t(c)] = scale * std::cos(q[1]);
      cz[size_t(c)] = scale * std::sin(q[1]);
      n[size_t(c)] = exponent;
    }
    ParamSet lobe;
    lobe.set("cx", cxy);
    lobe.set("cy", cxy);
    lobe.set("cz", cz);
    lobe.set("exponent", n);
    lobes.push_back(lobe);
  }
  params.set("lobes", lobes);
  result.model = "lafortune";
  result.params = params;
  result.report.sum_squares = total_ss;
  result.report.starts = static_cast<int>(start_ss.size());
  for (double x : start_ss) result.report.start_errors.push_back(rms(x, s.size()));
  return result;
}

// ---- Torrance–Sparrow microfacet lobe over a Lambertian term, fitted jointly over channels ---

struct MicrofacetSpec {
  Distribution distribution;
  int roughness_params;  // 1, or 2 for anisotropic Ashikhmin–Shirley
  bool fresnel;          // dielectric Fresnel with a fitted η
  bool smith;            // Smith (GGX) instead of V-groove shadowing
};

template <int N>
struct MicrofacetCost {
  const std::vector<FitSample>* samples;
  MicrofacetSpec spec;
  template <class T>
  bool operator()(const T* p, T* r) const {
    const auto& s = *samples;
    const T* rough = p + 6;
    for (size_t i = 0; i < s.size(); ++i) {
      T spec_term = distribution(spec.distribution, rough, s[i]) * s[i].inv_4cc;
      spec_term *= spec.smith ? smith_ggx(rough, s[i]) : T(s[i].g_vgroove);
      if (spec.fresnel) spec_term *= fresnel_dielectric(s[i].cos_d, p[N - 1]);
      for (int c = 0; c < 3; ++c)
        r[3 * i + size_t(c)] = (p[c] / kPiD + p[3 + c] * spec_term - s[i].ref[c]) * s[i].cos_i;
    }
    return true;
  }
};

template <int N>
FitResult fit_microfacet(const std::vector<FitSample>& s, const MicrofacetSpec& spec,
                         const FitOptions& options) {
  std::vector<Bound> bounds(N);
  for (int c = 0; c < 6; ++c) bounds[size_t(c)] = {0.0, 1.0};
  const bool exponent_form = spec.distribution == Distribution::Blinn ||
                             spec.distribution == Distribution::AshikhminShirley;
  for (int k = 0; k < spec.roughness_params; ++k)
    bounds[size_t(6 + k)] = exponent_form ? Bound{std::log(0.5), std::log(1e5)}
                                          : Bound{std::log(1e-3), std::log(1.5)};
  if (spec.fresnel) bounds[N - 1] = {1.01, 4.0};

  ChannelStats st[3];
  for (int c = 0; c < 3; ++c) st[c] = channel_stats(s, c);
  std::vector<std::vector<double>> starts;
  const std::vector<double> roughness =
      exponent_form ? std::vector<double>{10.0, 100.0, 1000.0, 10000.0}
                    : std::vector<double>{0.5, 0.2, 0.08, 0.03};
  for (double rough : roughness) {
    std::vector<double> p(N);
    // Peak ≈ ρs D(0) F0 / (4 cos²) with cos² ≈ 1/2 at 45°: choose ρs so the start has the peak.
    const double d0 = exponent_form ? (rough + 2.0) / (2.0 * kPiD) : 1.0 / (kPiD * rough * rough);
    const double f0 = spec.fresnel ? 0.04 : 1.0;
    for (int c = 0; c < 3; ++c) {
      p[size_t(c)] = std::clamp(kPiD * st[c].low, 0.0, 1.0);
      p[size_t(3 + c)] = std::clamp(2.0 * (st[c].peak - st[c].low) / (d0 * f0), 1e-3, 1.0);
    }
    for (int k = 0; k < spec.roughness_params; ++k) p[size_t(6 + k)] = std::log(rough);
    if (spec.fresnel) p[N - 1] = 1.5;
    starts.push_back(p);
  }
  if (options.max_starts > 0 && starts.size() > size_t(options.max_starts))
    starts.resize(size_t(options.max_starts));

  FitResult result;
  Solution best;
  for (const auto& p0 : starts) {
    auto* cost = new MicrofacetCost<N>{&s, spec};
    const Solution sol = solve<N>(cost, static_cast<int>(3 * s.size()), p0, bounds, options);
    result.report.total_iterations += sol.iterations;
    result.report.start_errors.push_back(rms(sol.sum_squares, s.size()));
    if (sol.sum_squares < best.sum_squares) best = sol;
  }
  result.report.iterations = best.iterations;
  result.report.sum_squares = best.sum_squares;
  result.report.starts = static_cast<int>(starts.size());

  const auto& p = best.p;
  ParamSet specular;
  specular.set("diffuse", RGBValue{p[0], p[1], p[2]});
  specular.set("reflectance", RGBValue{p[3], p[4], p[5]});
  switch (spec.distribution) {
    case Distribution::Blinn:
      specular.set("distribution", "blinn");
      specular.set("exponent", std::exp(p[6]));
      break;
    case Distribution::AshikhminShirley:
      specular.set("distribution", "ashikhmin_shirley");
      specular.set("exponent_x", std::exp(p[6]));
      specular.set("exponent_y", std::exp(p[7]));
      break;
    case Distribution::Beckmann:
    case Distribution::GGX:
      specular.set("distribution", spec.distribution == Distribution::GGX ? "ggx" : "beckmann");
      specular.set("alpha_x", std::exp(p[6]));
      specular.set("alpha_y", std::exp(p[6]));
      break;
  }
  specular.set("shadowing", spec.smith ? "smith" : "v_groove");
  if (spec.fresnel) {
    specular.set("fresnel", "dielectric");
    specular.set("eta_i", 1.0);
    specular.set("eta_t", p[N - 1]);
  } else {
    specular.set("fresnel", "none");
  }
  result.model = "microfacet";
  result.params = specular;
  return result;
}

}  // namespace

std::vector<std::string> fit_model_names() {
  return {"lambertian", "lafortune", "blinn", "ashikhmin_shirley", "cook_torrance", "ggx"};
}

FitResult fit(const std::vector<MeasuredSample>& samples, const FitOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<FitSample> s = prepare_samples(samples);
  if (s.size() < 16)
    throw ParameterError("fit: only " + std::to_string(s.size()) +
                         " usable samples (both directions above the horizon, finite values); "
                         "need at least 16");
  if (options.max_iterations < 1)
    throw ParameterError("fit: max_iterations = " + std::to_string(options.max_iterations) +
                         " is out of range; valid: [1, inf)");
  FitResult r;
  const std::string& m = options.model;
  if (m == "lambertian") {
    r = fit_lambertian(s);
  } else if (m == "lafortune") {
    switch (options.lobes) {
      case 1: r = fit_lafortune<1>(s, options); break;
      case 2: r = fit_lafortune<2>(s, options); break;
      case 3: r = fit_lafortune<3>(s, options); break;
      default:
        throw ParameterError("fit: lobes = " + std::to_string(options.lobes) +
                             " is out of range; valid: 1, 2 or 3");
    }
  } else if (m == "blinn") {
    r = fit_microfacet<8>(s, {Distribution::Blinn, 1, true, false}, options);
  } else if (m == "ashikhmin_shirley") {
    r = fit_microfacet<9>(s, {Distribution::AshikhminShirley, 2, true, false}, options);
  } else if (m == "cook_torrance") {
    r = fit_microfacet<8>(s, {Distribution::Beckmann, 1, true, false}, options);
  } else if (m == "ggx") {
    r = fit_microfacet<8>(s, {Distribution::GGX, 1, true, true}, options);
  } else {
    std::string known;
    for (const auto& n : fit_model_names()) known += (known.empty() ? "" : ", ") + n;
    throw ParameterError("fit: model '" + m + "' is not a fit model; valid: " + known);
  }
  // The registry fills the defaults and checks the ranges, so build() cannot fail.
  r.params = validate_params(r.model, find_model(r.model)->params, r.params);
  r.report.model = m == "lafortune" ? "lafortune" + std::to_string(options.lobes) : m;
  r.report.samples = s.size();
  r.report.error = rms(r.report.sum_squares, s.size());
  double base = 0.0;
  for (const auto& x : s)
    for (int c = 0; c < 3; ++c) base += x.ref[c] * x.cos_i * x.ref[c] * x.cos_i;
  r.report.baseline_error = rms(base, s.size());
  r.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

FitResult fit(const MeasuredData& data, const FitOptions& options) {
  return fit(data.samples(options.merl_stride), options);
}

FitResult fit(const BxDF& measured_model, const FitOptions& options) {
  const auto* m = dynamic_cast<const MeasuredBRDF*>(&measured_model);
  if (!m)
    throw ParameterError("fit: the model to fit to is '" + measured_model.model_name() +
                         "'; valid: a 'measured' model (a MERL or Cornell file)");
  return fit(m->data(), options);
}

BxDFPtr FitResult::build() const { return make(model, params); }

double fit_error(const std::vector<MeasuredSample>& samples, const BxDF& model, double* sum_squares) {
  double ss = 0.0;
  size_t n = 0;
  for (const MeasuredSample& m : samples) {
    if (!(m.wo.z > 1e-4f && m.wi.z > 1e-4f) || !finite_nonnegative(m.value)) continue;
    const RGB f = model.f(m.wo, m.wi);
    for (int c = 0; c < 3; ++c) {
      const double e = (double(f[c]) - m.value[c]) * m.wi.z;
      ss += e * e;
    }
    ++n;
  }
  if (sum_squares) *sum_squares = ss;
  return n ? rms(ss, n) : 0.0;
}

}  // namespace bxdf::fit

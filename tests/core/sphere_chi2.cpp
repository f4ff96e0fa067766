#include "sphere_chi2.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <vector>

#include "bxdf/rng.h"
#include "incomplete_gamma.h"

namespace bxdf::test {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr int kChunk = 4096;
// The horizon cell's two halves end this far from z = 0.
constexpr double kHorizonOffset = 1e-7;

// Integrands carry up to six channels (pdf: one; albedo: reflected and transmitted RGB).
constexpr int kMaxChannels = 6;
using Values = std::array<double, kMaxChannels>;

Values operator+(Values a, const Values& b) {
  for (int i = 0; i < kMaxChannels; ++i) a[i] += b[i];
  return a;
}
Values operator-(Values a, const Values& b) {
  for (int i = 0; i < kMaxChannels; ++i) a[i] -= b[i];
  return a;
}
Values operator*(Values a, double s) {
  for (double& x : a) x *= s;
  return a;
}
double max_abs(const Values& a) {
  double m = 0.0;
  for (double x : a) m = std::max(m, std::fabs(x));
  return m;
}

// Adaptive Simpson quadrature over the cells of the (φ, cosθ) grid: per cell, an outer
// integral over cosθ whose integrand is an inner integral over φ, each started as a composite
// of `panels` Simpson panels and refined wherever halving a panel changes its estimate by more
// than the tolerance. Lobes squeezed against the horizon at grazing incidence (a GGX lobe of
// α = 0.1 seen at θo = 89° is ~0.2° wide in φ) and transmitted lobes a few degrees wide about
// the pole are far narrower than any fixed lattice that could run in a test.
class CellIntegrator {
 public:
  using Integrand = std::function<Values(double cos_theta, double phi)>;
  CellIntegrator(const Chi2Config& c, Integrand f) : c_(c), f_(std::move(f)) {}

  Values cell(int j, int i) const {
    const double c0 = -1.0 + 2.0 * j / c_.cos_bins, c1 = -1.0 + 2.0 * (j + 1) / c_.cos_bins;
    const double p0 = kTwoPi * i / c_.phi_bins, p1 = kTwoPi * (i + 1) / c_.phi_bins;
    if (c0 < 0.0 && c1 > 0.0) {
      // The horizon cell: each hemisphere's half is integrated on its own, so that Simpson
      // never straddles the jump most reflection pdfs have at z = 0.
      return over_cos(c0, -kHorizonOffset, p0, p1) + over_cos(kHorizonOffset, c1, p0, p1);
    }
    return over_cos(c0, c1, p0, p1);
  }

 private:
  template <class G>
  Values adaptive(const G& g, double a, double b, const Values& fa, const Values& fm,
                  const Values& fb, const Values& whole, double tol, int depth) const {
    const double m = 0.5 * (a + b);
    const Values flm = g(0.5 * (a + m)), frm = g(0.5 * (m + b));
    const Values left = (fa + flm * 4.0 + fm) * ((m - a) / 6.0);
    const Values right = (fm + frm * 4.0 + fb) * ((b - m) / 6.0);
    const Values both = left + right;
    const double err = max_abs(both - whole);
    if (depth >= c_.integration_max_depth || err <= 15.0 * std::max(tol, c_.integration_rel_tol * max_abs(both)))
      return both + (both - whole) * (1.0 / 15.0);
    return adaptive(g, a, m, fa, flm, fm, left, 0.5 * tol, depth + 1) +
           adaptive(g, m, b, fm, frm, fb, right, 0.5 * tol, depth + 1);
  }

  // ∫_a^b g over `panels` Simpson panels, each refined adaptively to tolerance tol·width.
  template <class G>
  Values integrate(const G& g, double a, double b, double tol_per_unit) const {
    const int panels = c_.integration_res / 2;
    const double h = (b - a) / panels;
    Values total{}, fa = g(a);
    for (int p = 0; p < panels; ++p) {
      const double x0 = a + p * h, x1 = p + 1 == panels ? b : a + (p + 1) * h;
      const Values fm = g(0.5 * (x0 + x1)), fb = g(x1);
      const Values whole = (fa + fm * 4.0 + fb) * ((x1 - x0) / 6.0);
      total = total + adaptive(g, x0, x1, fa, fm, fb, whole, tol_per_unit * (x1 - x0), 0);
      fa = fb;
    }
    return total;
  }

  Values over_cos(double c0, double c1, double p0, double p1) const {
    // Tolerances are absolute, in probability: integration_abs_tol per cell overall.
    const double cell_area = (c1 - c0) * (p1 - p0);
    const double tol = c_.integration_abs_tol / cell_area;
    auto over_phi = [&](double cos_theta) {
      return integrate([&](double phi) { return f_(cos_theta, phi); }, p0, p1, 0.5 * tol);
    };
    return integrate(over_phi, c0, c1, 0.5 * tol * (p1 - p0));
  }

  Chi2Config c_;
  Integrand f_;
};

Vec3 direction_at(double cos_theta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return Vec3(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
              static_cast<float>(cos_theta));
}

std::string cell_name(const Chi2Config& c, size_t cell) {
  const int j = static_cast<int>(cell / c.phi_bins), i = static_cast<int>(cell % c.phi_bins);
  char buf[160];
  std::snprintf(buf, sizeof buf, "cos[%.4f,%.4f] phi[%.1f,%.1f]deg", -1.0 + 2.0 * j / c.cos_bins,
                -1.0 + 2.0 * (j + 1) / c.cos_bins, 360.0 * i / c.phi_bins,
                360.0 * (i + 1) / c.phi_bins);
  return buf;
}

}  // namespace

Chi2Result run_chi2(const BxDF& model, const Vec3& wo, const Chi2Config& c) {
  Chi2Result r;
  const size_t n_cells = static_cast<size_t>(c.cos_bins) * c.phi_bins;

  // Observed: bin N samples.
  std::vector<double> observed(n_cells, 0.0);
  {
    PCG32 rng(c.seed);
    std::vector<float> wox(kChunk, wo.x), woy(kChunk, wo.y), woz(kChunk, wo.z);
    std::vector<float> u1(kChunk), u2(kChunk), x(kChunk), y(kChunk), z(kChunk), fr(kChunk),
        fg(kChunk), fb(kChunk), pdf(kChunk);
    int64_t outside = 0;
    for (int64_t done = 0; done < c.samples; done += kChunk) {
      const size_t n = static_cast<size_t>(std::min<int64_t>(kChunk, c.samples - done));
      for (size_t s = 0; s < n; ++s) {
        u1[s] = rng.uniform();
        u2[s] = rng.uniform();
      }
      if (model.sample_f_is_exact()) {
        model.sample_f_batch(n, {wox.data(), woy.data(), woz.data()}, u1.data(), u2.data(),
                             {x.data(), y.data(), z.data()}, {fr.data(), fg.data(), fb.data()},
                             pdf.data());
      } else {  // the model's exact importance sampler (its sample_f runs Cycles' walk)
        for (size_t s = 0; s < n; ++s) {
          const BxDFSample smp = model.sample_f_exact(wo, Point2(u1[s], u2[s]));
          x[s] = smp.wi.x;
          y[s] = smp.wi.y;
          z[s] = smp.wi.z;
          pdf[s] = smp.pdf;
        }
      }
      for (size_t s = 0; s < n; ++s) {
        if (!(pdf[s] > 0.0f)) continue;
        const Vec3 wi(x[s], y[s], z[s]);
        if (!is_finite(wi) || std::fabs(length_squared(wi) - 1.0f) > 1e-3f) {
          ++outside;
          continue;
        }
        ++r.valid_samples;
        const double phi_raw = std::atan2(static_cast<double>(wi.y), static_cast<double>(wi.x));
        const double phi = phi_raw < 0.0 ? phi_raw + kTwoPi : phi_raw;
        const int i = std::clamp(static_cast<int>(phi / kTwoPi * c.phi_bins), 0, c.phi_bins - 1);
        const int j = std::clamp(static_cast<int>((wi.z + 1.0) * 0.5 * c.cos_bins), 0,
                                 c.cos_bins - 1);
        observed[static_cast<size_t>(j) * c.phi_bins + i] += 1.0;
      }
    }
    if (outside > 0) {
      r.hard_failure = std::to_string(outside) + " samples are not unit directions";
      return r;
    }
  }

  // Expected: N × ∫ pdf over each cell.
  const CellIntegrator integrator(c, [&](double cos_theta, double phi) {
    Values v{};
    v[0] = model.pdf(wo, direction_at(cos_theta, phi));
    return v;
  });
  std::vector<double> expected(n_cells);
  for (int j = 0; j < c.cos_bins; ++j)
    for (int i = 0; i < c.phi_bins; ++i)
      expected[static_cast<size_t>(j) * c.phi_bins + i] = integrator.cell(j, i)[0];
  r.pdf_integral = std::accumulate(expected.begin(), expected.end(), 0.0);
  if (r.pdf_integral > 1.1) {
    r.hard_failure = "pdf integrates to " + std::to_string(r.pdf_integral) + " > 1.1";
    return r;
  }
  for (double& e : expected) e *= static_cast<double>(c.samples);

  // Pool the cells in order of increasing expectation until each group expects min_expected.
  std::vector<size_t> order(n_cells);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  std::vector<std::pair<double, size_t>> contributions;
  double pooled_obs = 0.0, pooled_exp = 0.0;
  int groups = 0;
  for (size_t cell : order) {
    const double o = observed[cell], e = expected[cell];
    if (e == 0.0) {
      if (o > 0.0) {
        r.hard_failure = std::to_string(static_cast<int64_t>(o)) + " samples in " +
                         cell_name(c, cell) + " where pdf integrates to 0";
        return r;
      }
      continue;
    }
    if (e < c.min_expected) {
      pooled_obs += o;
      pooled_exp += e;
      if (pooled_exp >= c.min_expected) {
        r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++groups;
        pooled_obs = pooled_exp = 0.0;
      }
      continue;
    }
    const double term = (o - e) * (o - e) / e;
    r.statistic += term;
    contributions.push_back({term, cell});
    ++groups;
  }
  if (pooled_exp > 0.0) {  // the remainder forms one last group
    r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++groups;
  }
  r.dof = std::max(0, groups - 1);
  r.p_value = chi2_survival(r.statistic, r.dof);

  std::sort(contributions.rbegin(), contributions.rend());
  for (size_t t = 0; t < std::min<size_t>(5, contributions.size()); ++t) {
    const size_t cell = contributions[t].second;
    char buf[256];
    std::snprintf(buf, sizeof buf, "\n    %s observed %.0f expected %.1f (chi2 term %.1f)",
                  cell_name(c, cell).c_str(), observed[cell], expected[cell],
                  contributions[t].first);
    r.worst_cells += buf;
  }
  return r;
}

Albedo quadrature_albedo(const BxDF& model, const Vec3& wo, const Chi2Config& c) {
  // Six channels: reflected r, g, b (wi on wo's side), then transmitted r, g, b.
  const CellIntegrator integrator(c, [&](double cos_theta, double phi) {
    const Vec3 wi = direction_at(cos_theta, phi);
    const RGB f = model.f(wo, wi);
    const int side = wi.z * wo.z > 0.0f ? 0 : 3;
    Values v{};
    for (int ch = 0; ch < 3; ++ch) v[side + ch] = f[ch] * std::fabs(cos_theta);
    return v;
  });
  Values total{};
  for (int j = 0; j < c.cos_bins; ++j)
    for (int i = 0; i < c.phi_bins; ++i) total = total + integrator.cell(j, i);
  Albedo a;
  for (int ch = 0; ch < 3; ++ch) {
    a.reflected[ch] = static_cast<float>(total[ch]);
    a.transmitted[ch] = static_cast<float>(total[ch + 3]);
  }
  return a;
}

}  // namespace bxdf::test

#include "sphere_chi2.h"

#include <algorithm>
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
// The horizon row is evaluated this far above and below z = 0, so that each hemisphere's half
// of the horizon cell is integrated with its own one-sided values (most reflection pdfs jump to
// 0 there; Simpson across the jump would misjudge the cell).
constexpr float kHorizonOffset = 1e-6f;

// Composite Simpson weights 1 4 2 4 ... 4 1 for n (even) sub-intervals.
double simpson_weight(int m, int n) { return (m == 0 || m == n) ? 1.0 : (m % 2 ? 4.0 : 2.0); }

// The lattice of integration nodes: cos_bins·res + 1 rows in cosθ (plus a second, lower-side
// copy of the horizon row) by phi_bins·res + 1 columns in φ.
class Lattice {
 public:
  explicit Lattice(const Chi2Config& c)
      : c_(c), rows_(c.cos_bins * c.integration_res + 1), cols_(c.phi_bins * c.integration_res + 1),
        horizon_row_(c.cos_bins * c.integration_res / 2) {}

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int horizon_row() const { return horizon_row_; }
  double h_phi() const { return kTwoPi / (cols_ - 1); }
  double h_cos() const { return 2.0 / (rows_ - 1); }

  // cos θ of row k; `lower` picks the below-horizon copy of the horizon row.
  float cos_of_row(int k, bool lower) const {
    if (k == horizon_row_) return lower ? -kHorizonOffset : kHorizonOffset;
    return static_cast<float>(-1.0 + h_cos() * k);
  }

  // Fills dirs with the row's directions (x, y, z arrays of cols()).
  void row_directions(int k, bool lower, std::vector<float>& x, std::vector<float>& y,
                      std::vector<float>& z) const {
    const float ct = cos_of_row(k, lower);
    const float st = std::sqrt(std::max(0.0f, 1.0f - ct * ct));
    x.resize(cols_);
    y.resize(cols_);
    z.resize(cols_);
    for (int m = 0; m < cols_; ++m) {
      const double phi = h_phi() * m;
      x[m] = st * static_cast<float>(std::cos(phi));
      y[m] = st * static_cast<float>(std::sin(phi));
      z[m] = ct;
    }
  }

  // Integrates `channels` functions, given per lattice row, into per-cell integrals
  // (cos_bins × phi_bins, row-major in cos) for each channel. `row_values(k, lower, out)`
  // writes row k's values channel after channel: out[ch * cols() + m].
  std::vector<std::vector<double>> integrate(
      int channels, const std::function<void(int, bool, std::vector<double>&)>& row_values) const {
    const int res = c_.integration_res;
    const size_t nphi = static_cast<size_t>(c_.phi_bins);
    // Per row slot and channel: the φ-integral over each φ bin. The lower-side copy of the
    // horizon row lives at slot rows_.
    std::vector<double> by_phi(static_cast<size_t>(rows_ + 1) * channels * nphi);
    std::vector<double> values;
    auto at = [&](int slot, int ch, int i) -> double& {
      return by_phi[(static_cast<size_t>(slot) * channels + ch) * nphi + i];
    };
    auto phi_integrals = [&](int slot, int k, bool lower) {
      row_values(k, lower, values);
      for (int ch = 0; ch < channels; ++ch) {
        const double* v = values.data() + static_cast<size_t>(ch) * cols_;
        for (int i = 0; i < c_.phi_bins; ++i) {
          double s = 0.0;
          for (int m = 0; m <= res; ++m) s += simpson_weight(m, res) * v[i * res + m];
          at(slot, ch, i) = s * h_phi() / 3.0;
        }
      }
    };
    for (int k = 0; k < rows_; ++k) phi_integrals(k, k, false);
    phi_integrals(rows_, horizon_row_, true);

    auto slot_of = [&](int k, bool lower) { return (lower && k == horizon_row_) ? rows_ : k; };
    // Simpson over rows [k0, k0 + n]; `lower` selects the horizon row's lower copy.
    auto cos_integral = [&](int ch, int i, int k0, int n, bool lower) {
      double s = 0.0;
      for (int a = 0; a <= n; ++a) s += simpson_weight(a, n) * at(slot_of(k0 + a, lower), ch, i);
      return s * h_cos() / 3.0;
    };
    std::vector<std::vector<double>> cells(
        channels, std::vector<double>(static_cast<size_t>(c_.cos_bins) * nphi));
    const int mid = c_.cos_bins / 2;
    for (int ch = 0; ch < channels; ++ch) {
      for (int j = 0; j < c_.cos_bins; ++j) {
        for (int i = 0; i < c_.phi_bins; ++i) {
          const double v = j == mid ? cos_integral(ch, i, horizon_row_ - res / 2, res / 2, true) +
                                          cos_integral(ch, i, horizon_row_, res / 2, false)
                                    : cos_integral(ch, i, j * res, res, false);
          cells[ch][static_cast<size_t>(j) * nphi + i] = v;
        }
      }
    }
    return cells;
  }

 private:
  Chi2Config c_;
  int rows_, cols_, horizon_row_;
};

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
      model.sample_f_batch(n, {wox.data(), woy.data(), woz.data()}, u1.data(), u2.data(),
                           {x.data(), y.data(), z.data()}, {fr.data(), fg.data(), fb.data()},
                           pdf.data());
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
  const Lattice lattice(c);
  std::vector<float> x, y, z, wox(lattice.cols(), wo.x), woy(lattice.cols(), wo.y),
      woz(lattice.cols(), wo.z), p(lattice.cols());
  std::vector<double> expected =
      lattice.integrate(1, [&](int k, bool lower, std::vector<double>& v) {
        lattice.row_directions(k, lower, x, y, z);
        model.pdf_batch(static_cast<size_t>(lattice.cols()), {wox.data(), woy.data(), woz.data()},
                        {x.data(), y.data(), z.data()}, p.data());
        v.assign(p.begin(), p.end());
      })[0];
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
  const Lattice lattice(c);
  const size_t n = static_cast<size_t>(lattice.cols());
  std::vector<float> x, y, z, wox(n, wo.x), woy(n, wo.y), woz(n, wo.z), fr(n), fg(n), fb(n);
  // Six channels: reflected r, g, b (wi on wo's side), then transmitted r, g, b.
  const std::vector<std::vector<double>> cells =
      lattice.integrate(6, [&](int k, bool lower, std::vector<double>& v) {
        lattice.row_directions(k, lower, x, y, z);
        model.f_batch(n, {wox.data(), woy.data(), woz.data()}, {x.data(), y.data(), z.data()},
                      {fr.data(), fg.data(), fb.data()});
        v.assign(6 * n, 0.0);
        for (size_t m = 0; m < n; ++m) {
          const size_t side = (z[m] * wo.z > 0.0f) ? 0 : 3;
          const double cosine = std::fabs(z[m]);
          v[(side + 0) * n + m] = fr[m] * cosine;
          v[(side + 1) * n + m] = fg[m] * cosine;
          v[(side + 2) * n + m] = fb[m] * cosine;
        }
      });
  Albedo a;
  for (int ch = 0; ch < 3; ++ch) {
    a.reflected[ch] = static_cast<float>(std::accumulate(cells[ch].begin(), cells[ch].end(), 0.0));
    a.transmitted[ch] =
        static_cast<float>(std::accumulate(cells[ch + 3].begin(), cells[ch + 3].end(), 0.0));
  }
  return a;
}

}  // namespace bxdf::test

#include "bxdf/models/lafortune.h"

#include <cmath>
#include <sstream>

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

namespace {

uint32_t lafortune_flags(const RGB& diffuse) {
  return kReflection | kGlossy | (diffuse.is_black() ? 0u : static_cast<uint32_t>(kDiffuse));
}

// A rough albedo of one lobe channel, averaged over cosine-weighted ωo (an 8 × 8 grid), used
// only to share samples between the parts. For one ωo, with v = C ⊙ ωo, the lobe is
// |v|^n cos^n α about v̂, and ∫ cos^n α cos θi dωi = v̂.z 2π/(n + 2) when the lobe lies above
// the horizon (the transverse part of ∫ cos^n α ωi dωi cancels); clipping is ignored.
double estimated_lobe_albedo(const LafortuneLobe& l, int c) {
  constexpr int kSide = 8;
  const double n = l.exponent[c];
  double sum = 0.0;
  for (int i = 0; i < kSide; ++i) {
    for (int j = 0; j < kSide; ++j) {
      const Vec3 wo = sample_cosine_hemisphere(Point2((i + 0.5f) / kSide, (j + 0.5f) / kSide));
      const double vx = l.cx[c] * wo.x, vy = l.cy[c] * wo.y, vz = l.cz[c] * wo.z;
      const double len = std::sqrt(vx * vx + vy * vy + vz * vz);
      if (!(len > 0.0) || vz <= 0.0) continue;
      sum += std::pow(len, n) * (2.0 * static_cast<double>(kPi) / (n + 2.0)) * (vz / len);
    }
  }
  return sum / (kSide * kSide);
}

void check_peak(const LafortuneLobe& l, size_t index) {
  for (int c = 0; c < 3; ++c) {
    const double c_max = std::max({std::fabs(l.cx[c]), std::fabs(l.cy[c]), std::fabs(l.cz[c])});
    const double peak = std::pow(c_max, static_cast<double>(l.exponent[c]));
    if (!(peak <= Lafortune::kMaxPeak)) {
      const char channel = "rgb"[c];
      std::ostringstream os;
      os << "lafortune: lobes[" << index << "] channel " << channel
         << ": peak value max(|cx|, |cy|, |cz|)^exponent = " << c_max << "^" << l.exponent[c]
         << " = " << peak << " is out of range; valid: [0, " << Lafortune::kMaxPeak
         << "] (lower the exponent or the coefficients)";
      throw ParameterError(os.str());
    }
  }
}

}  // namespace

Lafortune::Lafortune(const RGB& diffuse, std::vector<LafortuneLobe> lobes)
    : BxDFImpl(lafortune_flags(diffuse)), diffuse_over_pi_(diffuse * kInvPi) {
  std::vector<double> weights;
  double lobe_total = 0.0;
  for (size_t j = 0; j < lobes.size(); ++j) {
    const LafortuneLobe& shape = lobes[j];
    check_peak(shape, j);
    Lobe l;
    l.shape = shape;
    l.mean_c = Vec3(shape.cx.average(), shape.cy.average(), shape.cz.average());
    l.mean_exponent = shape.exponent.average();
    lobes_.push_back(l);
    double w = 0.0;  // the channel average: every channel's lobe deserves samples
    for (int c = 0; c < 3; ++c) w += estimated_lobe_albedo(shape, c) / 3.0;
    weights.push_back(w);
    lobe_total += w;
  }
  if (!(lobe_total > 0.0)) return;  // nothing to aim at: cosine sampling only

  const double diffuse_weight = diffuse.average();
  diffuse_probability_ = static_cast<float>(
      std::max<double>(kMinDiffuseProbability, diffuse_weight / (diffuse_weight + lobe_total)));
  // Lay the lobes' slices end to end after the diffuse one; the last lobe that gets any share
  // ends exactly at 1 so that rounding leaves no gap.
  size_t last = 0;
  for (size_t j = 0; j < lobes_.size(); ++j)
    if (weights[j] > 0.0) last = j;
  const double lobe_share = 1.0 - diffuse_probability_;
  double cdf = diffuse_probability_;
  for (size_t j = 0; j < lobes_.size(); ++j) {
    Lobe& l = lobes_[j];
    l.cdf_lo = static_cast<float>(cdf);
    cdf += lobe_share * weights[j] / lobe_total;
    l.cdf_hi = j >= last ? 1.0f : static_cast<float>(cdf);
    l.probability = l.cdf_hi - l.cdf_lo;
  }
}

ModelInfo lafortune_model() {
  // Default: one Phong-like lobe about the mirror direction with C = (−0.95, −0.95, 0.95),
  // n = 10: peak 0.95^10 ≈ 0.60, lobe albedo ≈ 0.31 at normal incidence, so with diffuse 0.5
  // the default reflects ≈ 0.8 of normally incident light.
  const RGBValue default_cxy = {-0.95, -0.95, -0.95}, default_cz = {0.95, 0.95, 0.95},
                 default_n = {10.0, 10.0, 10.0};
  ParamSet default_lobe;
  default_lobe.set("cx", default_cxy);
  default_lobe.set("cy", default_cxy);
  default_lobe.set("cz", default_cz);
  default_lobe.set("exponent", default_n);

  ModelInfo m;
  m.name = "lafortune";
  m.doc = "Lafortune generalised cosine lobes plus a diffuse term (fits measured data)";
  m.params = {
      rgb_param("diffuse", {0.5, 0.5, 0.5}, 0.0, 1.0, "Diffuse reflectance rho_d"),
      list_param(
          "lobes", {default_lobe},
          {
              per_channel(rgb_param("cx", default_cxy, -100.0, 100.0, "Lobe coefficient Cx (on wo.x wi.x)")),
              per_channel(rgb_param("cy", default_cxy, -100.0, 100.0, "Lobe coefficient Cy (on wo.y wi.y)")),
              per_channel(rgb_param("cz", default_cz, -100.0, 100.0, "Lobe coefficient Cz (on wo.z wi.z)")),
              per_channel(rgb_param("exponent", default_n, 0.0, 10000.0, "Lobe exponent n")),
          },
          "Lobes max(0, Cx wo.x wi.x + Cy wo.y wi.y + Cz wo.z wi.z)^n; Cx = Cy = -Cz is Phong. "
          "Each lobe's peak max(|Cx|, |Cy|, |Cz|)^n must stay <= 1e20"),
  };
  m.create = [](const ParamSet& p) {
    std::vector<LafortuneLobe> lobes;
    for (const ParamSet& l : p.list("lobes"))
      lobes.push_back({to_rgb(l.rgb("cx")), to_rgb(l.rgb("cy")), to_rgb(l.rgb("cz")),
                       to_rgb(l.rgb("exponent"))});
    return std::make_unique<Lafortune>(to_rgb(p.rgb("diffuse")), std::move(lobes));
  };
  return m;
}

}  // namespace bxdf

#include "bxdf/microfacet/refraction_cover.h"

#include <algorithm>
#include <cmath>

#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/cycles_lobes.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

namespace bxdf {
namespace cycles {

namespace {

// kRefractionCoverTable[distribution][√α index][ln η index][cos θo index]
#include "refraction_cover_table.inc"

// A continuous table coordinate in [0, steps − 1]; 0 for NaN.
float grid_coordinate(float x, int steps) {
  const float hi = static_cast<float>(steps - 1);
  return x > 0.0f ? std::min(x, hi) : 0.0f;
}

template <class Distribution>
float estimate_share(float alpha, float eta, float cos_o, int strata, uint64_t seed) {
  const RefractionLobe<Distribution> lobe{Distribution(alpha, alpha)};
  const Vec3 wo(std::sqrt(std::max(0.0f, 1.0f - cos_o * cos_o)), 0.0f, cos_o);
  PCG32 rng(seed);
  double a = 0.0, b = 0.0;
  const float n_strata = static_cast<float>(strata);
  for (int y = 0; y < strata; ++y) {
    for (int x = 0; x < strata; ++x) {
      const Point2 u((static_cast<float>(x) + rng.uniform()) / n_strata,
                     (static_cast<float>(y) + rng.uniform()) / n_strata);
      // A: the facet sampler alone.
      Vec3 wi;
      if (lobe.sample(wo, u, eta, &wi)) {
        const float pdf = lobe.pdf(wo, wi, eta);
        if (pdf > 0.0f) {
          const double w = double(lobe.f(wo, wi, eta)) * std::fabs(wi.z) / pdf;
          a += w * w;
        }
      }
      // B: cover samples where the facet sampler has no density.
      const Vec3 wc = sample_refraction_cover(u);
      if (wc.z < 0.0f && lobe.pdf(wo, wc, eta) == 0.0f) {
        const double w = double(lobe.f(wo, wc, eta)) * -wc.z / refraction_cover_pdf(wc);
        b += w * w;
      }
    }
  }
  const double n = double(strata) * strata;
  a /= n;
  b /= n;
  // Where the lobe transmits next to nothing either way (total internal reflection of a smooth
  // lobe) the share does not matter; the least keeps the table smooth around it.
  const double s = a + b > 1e-6 ? std::sqrt(b) / (std::sqrt(a) + std::sqrt(b)) : 0.0;
  return std::clamp(static_cast<float>(s), kCoverShareMin, kCoverShareMax);
}

}  // namespace

float estimate_cover_share(CoverDistribution d, float alpha, float eta, float cos_o, int strata,
                           uint64_t seed) {
  return d == CoverDistribution::kGGX
             ? estimate_share<microfacet::GGX>(alpha, eta, cos_o, strata, seed)
             : estimate_share<microfacet::Beckmann>(alpha, eta, cos_o, strata, seed);
}

float cover_table_alpha(int i) {
  const float r = static_cast<float>(i) / static_cast<float>(kCoverRoughnessSteps - 1);
  return r * r;
}

float cover_table_eta(int j) {
  const float t = static_cast<float>(j) / static_cast<float>(kCoverLogEtaSteps - 1);
  return std::exp(kCoverLogEtaMax * (2.0f * t - 1.0f));
}

float cover_table_cos(int k) {
  return (static_cast<float>(k) + 0.5f) / static_cast<float>(kCoverCosSteps);
}

float cover_table_value(CoverDistribution d, int i, int j, int k) {
  return kRefractionCoverTable[static_cast<int>(d)][i][j][k];
}

float refraction_cover_share(CoverDistribution d, float alpha, float eta, float cos_o) {
  const float r = grid_coordinate(std::sqrt(std::max(alpha, 0.0f)) *
                                      static_cast<float>(kCoverRoughnessSteps - 1),
                                  kCoverRoughnessSteps);
  const float log_eta = eta > 0.0f ? std::log(eta) : -kCoverLogEtaMax;
  const float e = grid_coordinate((log_eta / kCoverLogEtaMax + 1.0f) * 0.5f *
                                      static_cast<float>(kCoverLogEtaSteps - 1),
                                  kCoverLogEtaSteps);
  const float c = grid_coordinate(cos_o * static_cast<float>(kCoverCosSteps) - 0.5f,
                                  kCoverCosSteps);
  const int i = std::min(static_cast<int>(r), kCoverRoughnessSteps - 2);
  const int j = std::min(static_cast<int>(e), kCoverLogEtaSteps - 2);
  const int k = std::min(static_cast<int>(c), kCoverCosSteps - 2);
  const float fr = r - static_cast<float>(i), fe = e - static_cast<float>(j),
              fc = c - static_cast<float>(k);
  const auto& t = kRefractionCoverTable[static_cast<int>(d)];
  const auto lerp = [](float a, float b, float x) { return a + (b - a) * x; };
  const auto along_cos = [&](int ii, int jj) {
    return lerp(t[ii][jj][k], t[ii][jj][k + 1], fc);
  };
  const float s = lerp(lerp(along_cos(i, j), along_cos(i, j + 1), fe),
                       lerp(along_cos(i + 1, j), along_cos(i + 1, j + 1), fe), fr);
  return std::clamp(s, kCoverShareMin, kCoverShareMax);
}

}  // namespace cycles
}  // namespace bxdf

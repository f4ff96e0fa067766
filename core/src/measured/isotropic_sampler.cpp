#include "bxdf/measured/isotropic_sampler.h"

#include <algorithm>

#include "bxdf/sampling.h"

namespace bxdf {

namespace {

constexpr float kThetaCell = kPiOver2 / IsotropicSampler::kThetaICells;
constexpr float kPhiCell = kPi / IsotropicSampler::kPhiCells;
// The last node sits just above the horizon, where the BRDF is still defined.
constexpr float kLastNodeTheta = kPiOver2 - 1e-3f;

float node_theta(int k) {
  return kLastNodeTheta * static_cast<float>(k) / (IsotropicSampler::kThetaONodes - 1);
}

// Index of the interval of a CDF (size n + 1, cdf[0] = 0, cdf[n] = 1) that holds u, and u
// rescaled to [0, 1) within it.
int sample_cdf(const float* cdf, int n, float* u) {
  const float* it = std::upper_bound(cdf, cdf + n + 1, *u);
  const int i = clamp(static_cast<int>(it - cdf) - 1, 0, n - 1);
  const float width = cdf[i + 1] - cdf[i];
  *u = width > 0.0f ? clamp((*u - cdf[i]) / width, 0.0f, 0x1.fffffep-1f) : 0.5f;
  return i;
}

float theta_of(const Vec3& w) { return std::atan2(std::sqrt(w.x * w.x + w.y * w.y), w.z); }

}  // namespace

IsotropicSampler::IsotropicSampler(const BRDF& f) {
  for (int i = 0; i <= kThetaICells; ++i) cos_edge_[i] = std::cos(kThetaCell * static_cast<float>(i));
  cos_edge_[kThetaICells] = 0.0f;
  nodes_.resize(kThetaONodes);
  constexpr int kSub = 2;  // sub-samples per cell side
  for (int k = 0; k < kThetaONodes; ++k) {
    Node& n = nodes_[static_cast<size_t>(k)];
    const float to = node_theta(k);
    const Vec3 wo(std::sin(to), 0.0f, std::cos(to));
    std::vector<double> weight(size_t(kThetaICells) * kPhiCells, 0.0);
    double total = 0.0;
    for (int i = 0; i < kThetaICells; ++i) {
      const float c0 = cos_edge_[i], c1 = cos_edge_[i + 1];
      const float solid_angle = (c0 - c1) * kPhiCell;
      for (int j = 0; j < kPhiCells; ++j) {
        double sum = 0.0;
        for (int a = 0; a < kSub; ++a) {
          for (int b = 0; b < kSub; ++b) {
            // Midpoints of a kSub × kSub split of the cell, uniform in (cos θ, φ).
            const float ct = c0 + (c1 - c0) * (static_cast<float>(a) + 0.5f) / kSub;
            const float st = safe_sqrt(1.0f - ct * ct);
            const float phi = kPhiCell * (static_cast<float>(j) + (static_cast<float>(b) + 0.5f) / kSub);
            const Vec3 wi(st * std::cos(phi), st * std::sin(phi), std::max(ct, 1e-4f));
            const RGB v = f(wo, normalize(wi));
            const float s = v.r + v.g + v.b;
            if (s > 0.0f && std::isfinite(s)) sum += static_cast<double>(s) * ct;
          }
        }
        const double w = sum / (kSub * kSub) * solid_angle;
        weight[size_t(i) * kPhiCells + size_t(j)] = w;
        total += w;
      }
    }
    if (!(total > 0.0)) continue;  // black node: cosine sampling
    n.empty = false;
    n.marginal_cdf.assign(kThetaICells + 1, 0.0f);
    n.conditional_cdf.assign(size_t(kThetaICells) * (kPhiCells + 1), 0.0f);
    n.density.assign(size_t(kThetaICells) * kPhiCells, 0.0f);
    double run = 0.0;
    for (int i = 0; i < kThetaICells; ++i) {
      double row = 0.0;
      for (int j = 0; j < kPhiCells; ++j) row += weight[size_t(i) * kPhiCells + size_t(j)];
      float* cc = &n.conditional_cdf[size_t(i) * (kPhiCells + 1)];
      double acc = 0.0;
      for (int j = 0; j < kPhiCells; ++j) {
        const double w = weight[size_t(i) * kPhiCells + size_t(j)];
        acc += w;
        cc[j + 1] = row > 0.0 ? static_cast<float>(acc / row) : static_cast<float>(j + 1) / kPhiCells;
        // Probability of the cell, split over its two mirror images, per unit solid angle.
        const double solid_angle = static_cast<double>(cos_edge_[i] - cos_edge_[i + 1]) * kPhiCell;
        n.density[size_t(i) * kPhiCells + size_t(j)] = static_cast<float>(w / total / (2.0 * solid_angle));
      }
      cc[kPhiCells] = 1.0f;
      run += row;
      n.marginal_cdf[size_t(i) + 1] = static_cast<float>(run / total);
    }
    n.marginal_cdf[kThetaICells] = 1.0f;
  }
}

void IsotropicSampler::node_position(float cos_theta_o, int* k, float* t) const {
  const float to = std::acos(clamp(cos_theta_o, 0.0f, 1.0f));
  const float x = clamp(to / kLastNodeTheta * (kThetaONodes - 1), 0.0f,
                        static_cast<float>(kThetaONodes - 1));
  *k = std::min(static_cast<int>(x), kThetaONodes - 2);
  *t = x - static_cast<float>(*k);
}

Vec3 IsotropicSampler::sample_node(const Node& n, Point2 u) const {
  if (n.empty) return sample_cosine_hemisphere(u);
  // u.y first picks the mirror side, then the Δφ cell; u.x picks the θi row.
  float sign = 1.0f;
  if (u.y < 0.5f) {
    sign = -1.0f;
    u.y = u.y * 2.0f;
  } else {
    u.y = (u.y - 0.5f) * 2.0f;
  }
  u.y = std::min(u.y, 0x1.fffffep-1f);
  const int i = sample_cdf(n.marginal_cdf.data(), kThetaICells, &u.x);
  const int j = sample_cdf(&n.conditional_cdf[size_t(i) * (kPhiCells + 1)], kPhiCells, &u.y);
  const float ct = cos_edge_[i] + (cos_edge_[i + 1] - cos_edge_[i]) * u.x;
  const float st = safe_sqrt(1.0f - ct * ct);
  const float phi = sign * kPhiCell * (static_cast<float>(j) + u.y);
  return {st * std::cos(phi), st * std::sin(phi), ct};
}

float IsotropicSampler::node_density(const Node& n, const Vec3& wi_local) const {
  if (n.empty) return cosine_hemisphere_pdf(wi_local.z);
  const float ti = theta_of(wi_local);
  const int i = clamp(static_cast<int>(ti / kThetaCell), 0, kThetaICells - 1);
  const float phi = std::atan2(std::fabs(wi_local.y), wi_local.x);
  const int j = clamp(static_cast<int>(phi / kPhiCell), 0, kPhiCells - 1);
  return n.density[size_t(i) * kPhiCells + size_t(j)];
}

Vec3 IsotropicSampler::sample(const Vec3& wo, Point2 u) const {
  if (u.y < kCosineFraction) {
    u.y = std::min(u.y / kCosineFraction, 0x1.fffffep-1f);
    return sample_cosine_hemisphere(u);
  }
  u.y = std::min((u.y - kCosineFraction) / (1.0f - kCosineFraction), 0x1.fffffep-1f);
  int k;
  float t;
  node_position(wo.z, &k, &t);
  const Node* node;
  if (u.y < 1.0f - t) {
    node = &nodes_[size_t(k)];
    u.y = std::min(u.y / (1.0f - t), 0x1.fffffep-1f);
  } else {
    node = &nodes_[size_t(k) + 1];
    u.y = std::min((u.y - (1.0f - t)) / t, 0x1.fffffep-1f);
  }
  const Vec3 local = sample_node(*node, u);
  // Rotate from wo's azimuth frame (wo in the xz plane) to the shading frame.
  const float r = std::sqrt(wo.x * wo.x + wo.y * wo.y);
  const float c = r > 0.0f ? wo.x / r : 1.0f, s = r > 0.0f ? wo.y / r : 0.0f;
  return {c * local.x - s * local.y, s * local.x + c * local.y, local.z};
}

float IsotropicSampler::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wi.z <= 0.0f) return 0.0f;
  const float r = std::sqrt(wo.x * wo.x + wo.y * wo.y);
  const float c = r > 0.0f ? wo.x / r : 1.0f, s = r > 0.0f ? wo.y / r : 0.0f;
  const Vec3 local(c * wi.x + s * wi.y, -s * wi.x + c * wi.y, wi.z);
  int k;
  float t;
  node_position(wo.z, &k, &t);
  float table = (1.0f - t) * node_density(nodes_[size_t(k)], local);
  if (t > 0.0f) table += t * node_density(nodes_[size_t(k) + 1], local);
  return kCosineFraction * cosine_hemisphere_pdf(wi.z) + (1.0f - kCosineFraction) * table;
}

}  // namespace bxdf

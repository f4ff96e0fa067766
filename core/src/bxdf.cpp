#include "bxdf/bxdf.h"

#include <cmath>
#include <vector>

#include "bxdf/rng.h"
#include "bxdf/sampling.h"

namespace bxdf {

namespace {

// Stratified point i of an n = side × side grid, jittered by rng.
Point2 stratified(int i, int side, PCG32& rng) {
  const float inv = 1.0f / static_cast<float>(side);
  const float x = (static_cast<float>(i % side) + rng.uniform()) * inv;
  const float y = (static_cast<float>(i / side) + rng.uniform()) * inv;
  return {std::min(x, 0x1.fffffep-1f), std::min(y, 0x1.fffffep-1f)};
}

int grid_side(int n_samples) {
  return std::max(1, static_cast<int>(std::sqrt(static_cast<double>(std::max(1, n_samples)))));
}

}  // namespace

RGB BxDF::rho_hd(const Vec3& wo_in, int n_samples, uint64_t seed) const {
  Vec3 wo = wo_in;
  if (!normalize_direction(wo) || n_samples <= 0) return RGB(0.0f);
  const int side = grid_side(n_samples);
  const int n = side * side;
  PCG32 rng(seed);
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const BxDFSample s = sample_f(wo, stratified(i, side, rng));
    if (!s.valid()) continue;
    const float w = std::fabs(s.wi.z) / s.pdf;
    for (int c = 0; c < 3; ++c) sum[c] += static_cast<double>(s.f[c] * w);
  }
  return sanitize_nonnegative(RGB(static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n),
                                  static_cast<float>(sum[2] / n)));
}

RGB BxDF::rho_hh(int n_samples, uint64_t seed) const {
  if (n_samples <= 0) return RGB(0.0f);
  const int side = grid_side(n_samples);
  const int n = side * side;
  PCG32 rng(seed, 0x9e3779b97f4a7c15ULL);
  // The two grids are decorrelated by shuffling the outgoing strata.
  std::vector<int> perm(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) perm[static_cast<size_t>(i)] = i;
  for (int i = n - 1; i > 0; --i)
    std::swap(perm[static_cast<size_t>(i)], perm[rng.bounded(static_cast<uint32_t>(i + 1))]);
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const Vec3 wo = sample_uniform_hemisphere(stratified(perm[static_cast<size_t>(i)], side, rng));
    const BxDFSample s = sample_f(wo, stratified(i, side, rng));
    if (!s.valid()) continue;
    const float w = std::fabs(s.wi.z) * std::fabs(wo.z) / (s.pdf * uniform_hemisphere_pdf());
    for (int c = 0; c < 3; ++c) sum[c] += static_cast<double>(s.f[c] * w);
  }
  const double norm = 1.0 / (kPi * n);
  return sanitize_nonnegative(RGB(static_cast<float>(sum[0] * norm),
                                  static_cast<float>(sum[1] * norm),
                                  static_cast<float>(sum[2] * norm)));
}

std::string flags_to_string(uint32_t flags) {
  static const std::pair<uint32_t, const char*> names[] = {
      {kReflection, "reflection"}, {kTransmission, "transmission"}, {kDiffuse, "diffuse"},
      {kGlossy, "glossy"},         {kSpecular, "specular"}};
  std::string s;
  for (const auto& [bit, name] : names) {
    if (flags & bit) s += (s.empty() ? "" : "|") + std::string(name);
  }
  return s;
}

}  // namespace bxdf

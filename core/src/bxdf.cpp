#include "bxdf/bxdf.h"

#include <cmath>

#include "bxdf/rng.h"
#include "bxdf/sampling.h"

namespace bxdf {

const std::string& BxDF::model_name() const {
  static const std::string none;
  return identity_ ? identity_->name : none;
}

const ParamSet& BxDF::params() const {
  static const ParamSet none;
  return identity_ ? identity_->params : none;
}

void BxDF::set_identity(std::string name, ParamSet params) {
  identity_ = std::make_unique<const Identity>(Identity{std::move(name), std::move(params)});
}

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

// A pseudo-random permutation of [0, n) evaluated one index at a time (Kensler 2013,
// "Correlated Multi-Jittered Sampling", cycle-walking a hash on the next power of two): no table,
// so rho_hh needs no memory however many samples it takes.
uint32_t permuted_index(uint32_t i, uint32_t n, uint32_t p) {
  uint32_t w = n - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= p;
    i *= 0xe170893du;
    i ^= p >> 16;
    i ^= (i & w) >> 4;
    i ^= p >> 8;
    i *= 0x0929eb3fu;
    i ^= p >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | p >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return static_cast<uint32_t>((uint64_t(i) + p) % n);
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
    const BxDFSample s = sample_f_exact(wo, stratified(i, side, rng));
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
  // The two grids are decorrelated by permuting the outgoing strata.
  const uint32_t perm_seed = rng.next_u32();
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const int stratum = static_cast<int>(
        permuted_index(static_cast<uint32_t>(i), static_cast<uint32_t>(n), perm_seed));
    const Vec3 wo = sample_uniform_hemisphere(stratified(stratum, side, rng));
    const BxDFSample s = sample_f_exact(wo, stratified(i, side, rng));
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

// Warps from the unit square to disks, hemispheres and spheres, each with its pdf
// (per unit solid angle for directions).
#pragma once

#include "bxdf/math.h"

namespace bxdf {

// Shirley–Chiu concentric map: area-preserving, low distortion. sincosf was 2% of a diffuse
// scene's render; the map's angles need no range reduction, so their polynomial is inline. The
// angle is π/4 · t in one half of the square and π/2 − π/4 · t in the other (|t| <= 1), whose
// cosine and sine are the sine and cosine of π/4 · t. The half is chosen with selects, not a
// branch: which half a sample falls in is a coin toss, so a branch there is mispredicted half
// the time.
inline Point2 sample_concentric_disk(Point2 u) {
  const float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  const bool x_major = std::fabs(ox) > std::fabs(oy);
  const float r = x_major ? ox : oy;
  const float t = r == 0.0f ? 0.0f : (x_major ? oy : ox) / r;  // r = 0 only at the centre
  const SinCos a = sin_cos_within_quarter_pi(kPiOver4 * t);
  const float along = r * a.cos, across = r * a.sin;
  return x_major ? Point2{along, across} : Point2{across, along};
}

// Malley's method: project the concentric disk up to the hemisphere; pdf = cos θ / π.
inline Vec3 sample_cosine_hemisphere(Point2 u) {
  const Point2 d = sample_concentric_disk(u);
  const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
  return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta * kInvPi; }

inline Vec3 sample_uniform_hemisphere(Point2 u) {
  const float z = u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_hemisphere_pdf() { return kInv2Pi; }

inline Vec3 sample_uniform_sphere(Point2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform direction inside a cone of half-angle acos(cos_max) about +z.
inline Vec3 sample_uniform_cone(Point2 u, float cos_max) {
  const float cos_t = (1.0f - u.x) + u.x * cos_max;
  const float sin_t = safe_sqrt(1.0f - cos_t * cos_t);
  const float phi = 2.0f * kPi * u.y;
  return {std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t};
}
inline float uniform_cone_pdf(float cos_max) { return 1.0f / (2.0f * kPi * (1.0f - cos_max)); }

// Sample about +z with density proportional to cos^n(θ): pdf = (n + 1)/(2π) cos^n θ.
inline Vec3 sample_cosine_power(Point2 u, float n) {
  const float cos_t = std::pow(u.x, 1.0f / (n + 1.0f));
  const float sin_t = safe_sqrt(1.0f - cos_t * cos_t);
  const float phi = 2.0f * kPi * u.y;
  return {std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t};
}
inline float cosine_power_pdf(float cos_t, float n) {
  return cos_t > 0.0f ? (n + 1.0f) * kInv2Pi * std::pow(cos_t, n) : 0.0f;
}

// Power heuristic (β = 2) for multiple importance sampling.
inline float power_heuristic(float nf, float f_pdf, float ng, float g_pdf) {
  const float f = nf * f_pdf, g = ng * g_pdf;
  if (f == 0.0f) return 0.0f;
  if (std::isinf(f)) return 1.0f;
  return (f * f) / (f * f + g * g);
}

}  // namespace bxdf

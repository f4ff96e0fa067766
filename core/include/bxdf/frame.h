// The local shading frame: z is the normal, x and y the tangents. The helpers are the
// seed's definitions (cos θ = ω.z, cos φ = ω.x / sin θ, ...), written to stay finite at
// the pole and slightly outside [-1, 1].
#pragma once

#include "bxdf/math.h"

namespace bxdf {

inline float cos_theta(const Vec3& w) { return w.z; }
inline float cos2_theta(const Vec3& w) { return w.z * w.z; }
inline float abs_cos_theta(const Vec3& w) { return std::fabs(w.z); }
inline float sin2_theta(const Vec3& w) { return std::max(0.0f, 1.0f - w.z * w.z); }
inline float sin_theta(const Vec3& w) { return std::sqrt(sin2_theta(w)); }
inline float tan_theta(const Vec3& w) { return sin_theta(w) / cos_theta(w); }
inline float tan2_theta(const Vec3& w) { return sin2_theta(w) / cos2_theta(w); }
inline float cos_phi(const Vec3& w) {
  const float s = sin_theta(w);
  return s == 0.0f ? 1.0f : clamp(w.x / s, -1.0f, 1.0f);
}
inline float sin_phi(const Vec3& w) {
  const float s = sin_theta(w);
  return s == 0.0f ? 0.0f : clamp(w.y / s, -1.0f, 1.0f);
}
inline float cos2_phi(const Vec3& w) { return cos_phi(w) * cos_phi(w); }
inline float sin2_phi(const Vec3& w) { return sin_phi(w) * sin_phi(w); }
inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.0f; }

// Turns a pair over (z → −z on both) when wo is below the surface, as a two-sided reflection
// model does; true when both are then strictly above.
inline bool turn_pair_upward(Vec3* wo, Vec3* wi) {
  if (wo->z < 0.0f) {
    wo->z = -wo->z;
    wi->z = -wi->z;
  }
  return wo->z > 0.0f && wi->z > 0.0f;
}

inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return -wo + n * (2.0f * dot(wo, n)); }

// Refracts wi about n (n on wi's side). eta = eta_i / eta_t. False on total internal reflection.
inline bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt) {
  const float cos_i = dot(n, wi);
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  const float sin2_t = eta * eta * sin2_i;
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  *wt = -wi * eta + n * (eta * cos_i - cos_t);
  return true;
}

// An orthonormal frame (s, t, n); to_local/to_world move directions between it and world space.
struct Frame {
  Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};
  Frame() = default;
  Frame(const Vec3& s_, const Vec3& t_, const Vec3& n_) : s(s_), t(t_), n(n_) {}
  static Frame from_normal(const Vec3& n) {
    Frame f;
    f.n = n;
    coordinate_system(n, &f.s, &f.t);
    return f;
  }
  // Frame with n and the tangent closest to `tangent` (Gram–Schmidt), for anisotropic models.
  static Frame from_normal_tangent(const Vec3& n, const Vec3& tangent) {
    Vec3 s = tangent - n * dot(n, tangent);
    if (!normalize_direction(s)) return from_normal(n);
    return Frame(s, cross(n, s), n);
  }
  Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace bxdf

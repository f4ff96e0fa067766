// Cosine-weighted directions about +z that stay above a second plane, the one of the true
// (geometric) normal `g` of a smooth-shaded triangle, given in the same local frame (g.z > 0).
//
// With shading normals, the part of the cosine lobe that lies below the triangle's plane
// cannot leave the surface: Cycles (bsdf_diffuse_sample) drops such a sample, and on a
// smooth mesh in a furnace those rare lost samples are all of the noise. That part is the
// region x²/cos²δ + y² > 1, x < 0 of the unit disk that Malley's method projects up (x along
// g's tangential part, cos δ = g.z), so its cosine-weighted measure is (1 − g.z)/2. Here the
// disk's half with x < 0 is squeezed along that axis by g.z onto the valid half-ellipse: the
// directions are exactly the valid ones, still drawn through the concentric map, with
// pdf = cos θ/π on the x ≥ 0 side and cos θ/(π g.z) on the other. The estimator f cos θ/pdf
// of a diffuse lobe is then R or R g.z, never 0, and its expectation is unchanged.
#pragma once

#include "bxdf/math.h"
#include "bxdf/sampling.h"

namespace bxdf {

// g's tangential part, normalised, or (0, 0) when g is (nearly) the z axis: no clipping then.
inline Point2 horizon_tilt_axis(const Vec3& g) {
  const float len = std::sqrt(g.x * g.x + g.y * g.y);
  if (!(len > 1e-6f)) return {0.0f, 0.0f};
  return {g.x / len, g.y / len};
}

// The cosine lobe about +z above the plane of unit `g` (g.z > 0), g's tilt axis worked out
// once: a caller that samples the lobe and evaluates its density (BSDF, LoneDiffuse) pays for
// the axis's square root and divisions once, not at every call.
class CosineAbovePlane {
 public:
  CosineAbovePlane() = default;  // the plane of +z: nothing clipped
  explicit CosineAbovePlane(const Vec3& g) : g_(g), axis_(horizon_tilt_axis(g)) {}

  // A direction on the lobe.
  Vec3 sample(Point2 u) const {
    Point2 d = sample_concentric_disk(u);
    const float t = d.x * axis_.x + d.y * axis_.y;
    if (t < 0.0f) {
      const float squeeze = (g_.z - 1.0f) * t;  // moves the point to t·g.z along the axis
      d.x += squeeze * axis_.x;
      d.y += squeeze * axis_.y;
    }
    const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
  }
  // The density of sample() per unit solid angle: 0 below either plane.
  float pdf(const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(dot(wi, g_) > 0.0f)) return 0.0f;
    const bool squeezed = wi.x * axis_.x + wi.y * axis_.y < 0.0f;
    const float p = cosine_hemisphere_pdf(wi.z);
    return squeezed ? p / g_.z : p;
  }

 private:
  Vec3 g_{0.0f, 0.0f, 1.0f};
  Point2 axis_{0.0f, 0.0f};
};

// One sample and one density of the lobe above g's plane.
inline Vec3 sample_cosine_above_plane(Point2 u, const Vec3& g) {
  return CosineAbovePlane(g).sample(u);
}
inline float cosine_above_plane_pdf(const Vec3& wi, const Vec3& g) {
  return CosineAbovePlane(g).pdf(wi);
}

}  // namespace bxdf

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

// A direction on the cosine lobe about +z above the plane of unit `g` (g.z > 0).
inline Vec3 sample_cosine_above_plane(Point2 u, const Vec3& g) {
  Point2 d = sample_concentric_disk(u);
  const Point2 axis = horizon_tilt_axis(g);
  const float t = d.x * axis.x + d.y * axis.y;
  if (t < 0.0f) {
    const float squeeze = (g.z - 1.0f) * t;  // moves the point to t·g.z along the axis
    d.x += squeeze * axis.x;
    d.y += squeeze * axis.y;
  }
  const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
  return {d.x, d.y, z};
}

// The density of sample_cosine_above_plane per unit solid angle: 0 below either plane.
inline float cosine_above_plane_pdf(const Vec3& wi, const Vec3& g) {
  if (!(wi.z > 0.0f) || !(dot(wi, g) > 0.0f)) return 0.0f;
  const Point2 axis = horizon_tilt_axis(g);
  const bool squeezed = wi.x * axis.x + wi.y * axis.y < 0.0f;
  const float p = cosine_hemisphere_pdf(wi.z);
  return squeezed ? p / g.z : p;
}

}  // namespace bxdf

// Uniform sampling of the solid angle a rectangle subtends (Ureña, Fajardo and King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles"), as Cycles samples rectangular area
// lights (rect_light_sample).
#pragma once

#include "bxdf/math.h"

namespace bxdf::render {

// The rectangle centre ± axis_u/2 ± axis_v/2 (axes perpendicular), with what of its frame does
// not depend on the shading point (its corner, unit axes and edge lengths) worked out once, when
// the light is made, instead of at every light sample and every BSDF ray that hits it.
class SphericalRectangle {
 public:
  SphericalRectangle() = default;
  SphericalRectangle(const Vec3& centre, const Vec3& axis_u, const Vec3& axis_v);

  // Picks a point *q on the rectangle whose direction from p is uniform in the solid angle S it
  // subtends there; returns 1/S (0 when p lies in the rectangle's plane).
  float sample(const Vec3& p, Point2 u, Vec3* q) const;
  // 1/S without sampling.
  float pdf(const Vec3& p) const;

 private:
  struct Frame;  // the rectangle seen from a shading point (spherical_rectangle.cpp)
  Frame frame(const Vec3& p) const;

  Vec3 corner_;      // centre − axis_u/2 − axis_v/2
  Vec3 x_, y_, z_;   // axis_u and axis_v made unit, and x × y
  float len_u_ = 0.0f, len_v_ = 0.0f;
};

}  // namespace bxdf::render

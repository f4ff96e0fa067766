// Uniform sampling of the solid angle a rectangle subtends (Ureña, Fajardo and King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles"), as Cycles samples rectangular area
// lights (rect_light_sample).
#pragma once

#include "bxdf/math.h"

namespace bxdf::render {

// The rectangle is centre ± axis_u/2 ± axis_v/2 (axes perpendicular). Picks a point *q on it
// whose direction from p is uniform in the subtended solid angle S; returns 1/S (0 when p lies
// in the rectangle's plane).
float sample_spherical_rectangle(const Vec3& p, const Vec3& centre, const Vec3& axis_u,
                                 const Vec3& axis_v, Point2 u, Vec3* q);
// 1/S without sampling.
float spherical_rectangle_pdf(const Vec3& p, const Vec3& centre, const Vec3& axis_u,
                              const Vec3& axis_v);

}  // namespace bxdf::render

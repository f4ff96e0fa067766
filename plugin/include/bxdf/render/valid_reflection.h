// Cycles 3.4's ensure_valid_reflection (K/closure/bsdf_util.h), which every BSDF closure's
// normal goes through (K/svm/closure.h): a smooth normal that turns away from the viewer, as on
// the silhouette of a smooth-shaded mesh, is bent towards the geometric normal just enough that
// the mirror direction of the view clears the surface. Without it those pixels render black;
// Cycles lights them.
#pragma once

#include "bxdf/math.h"

namespace bxdf::render {

// The normal a closure shades with. ng: the geometric normal on the viewer's side, wo: the unit
// direction towards the viewer, n: the unit shading normal (same side as ng). Returns n itself
// when the reflection of wo about it already rises above min(0.9·(ng·wo), 0.01); else the unit
// normal in the plane of ng and n whose reflection rises exactly that much; ng when none does.
Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& wo, const Vec3& n);

}  // namespace bxdf::render

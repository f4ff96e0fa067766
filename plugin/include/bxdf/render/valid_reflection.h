// Cycles 3.4's ensure_valid_reflection (K/closure/bsdf_util.h), which every BSDF closure's
// normal goes through (K/svm/closure.h): a smooth normal that turns away from the viewer, as on
// the silhouette of a smooth-shaded mesh, is bent towards the geometric normal just enough that
// the mirror direction of the view clears the surface. Without it those pixels render black;
// Cycles lights them.
#pragma once

#include <algorithm>

#include "bxdf/math.h"

namespace bxdf::render {

// ensure_valid_reflection's bending, where n's reflection fell below `threshold`.
Vec3 bend_to_valid_reflection(const Vec3& ng, const Vec3& wo, const Vec3& n, float threshold);

// The normal a closure shades with. ng: the geometric normal on the viewer's side, wo: the unit
// direction towards the viewer, n: the unit shading normal (same side as ng). Returns n itself
// when the reflection of wo about it already rises above min(0.9·(ng·wo), 0.01); else the unit
// normal in the plane of ng and n whose reflection rises exactly that much; ng when none does.
// The test is inline: it runs at every hit and nearly always passes.
inline Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& wo, const Vec3& n) {
  const Vec3 mirrored = n * (2.0f * dot(n, wo)) - wo;
  // The reflection may always be as shallow as the view itself.
  const float threshold = std::min(0.9f * dot(ng, wo), 0.01f);
  if (dot(ng, mirrored) >= threshold) return n;
  return bend_to_valid_reflection(ng, wo, n, threshold);
}

}  // namespace bxdf::render

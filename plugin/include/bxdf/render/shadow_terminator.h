// Cycles' two remedies for the shadow terminator of smooth-shaded low-poly meshes.
// - Geometry offset (K/light/sample.h, shadow_ray_offset): a shadow ray leaves from the point
//   lifted onto the parabolic surface the vertex normals describe, for light directions close
//   to the terminator (how close: the object's offset, default 0.1), so that the flat triangle
//   does not shadow points the smooth surface would light.
// - Shading offset (K/closure/bsdf.h, shift_cos_in, from appleseed): the cosine of the incoming
//   direction is rescaled so that the light falls off before the terminator.
#pragma once

#include <algorithm>
#include <cmath>

#include "bxdf/math.h"

namespace bxdf::render {

// One triangle's vertices and vertex normals, and a point on it by barycentrics b1, b2.
struct SmoothTriangle {
  Vec3 v[3], n[3];
};

// How much of the geometry offset a shadow ray towards unit `wi` gets, in [0, 1]: 0 unless wi
// is close to the terminator (ns, ng as below), as for most light directions, which can then
// skip fetching the triangle. Inline: it runs for every shadow ray.
inline float terminator_offset_amount(const Vec3& ns, const Vec3& ng, const Vec3& wi,
                                      float geometry_offset) {
  if (!(geometry_offset > 0.0f)) return 0.0f;
  const float nl = dot(ns, wi);
  const float ngl = dot(nl < 0.0f ? -ng : ng, wi);  // against the side wi leaves from
  const float anl = std::fabs(nl);
  // Only directions near the terminator are offset, with a smooth transition at the cutoff.
  return anl < geometry_offset ? clamp(2.0f - (ngl + anl) / geometry_offset, 0.0f, 1.0f)
                               : clamp(1.0f - ngl / geometry_offset, 0.0f, 1.0f);
}

// The origin for a shadow ray towards unit `wi` from the point with barycentrics (b1, b2):
// `p` lifted along the interpolated normal when the offset applies. ns, ng: the shading point's
// shading and geometric normals (facing the viewer). *lifted tells whether it moved.
Vec3 terminator_shadow_origin(const SmoothTriangle& tri, float b1, float b2, const Vec3& p,
                              const Vec3& ns, const Vec3& ng, const Vec3& wi,
                              float geometry_offset, bool* lifted);

// Cycles' factor on f·cos for a shading offset s in [0, 1): the frequency multiplier
// 1/(1 − s/2) stretches the angle; 1 when s is 0. cos_in is against the normal facing the
// viewer (Cycles flips it on back faces, transmissive or not); at or below that horizon the
// factor is 0, as Cycles' shift_cos_in gives there. Cycles applies it on the reflection side
// only: to a light direction with cos_in >= 0 (bsdf_eval) and to a sampled direction whose lobe
// is not a transmission (bsdf_sample, whatever side the direction falls on). Inline: most
// meshes have no shading offset, and the test runs twice at every path vertex.
inline float shading_offset_factor(float cos_in, float shading_offset) {
  if (!(shading_offset > 0.0f)) return 1.0f;
  if (!(cos_in > 0.0f)) return 0.0f;  // Cycles: max(cos(angle·m), 0) = 0 past the horizon
  const float frequency = 1.0f / (1.0f - 0.5f * shading_offset);
  const float angle = std::acos(std::min(cos_in, 1.0f));
  return std::max(std::cos(angle * frequency), 0.0f) / cos_in;
}

}  // namespace bxdf::render

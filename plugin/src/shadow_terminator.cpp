#include "bxdf/render/shadow_terminator.h"

#include <algorithm>
#include <cmath>

namespace bxdf::render {

namespace {

// Cycles' shadow_ray_smooth_surface_offset: the height of the parabola through the triangle's
// vertices with the vertex normals as slopes, bounded by the local linear envelope.
Vec3 smooth_surface_offset(const SmoothTriangle& t, float b1, float b2, const Vec3& ng) {
  const Vec3* V = t.v;
  const Vec3* N = t.n;
  const float u = 1.0f - b1 - b2, v = b1, w = b2;
  const Vec3 P = V[0] * u + V[1] * v + V[2] * w;
  const Vec3 n = N[0] * u + N[1] * v + N[2] * w;  // not normalised, as Cycles
  const float a = dot(N[2] - N[0], V[0] - V[2]);
  const float b = dot(N[2] - N[1], V[1] - V[2]);
  const float c = dot(N[1] - N[0], V[1] - V[0]);
  float h = a * u * (u - 1) + (a + b + c) * u * v + b * v * (v - 1);
  if (dot(n, ng) > 0.0f) {
    float h0 = std::max(std::max(dot(V[1] - V[0], N[0]), dot(V[2] - V[0], N[0])), 0.0f);
    float h1 = std::max(std::max(dot(V[0] - V[1], N[1]), dot(V[2] - V[1], N[1])), 0.0f);
    float h2 = std::max(std::max(dot(V[0] - V[2], N[2]), dot(V[1] - V[2], N[2])), 0.0f);
    h0 = std::max(dot(V[0] - P, N[0]) + h0, 0.0f);
    h1 = std::max(dot(V[1] - P, N[1]) + h1, 0.0f);
    h2 = std::max(dot(V[2] - P, N[2]) + h2, 0.0f);
    h = std::max(std::min(std::min(h0, h1), h2), h * 0.5f);
  } else {
    float h0 = std::max(std::max(dot(V[0] - V[1], N[0]), dot(V[0] - V[2], N[0])), 0.0f);
    float h1 = std::max(std::max(dot(V[1] - V[0], N[1]), dot(V[1] - V[2], N[1])), 0.0f);
    float h2 = std::max(std::max(dot(V[2] - V[0], N[2]), dot(V[2] - V[1], N[2])), 0.0f);
    h0 = std::max(dot(P - V[0], N[0]) + h0, 0.0f);
    h1 = std::max(dot(P - V[1], N[1]) + h1, 0.0f);
    h2 = std::max(dot(P - V[2], N[2]) + h2, 0.0f);
    h = std::min(-std::min(std::min(h0, h1), h2), h * 0.5f);
  }
  return n * h;
}

}  // namespace

Vec3 terminator_shadow_origin(const SmoothTriangle& tri, float b1, float b2, const Vec3& p,
                              const Vec3& ns, const Vec3& ng, const Vec3& wi,
                              float geometry_offset, bool* lifted) {
  *lifted = false;
  const float amount = terminator_offset_amount(ns, ng, wi, geometry_offset);
  if (!(amount > 0.0f)) return p;
  const Vec3 g = dot(ns, wi) < 0.0f ? -ng : ng;  // the side wi leaves from
  const Vec3 offset = smooth_surface_offset(tri, b1, b2, g) * amount;
  if (!is_finite(offset)) return p;
  *lifted = true;
  return p + offset;
}

}  // namespace bxdf::render

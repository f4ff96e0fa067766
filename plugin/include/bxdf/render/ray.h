// A ray with its valid parameter interval.
#pragma once

#include <limits>

#include "bxdf/math.h"

namespace bxdf::render {

// The largest coordinate (metres) a camera or a mesh vertex may have. Embree refuses (asserts on)
// rays whose origin has a component past 1.8e18; paths leave from hit points, so scene
// coordinates must stay well inside that. At 1e9 m float spacing is already 64 m, so no scene
// that renders meaningfully is refused.
constexpr float kMaxSceneCoordinate = 1e9f;

struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  Vec3 at(float t) const { return origin + dir * t; }
};

}  // namespace bxdf::render

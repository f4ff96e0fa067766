// A ray with its valid parameter interval.
#pragma once

#include <limits>

#include "bxdf/math.h"

namespace bxdf::render {

struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  Vec3 at(float t) const { return origin + dir * t; }
};

}  // namespace bxdf::render

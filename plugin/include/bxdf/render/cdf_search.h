// Finding the interval of a piecewise-constant distribution that a number falls in, and the
// number's place within it, for the light picker and a mesh light's triangles.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "bxdf/math.h"

namespace bxdf::render {

// The index of the first entry of the ascending `cdf` above x (std::upper_bound's). A few
// entries (a quad light's two triangles; a light and the world) are counted without branches:
// which interval a sample falls in is a coin toss, which a binary search's branches mispredict
// half the time.
inline size_t first_above(const std::vector<float>& cdf, float x) {
  constexpr size_t kCounted = 8;
  if (cdf.size() > kCounted)
    return static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin());
  size_t at_or_below = 0;
  for (float c : cdf) at_or_below += c <= x;
  return at_or_below;
}

// A number's place within the interval it fell in, (x − lo) / width, clamped back to [0, 1):
// the picked light, or triangle, samples with it.
inline float into_unit_interval(float v) { return clamp(v, 0.0f, 0x1.fffffep-1f); }

}  // namespace bxdf::render

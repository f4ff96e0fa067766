// Pixel filters by importance sampling (as Cycles does): each camera sample's offset from the
// pixel centre is drawn with density proportional to the filter, and every sample then counts
// with weight 1 for its own pixel, so tiles never write to each other's pixels.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "bxdf/math.h"

namespace bxdf::render {

enum class FilterType {
  Box,          // uniform over a square of side `width` pixels
  Gaussian,     // Cycles' Gaussian: σ = width/4 per axis, truncated at ±1.5·width
  BlackmanHarris,  // Cycles' default: the Blackman–Harris window over ±width per axis
  PixelCenter,  // every sample through the pixel centre
};

// The names parse_filter takes, for messages.
constexpr const char* kFilterNames = "'box', 'gaussian', 'blackman_harris' or 'pixel_center'";
// "box", "gaussian", "blackman_harris", "pixel_center" (also "pixel_centre", "center"); throws
// ParameterError otherwise.
FilterType parse_filter(const std::string& name);
const char* to_string(FilterType type);

class PixelFilter {
 public:
  // Throws ParameterError for a width outside (0, 16].
  PixelFilter(FilterType type = FilterType::Box, float width = 1.0f);

  // Offset from the pixel centre, in pixels, for a uniform point u in [0, 1)².
  Point2 sample(Point2 u) const {
    switch (type_) {
      case FilterType::PixelCenter:
        return {0.0f, 0.0f};
      case FilterType::Box:
        return {(u.x - 0.5f) * width_, (u.y - 0.5f) * width_};
      case FilterType::Gaussian:
      case FilterType::BlackmanHarris:
        return {sample_table(u.x), sample_table(u.y)};
    }
    return {0.0f, 0.0f};
  }
  FilterType type() const { return type_; }
  float width() const { return width_; }

 private:
  // Inverse CDF of the 1D filter over [-radius, radius], tabulated and linearly interpolated.
  // In int, not size_t: x86 converts between float and unsigned 64-bit numbers with branches and
  // shifts, which made this lookup the larger part of a camera sample's setup.
  float sample_table(float u) const {
    const int last = static_cast<int>(inverse_cdf_.size()) - 1;
    const float x = u * static_cast<float>(last);
    const int i = std::clamp(static_cast<int>(x), 0, last - 1);
    const float f = x - static_cast<float>(i);
    return inverse_cdf_[size_t(i)] * (1.0f - f) + inverse_cdf_[size_t(i) + 1] * f;
  }

  FilterType type_;
  float width_;
  std::vector<float> inverse_cdf_;
};

}  // namespace bxdf::render

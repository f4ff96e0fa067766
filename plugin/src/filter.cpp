#include "bxdf/render/filter.h"

#include <cmath>

#include "bxdf/params.h"

namespace bxdf::render {

FilterType parse_filter(const std::string& name) {
  if (name == "box") return FilterType::Box;
  if (name == "gaussian") return FilterType::Gaussian;
  if (name == "blackman_harris") return FilterType::BlackmanHarris;
  if (name == "pixel_center" || name == "pixel_centre" || name == "center")
    return FilterType::PixelCenter;
  throw ParameterError("filter '" + name + "' is not one of " + kFilterNames);
}

const char* to_string(FilterType type) {
  switch (type) {
    case FilterType::Box: return "box";
    case FilterType::Gaussian: return "gaussian";
    case FilterType::BlackmanHarris: return "blackman_harris";
    case FilterType::PixelCenter: return "pixel_center";
  }
  return "?";
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// Cycles' filter functions (scene/film.cpp) over their support [-radius, radius]: the Gaussian
// exp(-2 (6x / 3w)²) over ±1.5 w (σ = w/4), and the four-term Blackman–Harris window over ±w
// (Cycles doubles the width for it).
double filter_density(FilterType type, double x, double width) {
  if (type == FilterType::Gaussian) {
    const double sigma = 0.25 * width;
    return std::exp(-0.5 * x * x / (sigma * sigma));
  }
  const double v = 2.0 * kPi * (x / (2.0 * width) + 0.5);
  return 0.35875 - 0.48829 * std::cos(v) + 0.14128 * std::cos(2.0 * v) -
         0.01168 * std::cos(3.0 * v);
}

double filter_radius(FilterType type, double width) {
  return type == FilterType::Gaussian ? 1.5 * width : width;
}

}  // namespace

PixelFilter::PixelFilter(FilterType type, float width) : type_(type), width_(width) {
  if (!(width > 0.0f && width <= 16.0f))
    throw ParameterError("filter width " + std::to_string(width) + " must be in (0, 16] pixels");
  if (type != FilterType::Gaussian && type != FilterType::BlackmanHarris) return;
  // Cycles tabulates the inverse CDF of the filter (util_cdf_inverted) and samples x and y from
  // it independently; so do we, on a finer grid.
  constexpr int kGrid = 4096, kTable = 1024;
  const double radius = filter_radius(type, width);
  std::vector<double> cdf(kGrid + 1, 0.0);
  for (int i = 0; i < kGrid; ++i) {
    const double x = -radius + (i + 0.5) * (2.0 * radius / kGrid);
    cdf[i + 1] = cdf[i] + std::max(0.0, filter_density(type, x, width));
  }
  for (double& c : cdf) c /= cdf[kGrid];
  inverse_cdf_.resize(kTable);
  int j = 0;
  for (int k = 0; k < kTable; ++k) {
    const double u = static_cast<double>(k) / (kTable - 1);
    while (j < kGrid - 1 && cdf[j + 1] < u) ++j;
    const double span = cdf[j + 1] - cdf[j];
    const double f = span > 0.0 ? (u - cdf[j]) / span : 0.0;
    inverse_cdf_[k] = static_cast<float>(-radius + (j + std::min(1.0, std::max(0.0, f))) *
                                                       (2.0 * radius / kGrid));
  }
}

}  // namespace bxdf::render

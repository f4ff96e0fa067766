#include "bxdf/render/filter.h"

#include <cmath>

#include "bxdf/params.h"

namespace bxdf::render {

FilterType parse_filter(const std::string& name) {
  if (name == "box") return FilterType::Box;
  if (name == "gaussian") return FilterType::Gaussian;
  if (name == "pixel_center" || name == "center") return FilterType::PixelCenter;
  throw ParameterError("filter '" + name + "' is not one of {box, gaussian, pixel_center}");
}

const char* to_string(FilterType type) {
  switch (type) {
    case FilterType::Box: return "box";
    case FilterType::Gaussian: return "gaussian";
    case FilterType::PixelCenter: return "pixel_center";
  }
  return "?";
}

PixelFilter::PixelFilter(FilterType type, float width) : type_(type), width_(width) {
  if (!(width > 0.0f && width <= 16.0f))
    throw ParameterError("filter width " + std::to_string(width) + " must be in (0, 16] pixels");
  if (type != FilterType::Gaussian) return;
  // Cycles' Gaussian (film.cpp): exp(-2 (6x / (3w))²) over |x| <= 1.5 w, i.e. σ = w/4. Tabulate
  // the CDF of the truncated density on a fine grid and invert it.
  constexpr int kGrid = 4096, kTable = 1024;
  const double radius = 1.5 * width, sigma = 0.25 * width;
  std::vector<double> cdf(kGrid + 1, 0.0);
  for (int i = 0; i < kGrid; ++i) {
    const double x = -radius + (i + 0.5) * (2.0 * radius / kGrid);
    cdf[i + 1] = cdf[i] + std::exp(-0.5 * x * x / (sigma * sigma));
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

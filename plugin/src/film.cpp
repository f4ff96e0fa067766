#include "bxdf/render/film.h"

#include <string>

#include "bxdf/params.h"

namespace bxdf::render {

Film::Film(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1 || width > 65536 || height > 65536)
    throw ParameterError("film size " + std::to_string(width) + "x" + std::to_string(height) +
                         " must be within [1, 65536] per side");
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  sums_.assign(4 * n, 0.0);
  counts_.assign(n, 0u);
}

void Film::enable_adaptive() {
  const size_t n = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  half_sums_.assign(3 * n, 0.0);
  converged_.assign(n, 0u);
}

void Film::pixel(int x, int y, float rgba[4]) const {
  const size_t i = index(x, y);
  const double inv = counts_[i] ? 1.0 / counts_[i] : 0.0;
  for (int c = 0; c < 4; ++c) rgba[c] = static_cast<float>(sums_[4 * i + c] * inv);
}

std::vector<float> Film::rgba() const {
  std::vector<float> out(4 * static_cast<size_t>(width_) * static_cast<size_t>(height_));
  rgba(out.data());
  return out;
}

void Film::rgba(float* out) const {
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      pixel(x, y, out + 4 * (static_cast<size_t>(y) * width_ + x));
}

}  // namespace bxdf::render

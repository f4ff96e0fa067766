// The film: per-pixel sums of linear RGB radiance and alpha, and the sample count, in double
// precision. Tiles own disjoint pixels, so threads add without locks.
#pragma once

#include <cstdint>
#include <vector>

#include "bxdf/spectrum.h"

namespace bxdf::render {

class Film {
 public:
  Film() = default;
  // Throws ParameterError unless 1 <= width, height <= 65536.
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }

  void add_sample(int x, int y, const RGB& radiance, float alpha) {
    const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x);
    double* s = &sums_[4 * i];
    s[0] += radiance.r;
    s[1] += radiance.g;
    s[2] += radiance.b;
    s[3] += alpha;
    counts_[i] += 1;
  }

  // Mean RGBA of pixel (x, y); row 0 is the top of the image. 0 before any sample.
  void pixel(int x, int y, float rgba[4]) const;
  // The whole image as linear float RGBA, row-major, top row first: width·height·4 floats.
  std::vector<float> rgba() const;
  void rgba(float* out) const;  // same into a caller's buffer (e.g. a numpy array)
  uint32_t samples(int x, int y) const {
    return counts_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)];
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<double> sums_;
  std::vector<uint32_t> counts_;
};

}  // namespace bxdf::render

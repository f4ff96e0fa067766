// The film: per-pixel sums of linear RGB radiance and alpha, and the sample count, in double
// precision. Tiles own disjoint pixels, so threads add without locks. With adaptive sampling
// (enable_adaptive) also the sum of half of the samples, each counted twice (Cycles' adaptive
// aux buffer), and whether the pixel has stopped being sampled (adaptive_sampling.h).
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
    const size_t i = index(x, y);
    double* s = &sums_[4 * i];
    s[0] += radiance.r;
    s[1] += radiance.g;
    s[2] += radiance.b;
    s[3] += alpha;
    counts_[i] += 1;
  }

  // Allocates the half sums and the stopped flags (all pixels sampled).
  void enable_adaptive();
  // Adds a class-A sample's radiance, twice, to the half sum (after add_sample).
  void add_half_sample(int x, int y, const RGB& radiance) {
    double* a = &half_sums_[3 * index(x, y)];
    a[0] += 2.0 * radiance.r;
    a[1] += 2.0 * radiance.g;
    a[2] += 2.0 * radiance.b;
  }
  // The pixel's RGBA sum and (adaptive films) its half sum, RGB.
  const double* sum(int x, int y) const { return &sums_[4 * index(x, y)]; }
  const double* half_sum(int x, int y) const { return &half_sums_[3 * index(x, y)]; }
  // Whether adaptive sampling stopped sampling the pixel (false on a film without it).
  bool converged(int x, int y) const { return !converged_.empty() && converged_[index(x, y)] != 0; }
  void set_converged(int x, int y, bool c) { converged_[index(x, y)] = c; }

  // Mean RGBA of pixel (x, y); row 0 is the top of the image. 0 before any sample.
  void pixel(int x, int y, float rgba[4]) const;
  // The whole image as linear float RGBA, row-major, top row first: width·height·4 floats.
  std::vector<float> rgba() const;
  void rgba(float* out) const;  // same into a caller's buffer (e.g. a numpy array)
  uint32_t samples(int x, int y) const { return counts_[index(x, y)]; }

 private:
  size_t index(int x, int y) const {
    return static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x);
  }

  int width_ = 0, height_ = 0;
  std::vector<double> sums_;
  std::vector<uint32_t> counts_;
  std::vector<double> half_sums_;
  std::vector<uint8_t> converged_;
};

}  // namespace bxdf::render

// Adaptive sampling as Cycles does it (integrator/adaptive_sampling.cpp, scene/integrator.cpp's
// get_adaptive_sampling, kernel/film/adaptive_sampling.h): every 16 samples past a minimum, each
// pixel compares its mean with the mean of half its samples (those of class A, counted twice);
// where the difference, relative to the square root of the pixel's brightness, is below the
// noise threshold the pixel stops being sampled, unless a neighbour in its row or column is still
// sampled. The render ends when every pixel has stopped or the samples run out.
//
// It is unbiased per pixel only in the limit: a pixel stops once its estimate looks converged,
// which is what the threshold trades against time (Cycles' Noise Threshold).
#pragma once

#include <algorithm>
#include <cstdint>

#include "bxdf/render/film.h"
#include "bxdf/render/renderer.h"

namespace bxdf::render {

struct AdaptiveSampling {
  bool use = false;
  // Cycles' internal threshold: the setting (or its automatic value) times 5.
  float threshold = 0.0f;
  int min_samples = 0;
  // Samples between two convergence checks (a power of two).
  static constexpr int kStep = 16;

  // From the render settings, as Cycles' Integrator::get_adaptive_sampling: threshold 0 is
  // automatic, max(0.001, 1 / samples); min_samples 0 is automatic, max(4, ⌈16 / threshold^0.3⌉)
  // (threshold 0.1 → 32, 0.01 → 64, 0.001 → 128).
  static AdaptiveSampling of(const RenderSettings& settings);

  // Whether the convergence check runs once sample `sample` (0-based) of every pixel is done.
  bool need_filter(int sample) const {
    return use && sample > min_samples && (sample & (kStep - 1)) == kStep - 1;
  }
  // How many of `num_samples` from `start_sample` to render before the next check.
  int align_samples(int start_sample, int num_samples) const;
};

// Cycles' sample_is_class_A: half of the samples, spread evenly over the sequence's prefixes.
inline bool sample_is_class_a(uint32_t sample) {
  return (__builtin_popcount(sample & 0xaaaaaaaau) & 1) != 0;
}

// Runs the convergence check on every pixel of `film` (those already stopped only when `reset`),
// then lets each stopped pixel next to a sampled one (in its row, then its column) be sampled
// again, as Cycles' filter_x and filter_y. Returns how many pixels are still sampled.
uint64_t update_converged_pixels(Film& film, float threshold, bool reset);

// The checks of one render (Cycles' RenderScheduler around them): each runs
// update_converged_pixels at the current threshold. With the progressive noise floor (a render
// that shows partial images: the viewport) the threshold starts at 0.4 and, each time every
// pixel has met it, halves down to the setting's and every pixel is judged again; a final render
// checks against the setting's threshold from the start.
class ConvergenceChecks {
 public:
  ConvergenceChecks(const AdaptiveSampling& adaptive, bool progressive_noise_floor)
      : final_(adaptive.threshold),
        threshold_(progressive_noise_floor ? std::max(0.4f, adaptive.threshold) : adaptive.threshold) {}
  // Runs a check on `film`; true when every pixel has stopped at the setting's threshold (the
  // render is done).
  bool all_converged(Film& film);
  float threshold() const { return threshold_; }

 private:
  float final_, threshold_;
};

}  // namespace bxdf::render

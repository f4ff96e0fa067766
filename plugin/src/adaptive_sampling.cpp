#include "adaptive_sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

namespace bxdf::render {

AdaptiveSampling AdaptiveSampling::of(const RenderSettings& settings) {
  AdaptiveSampling a;
  a.use = settings.adaptive_sampling;
  if (!a.use) return a;
  const float threshold = settings.adaptive_threshold > 0.0f
                              ? settings.adaptive_threshold
                              : std::max(0.001f, 1.0f / float(settings.samples_per_pixel));
  a.min_samples = settings.adaptive_min_samples > 0
                      ? std::max(4, settings.adaptive_min_samples)
                      : std::max(4, int(std::ceil(16.0f / std::pow(threshold, 0.3f))));
  // Cycles' "arbitrary factor that makes the threshold more similar to what it was before".
  a.threshold = threshold * 5.0f;
  return a;
}

int AdaptiveSampling::align_samples(int start_sample, int num_samples) const {
  if (!use) return num_samples;
  // The first sample (0-based) after which the check runs, then every kStep.
  const int first_filter_sample = (min_samples + 1) | (kStep - 1);
  if (start_sample + num_samples <= first_filter_sample) return num_samples;
  const int next_filter_sample = std::max(first_filter_sample, start_sample | (kStep - 1));
  return std::min(next_filter_sample - start_sample + 1, num_samples);
}

namespace {

// Cycles' film_adaptive_sampling_convergence_check for one pixel.
bool pixel_converged(const Film& film, int x, int y, float threshold) {
  const uint32_t n = film.samples(x, y);
  if (n == 0) return false;
  const double* I = film.sum(x, y);
  const double* A = film.half_sum(x, y);
  const float inv_n = 1.0f / float(n);
  const float difference =
      float(std::fabs(I[0] - A[0]) + std::fabs(I[1] - A[1]) + std::fabs(I[2] - A[2])) * inv_n;
  const float normalize = std::sqrt(std::max(float(I[0] + I[1] + I[2]) * inv_n, 0.0f));
  return difference / (0.0001f + normalize) < threshold;
}

// Along the line of n pixels from (x, y) in steps of (dx, dy): a stopped pixel next to a
// sampled one is sampled again (one of Cycles' filter_x / filter_y passes).
void keep_neighbours_sampled(Film& film, int x, int y, int dx, int dy, int n) {
  bool prev = false;  // the previous pixel is sampled
  for (int i = 0; i < n; ++i, x += dx, y += dy) {
    if (!film.converged(x, y)) {
      if (i > 0 && !prev) film.set_converged(x - dx, y - dy, false);
      prev = true;
    } else {
      if (prev) film.set_converged(x, y, false);
      prev = false;
    }
  }
}

}  // namespace

uint64_t update_converged_pixels(Film& film, float threshold, bool reset) {
  const int w = film.width(), h = film.height();
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < w; ++x)
        if (reset || !film.converged(x, y)) film.set_converged(x, y, pixel_converged(film, x, y, threshold));
  });
  // A sampled pixel keeps its stopped neighbours sampled: along each row, then each column
  // (Cycles' filter_x, filter_y; the column pass sees the row pass's result).
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) keep_neighbours_sampled(film, 0, y, 1, 0, w);
  });
  tbb::parallel_for(tbb::blocked_range<int>(0, w), [&](const tbb::blocked_range<int>& columns) {
    for (int x = columns.begin(); x != columns.end(); ++x) keep_neighbours_sampled(film, x, 0, 0, 1, h);
  });
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, h), uint64_t(0),
      [&](const tbb::blocked_range<int>& rows, uint64_t active) {
        for (int y = rows.begin(); y != rows.end(); ++y)
          for (int x = 0; x < w; ++x) active += !film.converged(x, y);
        return active;
      },
      [](uint64_t a, uint64_t b) { return a + b; });
}

bool ConvergenceChecks::all_converged(Film& film) {
  bool reset = false;
  while (update_converged_pixels(film, threshold_, reset) == 0) {
    if (!(threshold_ > final_)) return true;
    threshold_ = std::max(threshold_ * 0.5f, final_);
    reset = true;  // every pixel judged again against the lower floor
  }
  return false;
}

}  // namespace bxdf::render

// Progressive passes (RenderSettings::progressive): each pass as many samples as fit the time
// until the display's next update, as Cycles' render scheduler sizes its viewport's work
// (RenderScheduler::calculate_num_samples_per_update). The interval grows with the time rendered,
// so that the first images come quickly and a long render is not cut into a pass, a barrier and
// a partial image per sample.
#pragma once

#include <algorithm>

namespace bxdf::render {

// Seconds between two display updates after `elapsed` seconds of rendering and `samples_done`
// samples per pixel (Cycles' guess_display_update_interval_in_seconds for an interactive render).
inline double display_update_interval(double elapsed, int samples_done) {
  if (elapsed < 1.0) return 0.1;
  if (elapsed < 2.0) return 0.25;
  if (elapsed < 4.0) return 0.5;
  if (elapsed < 8.0 || samples_done < 32) return 1.0;
  return 2.0;
}

// The next pass's samples per pixel: one before any has been timed, then as many as fit the
// interval at the average seconds per sample so far, at least one and at most `remaining`.
inline int progressive_pass_samples(double elapsed, int samples_done, int remaining) {
  if (samples_done <= 0 || !(elapsed > 0.0)) return std::min(1, remaining);
  const double seconds_per_sample = elapsed / samples_done;
  const double fit = display_update_interval(elapsed, samples_done) / seconds_per_sample;
  return fit < double(remaining) ? std::max(int(fit), 1) : remaining;
}

}  // namespace bxdf::render

// Rendering a scene to a film: progressive passes over tiles on all cores (TBB), a progress
// callback and a cancel flag checked between tiles. This is the entry point a binding calls
// (with the GIL released: nothing here touches Python unless a callback does).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "bxdf/render/camera.h"
#include "bxdf/render/film.h"
#include "bxdf/render/filter.h"
#include "bxdf/render/integrator.h"
#include "bxdf/render/scene.h"

namespace bxdf::render {

// A rectangle of pixels: columns [x0, x1), rows [y0, y1) counted from the top of the image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool is_set() const { return x0 != 0 || y0 != 0 || x1 != 0 || y1 != 0; }  // not all zero
};

struct RenderSettings {
  int width = 64, height = 64;
  // Blender's Render Region: only these pixels are rendered, into a film (and an image) of the
  // region's size, each pixel as the whole image's render has it. All zero (the default): the
  // whole image.
  PixelRect region;
  int samples_per_pixel = 16;
  int max_bounces = 8;
  int russian_roulette_depth = 1;   // Cycles' Min Light Bounces + 1 (integrator.h)
  int transparent_max_bounces = 8;  // Cycles' transparent_max_bounces (integrator.h)
  FilterType filter = FilterType::Box;
  float filter_width = 1.0f;  // pixels (Blender's filter_width for Gaussian)
  uint64_t seed = 0;
  int threads = 0;            // 0 = all cores
  int tile_size = 16;
  // 0 = about spp/8, at most 16, when RenderCallbacks::on_pass is set (its partial images),
  // else all samples in one pass.
  int samples_per_pass = 0;
  // Passes sized by time instead (samples_per_pass 0), when RenderCallbacks::on_pass is set, as
  // Cycles sizes its viewport's updates (progressive_pass.h): one sample first, then as many as
  // fit the display interval for the time rendered so far. A viewport's first image comes at once
  // and the later ones do not cost a pass (and a partial image) per sample.
  bool progressive = false;
  bool transparent_background = false;  // alpha = coverage instead of 1
  // Cycles' adaptive sampling (adaptive_sampling.h): pixels whose noise is below the threshold
  // stop being sampled. Threshold 0 = automatic (max(0.001, 1/samples)); min samples 0 =
  // automatic (from the threshold), as Cycles' Noise Threshold and Min Samples.
  bool adaptive_sampling = false;
  float adaptive_threshold = 0.01f;  // [0, 1]
  int adaptive_min_samples = 0;      // [0, 4096]
};

struct RenderProgress {
  int pass = 0, passes = 0;      // passes finished / total (0: not known ahead, progressive
                                 // passes or adaptive sampling)
  int samples_done = 0;          // per pixel, in finished passes
  bool last = false;             // on_pass: the render's last pass (its film is the result)
  // Over the whole render; 64-bit, as passes x tiles passes 2^31 at the largest spp and size.
  // With progressive passes or adaptive sampling, tile-samples (a tile of a pass of k samples
  // counts k).
  uint64_t tiles_done = 0, tiles_total = 0;
  double fraction() const { return tiles_total ? double(tiles_done) / tiles_total : 0.0; }
};

struct RenderCallbacks {
  // After every tile, serialised (never two at once) but possibly from a worker thread.
  // Return false to cancel.
  std::function<bool(const RenderProgress&)> on_tile;
  // After every pass, on the calling thread; the film then holds a consistent image.
  std::function<void(const Film&, const RenderProgress&)> on_pass;
  // Checked before every tile and between a tile's batches; set it from anywhere to stop.
  const std::atomic<bool>* cancel = nullptr;
};

struct RenderStats {
  double seconds = 0.0;
  uint64_t camera_samples = 0;
  uint64_t rays = 0, shadow_rays = 0;
  uint64_t rejected_samples = 0;  // NaN/Inf/negative radiance dropped
  int samples_per_pixel = 0;      // completed (less than asked when cancelled or converged)
  bool cancelled = false;
  // Adaptive sampling stopped every pixel before the samples ran out.
  bool converged = false;
  int threads = 0;                // the threads rendered on
  // Time the threads spent rendering tiles, summed: tile_seconds / (threads · seconds) is how
  // busy they were (the rest: waiting at the ends of passes, the set-up, other processes).
  double tile_seconds = 0.0;
  // The same threads' CPU time in tiles, summed: per camera sample, the renderer's cost without
  // the time other processes took the cores away (steadier than wall time on a shared machine).
  double tile_cpu_seconds = 0.0;
};

// The pixels a render with these settings covers: the region, or the whole image when it is
// not set. Throws ParameterError for a region that is not inside the image.
PixelRect rendered_rect(const RenderSettings& settings);

// Renders `scene` (committed) through `camera`. Throws ParameterError for bad settings.
// On cancel, returns the film with the passes finished so far and stats.cancelled = true.
Film render_scene(const Scene& scene, const CameraSettings& camera, const RenderSettings& settings,
            const RenderCallbacks& callbacks = {}, RenderStats* stats = nullptr);

}  // namespace bxdf::render

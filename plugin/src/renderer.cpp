#include "bxdf/render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <memory>
#include <mutex>
#include <string>

#include "bxdf/params.h"
#include "adaptive_sampling.h"
#include "path_batch.h"
#include "progressive_pass.h"
#include "sampler/path_sampler.h"

namespace bxdf::render {

namespace {

void check_settings(const RenderSettings& s) {
  const auto bad = [](const std::string& name, auto v, const std::string& range) {
    throw ParameterError("render setting '" + name + "' is " + std::to_string(v) +
                         "; valid range " + range);
  };
  if (s.width < 1 || s.width > 65536) bad("width", s.width, "[1, 65536]");
  if (s.height < 1 || s.height > 65536) bad("height", s.height, "[1, 65536]");
  if (s.samples_per_pixel < 1) bad("samples_per_pixel", s.samples_per_pixel, "[1, inf)");
  if (s.max_bounces < 0) bad("max_bounces", s.max_bounces, "[0, inf)");
  if (s.russian_roulette_depth < 0)
    bad("russian_roulette_depth", s.russian_roulette_depth, "[0, inf)");
  if (s.transparent_max_bounces < 0)
    bad("transparent_max_bounces", s.transparent_max_bounces, "[0, inf)");
  if (s.threads < 0) bad("threads", s.threads, "[0, inf) (0 = all cores)");
  if (s.tile_size < 1 || s.tile_size > 4096) bad("tile_size", s.tile_size, "[1, 4096]");
  if (s.samples_per_pass < 0) bad("samples_per_pass", s.samples_per_pass, "[0, inf)");
  if (s.progressive && s.samples_per_pass > 0)
    bad("samples_per_pass", s.samples_per_pass, "0 with progressive passes (they size themselves)");
  if (!(s.adaptive_threshold >= 0.0f && s.adaptive_threshold <= 1.0f))
    bad("adaptive_threshold", s.adaptive_threshold, "[0, 1] (0 = automatic)");
  if (s.adaptive_min_samples < 0 || s.adaptive_min_samples > 4096)
    bad("adaptive_min_samples", s.adaptive_min_samples, "[0, 4096] (0 = automatic)");
}

// Automatic passes take about an eighth of the samples, but no more than this many, so that a
// tile (between two checks of the cancel flag) stays short.
constexpr int kMaxAutoSamplesPerPass = 16;

struct Tile {
  int x0, y0, x1, y1;
};

// CPU time of the calling thread (Linux: CLOCK_THREAD_CPUTIME_ID), 0 if the clock is missing.
double thread_cpu_seconds() {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0.0;
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

PixelRect rendered_rect(const RenderSettings& s) {
  const PixelRect& r = s.region;
  if (!r.is_set()) return {0, 0, s.width, s.height};
  if (!(0 <= r.x0 && r.x0 < r.x1 && r.x1 <= s.width && 0 <= r.y0 && r.y0 < r.y1 &&
        r.y1 <= s.height))
    throw ParameterError("render setting 'region' is (" + std::to_string(r.x0) + ", " +
                         std::to_string(r.y0) + ", " + std::to_string(r.x1) + ", " +
                         std::to_string(r.y1) + "); valid: (x_min, y_min, x_max, y_max) with 0 <= "
                         "x_min < x_max <= width " + std::to_string(s.width) +
                         " and 0 <= y_min < y_max <= height " + std::to_string(s.height) +
                         " (rows from the top)");
  return r;
}

Film render_scene(const Scene& scene, const CameraSettings& camera_settings,
            const RenderSettings& settings, const RenderCallbacks& callbacks,
            RenderStats* stats_out) {
  check_settings(settings);
  // The film covers the rendered rectangle (a region outside the image is refused here); the
  // camera, the pixel seeds and the tiles' pixels keep the whole image's coordinates, so a
  // region's pixels are the whole render's.
  const PixelRect rect = rendered_rect(settings);
  if (!scene.committed()) throw ParameterError("render: the scene is not committed");
  const auto start = std::chrono::steady_clock::now();
  const Camera camera(camera_settings, settings.width, settings.height);
  const PixelFilter filter(settings.filter, settings.filter_width);
  IntegratorSettings integrator_settings;
  integrator_settings.max_bounces = settings.max_bounces;
  integrator_settings.russian_roulette_depth = settings.russian_roulette_depth;
  integrator_settings.transparent_max_bounces = settings.transparent_max_bounces;
  integrator_settings.transparent_background = settings.transparent_background;
  const PathTracer tracer(scene, integrator_settings);
  Film film(rect.width(), rect.height());
  const AdaptiveSampling adaptive = AdaptiveSampling::of(settings);
  if (adaptive.use) film.enable_adaptive();

  std::vector<Tile> tiles;
  for (int y = rect.y0; y < rect.y1; y += settings.tile_size)
    for (int x = rect.x0; x < rect.x1; x += settings.tile_size)
      tiles.push_back({x, y, std::min(x + settings.tile_size, rect.x1),
                       std::min(y + settings.tile_size, rect.y1)});
  const int spp = settings.samples_per_pixel;
  // Passes exist for the partial images on_pass shows; without it the render is one pass, as
  // each pass ends in a wait for the slowest tile (8 passes cost 5-7% of a 64-spp harness
  // render at 2 threads). Tiles check for cancelling between batches either way.
  const int per_pass =
      settings.samples_per_pass > 0 ? std::min(settings.samples_per_pass, spp)
      : callbacks.on_pass           ? std::clamp((spp + 7) / 8, 1, kMaxAutoSamplesPerPass)
                                    : spp;
  // Progressive passes, like the others, only where partial images are shown.
  const bool progressive = settings.progressive && callbacks.on_pass;
  // Progressive passes and adaptive sampling's (cut at its checks, and maybe ended early) are
  // not known ahead: progress counts tile-samples instead of tiles.
  const bool counts_samples = progressive || adaptive.use;
  const int passes = counts_samples ? 0 : (spp + per_pass - 1) / per_pass;

  RenderProgress progress;
  progress.passes = passes;
  progress.tiles_total = static_cast<uint64_t>(counts_samples ? spp : passes) * tiles.size();
  std::mutex progress_mutex;
  std::atomic<bool> stop{false};
  std::atomic<uint64_t> rays{0}, shadow_rays{0}, rejected{0}, camera_samples{0};
  const float background_alpha = settings.transparent_background ? 0.0f : 1.0f;

  const auto cancelled = [&]() {
    return stop.load(std::memory_order_relaxed) ||
           (callbacks.cancel && callbacks.cancel->load(std::memory_order_relaxed));
  };

  // One batch of paths per render thread, made when the thread first needs it.
  tbb::enumerable_thread_specific<std::unique_ptr<PathBatch>> batches(
      [&] { return std::make_unique<PathBatch>(scene, tracer); });
  const auto render_tile = [&](const Tile& tile, int first_sample, int count) {
    PathStats local;
    uint64_t samples = 0;
    // Traced in batches of consecutive samples (a pixel's, then the next pixel's; PathBatch);
    // the film takes the results in sample order.
    PathBatch& batch = *batches.local();
    // A batch's camera samples are gathered first and their rays made together
    // (Camera::generate_rays), then traced.
    std::array<PathBatch::Sample, PathBatch::kSize> pending;
    std::array<uint32_t, PathBatch::kSize> pixel_seeds, sample_indices;
    std::array<Point2, PathBatch::kSize> filter_numbers;
    std::array<float, PathBatch::kSize> film_x, film_y;
    std::array<Ray, PathBatch::kSize> camera_rays;
    int n_pending = 0;
    const auto trace_batch = [&] {
      // The pixel filter's numbers of every sample at once, then each sample's film point.
      PathSampler::draw_filters(pixel_seeds.data(), sample_indices.data(), n_pending,
                                filter_numbers.data());
      for (int k = 0; k < n_pending; ++k) {
        const Point2 offset = filter.sample(filter_numbers[size_t(k)]);
        film_x[size_t(k)] = static_cast<float>(pending[size_t(k)].x) + 0.5f + offset.x;
        film_y[size_t(k)] = static_cast<float>(pending[size_t(k)].y) + 0.5f + offset.y;
      }
      camera.generate_rays(film_x.data(), film_y.data(), n_pending, camera_rays.data());
      for (int k = 0; k < n_pending; ++k) batch.add(pending[size_t(k)], camera_rays[size_t(k)]);
      n_pending = 0;
      batch.trace(local);
      for (int k = 0; k < batch.size(); ++k) {
        const PathBatch::Sample& c = batch.sample(k);
        const PathResult& r = batch.result(k);
        film.add_sample(c.x - rect.x0, c.y - rect.y0, r.radiance, std::max(r.alpha, background_alpha));
        if (adaptive.use && sample_is_class_a(c.index))
          film.add_half_sample(c.x - rect.x0, c.y - rect.y0, r.radiance);
      }
      samples += uint64_t(batch.size());
      batch.clear();
    };
    for (int y = tile.y0; y < tile.y1; ++y) {
      for (int x = tile.x0; x < tile.x1; ++x) {
        if (film.converged(x - rect.x0, y - rect.y0)) continue;  // adaptive sampling stopped it
        // The pixel's samples are points first_sample.. of its own Sobol-Burley sequence: the
        // image depends on neither the thread count, the order of tiles nor the passes.
        const uint32_t pixel_seed =
            PathSampler::pixel_seed(static_cast<uint32_t>(x), static_cast<uint32_t>(y), settings.seed);
        for (int s = first_sample; s < first_sample + count; ++s) {
          const size_t k = size_t(n_pending++);
          pending[k] = {x, y, pixel_seed, static_cast<uint32_t>(s)};
          pixel_seeds[k] = pixel_seed;
          sample_indices[k] = static_cast<uint32_t>(s);
          if (n_pending == PathBatch::kSize) {
            trace_batch();
            if (cancelled()) break;
          }
        }
        if (cancelled()) break;
      }
      if (cancelled()) break;
    }
    if (n_pending > 0 && !cancelled()) trace_batch();
    rays += local.rays;
    shadow_rays += local.shadow_rays;
    rejected += local.rejected;
    camera_samples += samples;
  };

  const int threads = settings.threads > 0 ? settings.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  int completed_spp = 0;
  // The tiles' render times and their threads' CPU times, summed under the progress lock each
  // tile already takes.
  double busy_seconds = 0.0, busy_cpu_seconds = 0.0;
  // Where partial images are shown (the viewport), with Cycles' progressive noise floor.
  ConvergenceChecks checks(adaptive, progressive);
  bool converged = false;
  arena.execute([&] {
    // Each pass renders samples completed_spp.. of every pixel still sampled.
    for (int pass = 0; completed_spp < spp && !converged && !cancelled(); ++pass) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const int remaining = spp - completed_spp;
      const int count = adaptive.align_samples(
          completed_spp, progressive ? progressive_pass_samples(elapsed, completed_spp, remaining)
                                     : std::min(per_pass, remaining));
      tbb::parallel_for(
          tbb::blocked_range<size_t>(0, tiles.size(), 1),
          [&](const tbb::blocked_range<size_t>& range) {
            for (size_t t = range.begin(); t != range.end(); ++t) {
              if (cancelled()) return;
              const auto tile_start = std::chrono::steady_clock::now();
              const double cpu_start = thread_cpu_seconds();
              render_tile(tiles[t], completed_spp, count);
              const double cpu = thread_cpu_seconds() - cpu_start;
              const double wall =
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - tile_start).count();
              std::lock_guard<std::mutex> lock(progress_mutex);  // one callback at a time
              busy_seconds += wall;
              busy_cpu_seconds += cpu;
              progress.tiles_done += counts_samples ? uint64_t(count) : 1u;
              if (callbacks.on_tile && !callbacks.on_tile(progress)) stop = true;
            }
          },
          tbb::simple_partitioner());
      if (cancelled()) break;
      completed_spp += count;
      converged = adaptive.need_filter(completed_spp - 1) && checks.all_converged(film);
      progress.pass = pass + 1;
      progress.samples_done = completed_spp;
      progress.last = completed_spp >= spp || converged;
      if (converged) {
        // The samples no pixel needs count as done: the render is complete.
        progress.tiles_done = progress.tiles_total;
        std::lock_guard<std::mutex> lock(progress_mutex);
        if (callbacks.on_tile) callbacks.on_tile(progress);
      }
      if (callbacks.on_pass) callbacks.on_pass(film, progress);
    }
  });

  if (stats_out) {
    stats_out->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats_out->camera_samples = camera_samples;
    stats_out->rays = rays;
    stats_out->shadow_rays = shadow_rays;
    stats_out->rejected_samples = rejected;
    stats_out->samples_per_pixel = completed_spp;
    stats_out->tile_seconds = busy_seconds;
    stats_out->tile_cpu_seconds = busy_cpu_seconds;
    stats_out->threads = threads;
    stats_out->cancelled = completed_spp < spp && !converged;
    stats_out->converged = converged;
  }
  return film;
}

}  // namespace bxdf::render

// Renders the Cornell-box-like scene (diffuse walls, a glossy and a glass sphere, an area light;
// 256x256, 64 spp, 8 bounces unless the file or options say otherwise) and reports wall time,
// camera samples/s and rays/s; then measures Embree's own closest-hit rate on random rays inside
// the same box, one ray at a time (rtcIntersect1) and in packets of 8 (rtcIntersect8), on the
// same number of threads: the ceiling for the renderer's ray throughput.
//
//   bxdf_bench_render [scene.json] [--threads T] [--spp N] [--rays R] [-o image.exr]
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bxdf/render/image_io.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene_json.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Random rays from points inside the box [-0.99, 0.99]³ in uniform directions.
void random_ray(PCG32& rng, float o[3], float d[3]) {
  for (int c = 0; c < 3; ++c) o[c] = (rng.uniform() * 2.0f - 1.0f) * 0.99f;
  const Vec3 v = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
  d[0] = v.x;
  d[1] = v.y;
  d[2] = v.z;
}

struct Rate {
  double rays_per_second = 0;
  uint64_t hits = 0;
};

// Traces n random rays (rounded up to whole chunks) on `threads` threads and times it.
// trace_chunk(rng, ctx, count) traces `count` rays drawn from rng and returns how many hit;
// the two measurements below differ only in that function.
template <class TraceChunk>
Rate time_random_rays(uint64_t n, int threads, TraceChunk trace_chunk) {
  std::atomic<uint64_t> hits{0};
  tbb::task_arena arena(threads);
  const auto t0 = std::chrono::steady_clock::now();
  const uint64_t chunk = 1 << 14;
  const uint64_t chunks = (n + chunk - 1) / chunk;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1),
                      [&](const tbb::blocked_range<uint64_t>& r) {
      for (uint64_t c = r.begin(); c != r.end(); ++c) {
        PCG32 rng(c, 12345);
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        hits += trace_chunk(rng, ctx, chunk);
      }
    }, tbb::simple_partitioner());
  });
  const double s = seconds_since(t0);
  return {static_cast<double>(chunks * chunk) / s, hits.load()};
}

Rate embree_single(RTCScene scene, uint64_t n, int threads) {
  return time_random_rays(n, threads, [scene](PCG32& rng, RTCIntersectContext& ctx, uint64_t count) {
    uint64_t local = 0;
    for (uint64_t i = 0; i < count; ++i) {
      RTCRayHit rh;
      float o[3], d[3];
      random_ray(rng, o, d);
      rh.ray.org_x = o[0]; rh.ray.org_y = o[1]; rh.ray.org_z = o[2];
      rh.ray.dir_x = d[0]; rh.ray.dir_y = d[1]; rh.ray.dir_z = d[2];
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = 1e30f;
      rh.ray.time = 0.0f;
      rh.ray.mask = 0xffffffffu;
      rh.ray.id = 0;
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return local;
  });
}

Rate embree_packet8(RTCScene scene, uint64_t n, int threads) {
  return time_random_rays(n, threads, [scene](PCG32& rng, RTCIntersectContext& ctx, uint64_t count) {
    alignas(32) int valid[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
    uint64_t local = 0;
    for (uint64_t i = 0; i < count; i += 8) {
      alignas(32) RTCRayHit8 rh;
      for (int k = 0; k < 8; ++k) {
        float o[3], d[3];
        random_ray(rng, o, d);
        rh.ray.org_x[k] = o[0]; rh.ray.org_y[k] = o[1]; rh.ray.org_z[k] = o[2];
        rh.ray.dir_x[k] = d[0]; rh.ray.dir_y[k] = d[1]; rh.ray.dir_z[k] = d[2];
        rh.ray.tnear[k] = 0.0f;
        rh.ray.tfar[k] = 1e30f;
        rh.ray.time[k] = 0.0f;
        rh.ray.mask[k] = 0xffffffffu;
        rh.ray.id[k] = 0;
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect8(valid, scene, &ctx, &rh);
      for (int k = 0; k < 8; ++k) local += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    }
    return local;
  });
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = BXDF_CORNELL_SCENE, output;
  int threads = 0, spp = 0;
  uint64_t rays = 4'000'000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--spp" && i + 1 < argc) spp = std::atoi(argv[++i]);
    else if (a == "--rays" && i + 1 < argc) rays = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "-o" && i + 1 < argc) output = argv[++i];
    else if (!a.empty() && a[0] != '-') scene_path = a;
    else {
      std::fprintf(stderr, "usage: %s [scene.json] [--threads T] [--spp N] [--rays R] [-o out.exr]\n",
                   argv[0]);
      return 1;
    }
  }
  try {
    const auto t_load = std::chrono::steady_clock::now();
    LoadedScene loaded = load_scene_json(scene_path);
    const double load_s = seconds_since(t_load);
    RenderSettings settings = loaded.settings;
    settings.threads = threads;
    if (spp > 0) settings.samples_per_pixel = spp;
    const int used_threads = threads > 0 ? threads : tbb::this_task_arena::max_concurrency();

    RenderStats stats;
    const Film film = render_scene(*loaded.scene, loaded.camera, settings, {}, &stats);
    const double all_rays = static_cast<double>(stats.rays + stats.shadow_rays);
    std::printf("scene            %s (%zu triangles, %zu lights; load + BVH %.3f s)\n",
                scene_path.c_str(), loaded.scene->num_triangles(), loaded.scene->lights().size(),
                load_s);
    std::printf("render           %dx%d, %d spp, max %d bounces, %d threads\n", settings.width,
                settings.height, stats.samples_per_pixel, settings.max_bounces, used_threads);
    std::printf("wall time        %.3f s\n", stats.seconds);
    std::printf("threads busy     %.1f%% (time in tiles / (threads x wall time))\n",
                100.0 * stats.tile_seconds / (stats.threads * stats.seconds));
    std::printf("CPU per sample   %.3f us (the threads' CPU time in tiles per camera sample)\n",
                1e6 * stats.tile_cpu_seconds / double(stats.camera_samples));
    std::printf("camera samples/s %.4g\n", double(stats.camera_samples) / stats.seconds);
    std::printf("rays/s           %.4g (%.4g closest-hit + %.4g shadow; %.2f rays per sample)\n",
                all_rays / stats.seconds, double(stats.rays) / stats.seconds,
                double(stats.shadow_rays) / stats.seconds, all_rays / double(stats.camera_samples));
    std::printf("rejected samples %llu\n", static_cast<unsigned long long>(stats.rejected_samples));

    const auto scene = static_cast<RTCScene>(loaded.scene->embree_scene());
    const Rate single = embree_single(scene, rays, used_threads);
    const Rate packet = embree_packet8(scene, rays, used_threads);
    std::printf("embree ceiling   rtcIntersect1 %.4g rays/s, rtcIntersect8 %.4g rays/s "
                "(%llu random rays inside the box, %.1f%% hit)\n",
                single.rays_per_second, packet.rays_per_second,
                static_cast<unsigned long long>(rays),
                100.0 * double(single.hits) / double(rays));
    std::printf("renderer / ceiling  %.1f%% of rtcIntersect1\n",
                100.0 * all_rays / stats.seconds / single.rays_per_second);

    if (!output.empty()) {
      Image img;
      img.width = film.width();
      img.height = film.height();
      img.rgba = film.rgba();
      write_image(output, img);
      std::printf("image            %s\n", output.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bxdf_bench_render: %s\n", e.what());
    return 1;
  }
  return 0;
}

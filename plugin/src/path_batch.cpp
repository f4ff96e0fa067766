#include "path_batch.h"

#include <algorithm>

namespace bxdf::render {

void PathBatch::add(const Sample& sample, const Ray& camera_ray) {
  samples_[size_t(count_)] = sample;
  camera_rays_[size_t(count_)] = camera_ray;
  ++count_;
}

void PathBatch::prefetch_shading(int live) const {
  // Three passes, each over the whole batch, so that one path's loads are under way while the
  // others' are issued: the indices first, then (they have arrived) the vertices they name.
  for (int a = 0; a < live; ++a)
    if (found_[size_t(a)]) scene_.prefetch_triangle(hits_[size_t(a)]);
  for (int a = 0; a < live; ++a)
    if (found_[size_t(a)]) scene_.prefetch_vertices(hits_[size_t(a)]);
  for (int a = 0; a < live; ++a) {
    if (!found_[size_t(a)]) continue;
    const Hit& hit = hits_[size_t(a)];
    const MaterialGraph* graph = scene_.materials()[scene_.material_of(hit)].graph.get();
    if (graph && !graph->uv_lookups.empty()) graph->prefetch_texels(scene_, hit);
  }
}

void PathBatch::trace(PathStats& stats) {
  for (int k = 0; k < count_; k += Scene::kCameraPacket)
    scene_.intersect_camera_rays(&camera_rays_[size_t(k)], std::min(Scene::kCameraPacket, count_ - k),
                                 &camera_hits_[size_t(k)]);
  int live = 0;
  for (int k = 0; k < count_; ++k) {
    PathState& path = paths_[size_t(k)];
    tracer_.begin(camera_rays_[size_t(k)], &path);
    ++stats.rays;
    const CameraHit& h = camera_hits_[size_t(k)];
    tracer_.advance(path, sampler(k), stats, h.found ? &h.hit : nullptr);
    if (!path.done) live_[size_t(live++)] = k;
  }
  while (live > 0) {
    for (int a = 0; a < live; ++a) {
      const PathState& path = paths_[size_t(live_[size_t(a)])];
      rays_[size_t(a)] = &path.ray;
      camera_[size_t(a)] = path.bounce == 0;  // a camera ray past transparent surfaces
    }
    stats.rays += uint64_t(live);
    scene_.intersect_stream(rays_.data(), camera_.data(), live, hits_.data(), found_.data());
    prefetch_shading(live);
    int still = 0;
    for (int a = 0; a < live; ++a) {
      const int k = live_[size_t(a)];
      PathState& path = paths_[size_t(k)];
      tracer_.advance(path, sampler(k), stats, found_[size_t(a)] ? &hits_[size_t(a)] : nullptr);
      if (!path.done) live_[size_t(still++)] = k;
    }
    live = still;
  }
  for (int k = 0; k < count_; ++k) results_[size_t(k)] = tracer_.finish(paths_[size_t(k)], stats);
}

}  // namespace bxdf::render

#include "path_batch.h"

#include <algorithm>

namespace bxdf::render {

PathBatch::PathBatch(const Scene& scene, const PathTracer& tracer) : scene_(scene), tracer_(tracer) {
  for (const Material& m : scene.materials())
    if (m.graph) {
      registers_per_path_ = std::max(registers_per_path_, size_t(m.graph->num_registers));
      looks_up_texels_ = looks_up_texels_ || !m.graph->uv_lookups.empty();
    }
  register_block_.resize(registers_per_path_ * size_t(kSize));
}

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
  if (!looks_up_texels_) return;
  for (int a = 0; a < live; ++a) {
    if (!found_[size_t(a)]) continue;
    const Hit& hit = hits_[size_t(a)];
    const MaterialGraph* graph = scene_.materials()[scene_.material_of(hit)].graph.get();
    if (graph && !graph->uv_lookups.empty()) graph->prefetch_texels(scene_, hit);
  }
}

void PathBatch::draw_numbers(int live) {
  // An escaped path draws nothing more; a path draws its light point only where the scene has
  // a light to pick, and its roulette number only where it may be ended.
  int n = 0;
  for (int a = 0; a < live; ++a) {
    if (!found_[size_t(a)]) {
      number_slots_[size_t(a)] = -1;
      continue;
    }
    const int k = live_[size_t(a)];
    number_seeds_[size_t(n)] = samples_[size_t(k)].pixel_seed;
    number_indices_[size_t(n)] = samples_[size_t(k)].index;
    number_vertices_[size_t(n)] = paths_[size_t(k)].vertex;
    number_slots_[size_t(a)] = n++;
  }
  PathSampler::draw_vertices(number_seeds_.data(), number_indices_.data(), number_vertices_.data(),
                             n, !scene_.light_sampler().empty(), numbers_.data());
  // The roulette's subset, gathered in place (entry m <= j is read before it is overwritten).
  int m = 0;
  for (int a = 0; a < live; ++a) {
    const int j = number_slots_[size_t(a)];
    if (j < 0 || !(paths_[size_t(live_[size_t(a)])].continuation < 1.0f)) continue;
    number_seeds_[size_t(m)] = number_seeds_[size_t(j)];
    number_indices_[size_t(m)] = number_indices_[size_t(j)];
    number_vertices_[size_t(m)] = number_vertices_[size_t(j)];
    roulette_entries_[size_t(m++)] = j;
  }
  PathSampler::draw_roulette(number_seeds_.data(), number_indices_.data(), number_vertices_.data(),
                             m, roulette_numbers_.data());
  for (int i = 0; i < m; ++i) {
    VertexNumbers& v = numbers_[size_t(roulette_entries_[size_t(i)])];
    v.russian_roulette = roulette_numbers_[size_t(i)];
    v.has_roulette = true;
  }
}

int PathBatch::advance_live(int live, PathStats& stats) {
  draw_numbers(live);
  for (int a = 0; a < live; ++a) {
    programs_[size_t(a)] = nullptr;
    registers_[size_t(a)] = nullptr;
    if (!found_[size_t(a)]) continue;
    PreparedHit& p = prepared_[size_t(a)];
    const int k = live_[size_t(a)];
    tracer_.prepare(paths_[size_t(k)], sampler(k, a), hits_[size_t(a)], &p);
    if (p.runs_program) programs_[size_t(a)] = scene_.materials()[p.sp.material].graph.get();
  }
  // Each program over its hits (few materials per batch: one scan per program).
  for (int a = 0; a < live; ++a) {
    const MaterialGraph* graph = programs_[size_t(a)];
    if (!graph) continue;
    int n = 0;
    for (int b = a; b < live; ++b) {
      if (programs_[size_t(b)] != graph) continue;
      programs_[size_t(b)] = nullptr;
      Vec3* r = register_block_.data() + size_t(b) * registers_per_path_;
      registers_[size_t(b)] = r;
      program_ctxs_[size_t(n)] = prepared_[size_t(b)].ctx;
      program_registers_[size_t(n)] = r;
      ++n;
    }
    graph->evaluate_batch(program_ctxs_.data(), program_registers_.data(), n);
  }
  int still = 0, shadowed = 0;
  for (int a = 0; a < live; ++a) {
    const int k = live_[size_t(a)];
    PathState& path = paths_[size_t(k)];
    const bool found = found_[size_t(a)] != 0;
    tracer_.advance_deferring_shadow(path, sampler(k, a), stats, found ? &hits_[size_t(a)] : nullptr,
                                     found ? &prepared_[size_t(a)] : nullptr, registers_[size_t(a)],
                                     walk_slots_);
    if (path.shadow.active) {
      shadow_origins_[size_t(shadowed)] = path.shadow.origin;
      shadow_dirs_[size_t(shadowed)] = path.shadow.dir;
      shadow_tmax_[size_t(shadowed)] = path.shadow.tmax;
      shadowed_[size_t(shadowed++)] = k;
    }
    if (!path.done) live_[size_t(still++)] = k;
  }
  // The vertex's shadow rays together, before any path's next vertex adds to its L.
  scene_.occluded_stream(shadow_origins_.data(), shadow_dirs_.data(), shadow_tmax_.data(),
                         shadowed, shadow_occluded_.data());
  for (int j = 0; j < shadowed; ++j)
    PathTracer::resolve_shadow(paths_[size_t(shadowed_[size_t(j)])], shadow_occluded_[size_t(j)] != 0);
  return still;
}

void PathBatch::trace(PathStats& stats) {
  walk_slots_ = WalkSlots::of_this_thread();
  for (int k = 0; k < count_; k += Scene::kCameraPacket)
    scene_.intersect_camera_rays(&camera_rays_[size_t(k)], std::min(Scene::kCameraPacket, count_ - k),
                                 &camera_hits_[size_t(k)]);
  // A camera ray that escaped is finished at once (most of a small object's frame): it needs
  // no path state, numbers or shading, only what the world and lights give it.
  int live = 0;
  for (int k = 0; k < count_; ++k) {
    ++stats.rays;
    const CameraHit& h = camera_hits_[size_t(k)];
    if (!h.found) {
      results_[size_t(k)] = tracer_.escaped_camera_ray(camera_rays_[size_t(k)], stats);
      continue;
    }
    tracer_.begin(camera_rays_[size_t(k)], &paths_[size_t(k)]);
    live_[size_t(live)] = k;
    found_[size_t(live)] = 1;
    hits_[size_t(live++)] = h.hit;
  }
  live = advance_live(live, stats);
  while (live > 0) {
    for (int a = 0; a < live; ++a) {
      const PathState& path = paths_[size_t(live_[size_t(a)])];
      rays_[size_t(a)] = &path.ray;
      camera_[size_t(a)] = path.bounce == 0;  // a camera ray past transparent surfaces
    }
    stats.rays += uint64_t(live);
    scene_.intersect_stream(rays_.data(), camera_.data(), live, hits_.data(), found_.data());
    prefetch_shading(live);
    live = advance_live(live, stats);
  }
  for (int k = 0; k < count_; ++k)  // an escaped camera ray's result is already there
    if (camera_hits_[size_t(k)].found) results_[size_t(k)] = tracer_.finish(paths_[size_t(k)], stats);
}

}  // namespace bxdf::render

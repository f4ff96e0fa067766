// Camera samples traced together, vertex by vertex (a small wavefront): the batch's camera rays
// go to Embree in packets of nearby rays (a sample whose camera ray hit nothing is finished
// there, PathTracer::escaped_camera_ray), each later vertex's rays in one stream query, and
// between a vertex's intersections and its shading passes over the batch start loading what
// shading reads (the triangles' indices, then their vertices, then the texels a node material
// looks up at the hit's UVs), so that the batch's memory waits overlap instead of following one
// another. The vertex's Sobol-Burley numbers are drawn for all its paths at once (eight at a
// time where the CPU has AVX2: sampler/sobol_burley_batch.h). Every path is advanced by the path
// tracer's own step (PathTracer::advance_deferring_shadow), and the vertex's shadow rays then go
// to Embree together (Scene::occluded_stream) before any path's next vertex: its result is what
// tracing it alone gives.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "bxdf/microfacet/multiscatter_ggx.h"
#include "bxdf/render/integrator.h"
#include "bxdf/render/scene.h"
#include "sampler/path_sampler.h"

namespace bxdf::render {

class PathBatch {
 public:
  static constexpr int kSize = 32 * Scene::kCameraPacket;

  // A camera sample: its pixel and its number in the pixel's sequence.
  struct Sample {
    int x, y;
    uint32_t pixel_seed, index;
  };

  PathBatch(const Scene& scene, const PathTracer& tracer);

  bool full() const { return count_ == kSize; }
  int size() const { return count_; }
  void add(const Sample& sample, const Ray& camera_ray);
  // Traces every sample added since the last clear(); result(k) is sample(k)'s.
  void trace(PathStats& stats);
  const Sample& sample(int k) const { return samples_[size_t(k)]; }
  const PathResult& result(int k) const { return results_[size_t(k)]; }
  void clear() { count_ = 0; }

 private:
  // Path k's sampler at live slot a, with the numbers drawn for its vertex.
  PathSampler sampler(int k, int a) const {
    const int slot = number_slots_[size_t(a)];
    return PathSampler(samples_[size_t(k)].pixel_seed, samples_[size_t(k)].index,
                       slot < 0 ? nullptr : &numbers_[size_t(slot)]);
  }
  // Draws the numbers of the vertex every live path found, all together
  // (PathSampler::draw_vertices, draw_roulette).
  void draw_numbers(int live);
  // Starts loading what shading the live paths' hits reads.
  void prefetch_shading(int live) const;
  // Advances the live paths by one vertex each (hits_/found_ per live path): prepares every
  // hit, runs each node material's program over all of its hits at once (the hits' work
  // overlaps: MaterialGraph::evaluate_batch), then advances the paths in order. Returns how
  // many remain live (live_ compacted).
  int advance_live(int live, PathStats& stats);

  const Scene& scene_;
  const PathTracer& tracer_;
  // The tracing thread's multiscatter walk state, looked up once per trace().
  WalkSlots walk_slots_;
  int count_ = 0;
  std::array<Sample, kSize> samples_;
  std::array<Ray, kSize> camera_rays_;
  std::array<CameraHit, kSize> camera_hits_;
  std::array<PathState, kSize> paths_;
  std::array<PathResult, kSize> results_;
  // Per live path (index into the batch), its ray and what the stream query found.
  std::array<int, kSize> live_;
  std::array<const Ray*, kSize> rays_;
  std::array<uint8_t, kSize> camera_;
  std::array<uint8_t, kSize> found_;
  std::array<Hit, kSize> hits_;
  // The numbers of the vertices found (number_slots_: per live path, its entry or -1), what
  // they were drawn from, and the entries that draw a roulette number.
  std::array<int, kSize> number_slots_;
  std::array<VertexNumbers, kSize> numbers_;
  std::array<uint32_t, kSize> number_seeds_, number_indices_;
  std::array<int, kSize> number_vertices_, roulette_entries_;
  std::array<float, kSize> roulette_numbers_;
  // Per live path: its prepared hit, and where its program's registers are (null: it did not
  // run); the registers of every path in one block, the scene's largest program per path.
  std::array<PreparedHit, kSize> prepared_;
  std::array<const Vec3*, kSize> registers_;
  std::vector<Vec3> register_block_;
  size_t registers_per_path_ = 0;
  // Whether any material's program reads texels at the hit's UVs (prefetch_shading's last pass).
  bool looks_up_texels_ = false;
  // Per live path, the program still to run at its hit (null: none, or already run); one
  // program's hits at a time are gathered for evaluate_batch.
  std::array<const MaterialGraph*, kSize> programs_;
  std::array<ShadingContext, kSize> program_ctxs_;
  std::array<Vec3*, kSize> program_registers_;
  // The vertex's pending shadow rays (paths by index into the batch), tested in one stream.
  std::array<int, kSize> shadowed_;
  std::array<Vec3, kSize> shadow_origins_, shadow_dirs_;
  std::array<float, kSize> shadow_tmax_;
  std::array<uint8_t, kSize> shadow_occluded_;
};

}  // namespace bxdf::render

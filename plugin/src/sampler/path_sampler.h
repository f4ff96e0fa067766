// The random numbers of one camera sample's path, drawn from Owen-scrambled Sobol points
// (sobol_burley.h). Every decision of the path (pixel filter; at each bounce the light choice and
// light point, the BSDF sample, Russian roulette) is its own dimension set with its own hashed
// seed, so the sets are decorrelated from each other and from other pixels, while within a set
// the pixel's samples stay stratified. The numbers depend only on (render seed, pixel, sample
// index): images do not depend on threads, tiles or the split into passes.
#pragma once

#include <array>
#include <cstdint>

#include "bxdf/math.h"
#include "sampler/sobol_burley.h"

namespace bxdf::render {

// The numbers one path vertex draws, drawn ahead for a batch of paths
// (PathSampler::draw_vertices, draw_roulette): its BSDF sample, its light point (where the scene
// has a light to pick) and its roulette number (where the path may be ended there).
struct VertexNumbers {
  int vertex = -1;  // none drawn
  bool has_light = false, has_roulette = false;
  Point2 light, bsdf;
  float russian_roulette = 0.0f;
};

class PathSampler {
 public:
  // `pixel_seed` from pixel_seed(); `sample_index` counts the pixel's samples from 0. `drawn`,
  // if given, holds the numbers of one vertex, drawn ahead: the same bits as drawing them here.
  PathSampler(uint32_t pixel_seed, uint32_t sample_index, const VertexNumbers* drawn = nullptr)
      : seed_(pixel_seed),
        index_(sample_index),
        reversed_index_(sobol::reverse_bits(sample_index)),
        drawn_(drawn) {}

  // Many samples' draws at once (sobol_burley_batch.h), for i < n: the pixel filter's numbers
  // of sample (pixel_seed[i], sample_index[i]); the BSDF's (and, if `light`, the light's)
  // numbers of its path vertex vertex[i]; and that vertex's roulette number, which
  // draw_roulette adds to out[i] drawn by draw_vertices.
  static void draw_filters(const uint32_t* pixel_seed, const uint32_t* sample_index, int n,
                           Point2* out);
  static void draw_vertices(const uint32_t* pixel_seed, const uint32_t* sample_index,
                            const int* vertex, int n, bool light, VertexNumbers* out);
  static void draw_roulette(const uint32_t* pixel_seed, const uint32_t* sample_index,
                            const int* vertex, int n, float* out);

  // A pixel's seed: its position and the render seed, hashed.
  static uint32_t pixel_seed(uint32_t x, uint32_t y, uint64_t render_seed) {
    const uint32_t s = sobol::hash(static_cast<uint32_t>(render_seed) ^
                                   sobol::hash(static_cast<uint32_t>(render_seed >> 32)));
    return sobol::hash(x ^ sobol::hash(y ^ s));
  }

  Point2 filter() const { return point2(set(kFilter, 0)); }
  // The light sample at a path vertex: x picks the light and, remapped, is the light point's
  // first coordinate, y its second (Cycles' PRNG_LIGHT). Sobol dimensions 0 and 1 are the only
  // pair that is a (0, m, 2)-net; dimensions 1 and 2, which a third number for the choice
  // would leave the point, are not.
  Point2 light(int bounce) const {
    return drawn_ && drawn_->vertex == bounce && drawn_->has_light ? drawn_->light
                                                                   : point2(set(kLight, bounce));
  }
  Point2 bsdf(int bounce) const {
    return drawn_ && drawn_->vertex == bounce ? drawn_->bsdf : point2(set(kBsdf, bounce));
  }
  float russian_roulette(int bounce) const {
    if (drawn_ && drawn_->vertex == bounce && drawn_->has_roulette) return drawn_->russian_roulette;
    return sobol::sample_reversed<1>(reversed_index_, set(kRussianRoulette, bounce))[0];
  }
  // A number of its own for each (pixel, sample): the multiscatter walks' salt (nonzero, but
  // for one pair in 2^64).
  uint64_t walk_salt() const { return ((static_cast<uint64_t>(seed_) << 32) | index_) + 1u; }
  // The seed of the multiscatter sampling walks' numbers at the path's first vertex, as Cycles'
  // lcg_state_init makes it (walk_numbers.h): the pixel's hash plus the sample number times
  // 0xb4bc3953; each bounce adds 16.
  uint32_t walk_seed() const { return seed_ + index_ * 0xb4bc3953u; }

 private:
  enum Purpose : uint32_t { kFilter, kLight, kBsdf, kRussianRoulette, kPurposes };

  // The hashes of the first sets' numbers, made at compile time: one hash less per draw.
  static constexpr int kTabulatedSets = 64;
  static constexpr std::array<uint32_t, kTabulatedSets> kSetHashes = [] {
    std::array<uint32_t, kTabulatedSets> h{};
    for (uint32_t i = 0; i < kTabulatedSets; ++i) h[i] = sobol::hash(i);
    return h;
  }();

  // Set `purpose` of vertex vertex[i] (no vertex: 0) of sample (pixel_seed[i], sample_index[i])
  // for i < n, its first `dimensions` (1 or 2) coordinates handed to store(i, x, y).
  template <class Store>
  static void draw_set(const uint32_t* pixel_seed, const uint32_t* sample_index,
                       const int* vertex, int n, Purpose purpose, int dimensions, Store&& store);
  static uint32_t set(uint32_t pixel_seed, Purpose purpose, int bounce) {
    const uint32_t set_number = static_cast<uint32_t>(bounce) * kPurposes + purpose;
    return pixel_seed ^ (set_number < kTabulatedSets ? kSetHashes[set_number] : sobol::hash(set_number));
  }
  uint32_t set(Purpose purpose, int bounce) const { return set(seed_, purpose, bounce); }
  Point2 point2(uint32_t seed) const {
    const std::array<float, 2> u = sobol::sample_reversed<2>(reversed_index_, seed);
    return Point2(u[0], u[1]);
  }

  uint32_t seed_;
  uint32_t index_;
  uint32_t reversed_index_;  // reverse_bits(index_), which every set's draw starts from
  const VertexNumbers* drawn_;
};

}  // namespace bxdf::render

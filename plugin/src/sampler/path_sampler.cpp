#include "sampler/path_sampler.h"

#include <algorithm>

#include "sampler/sobol_burley_batch.h"

namespace bxdf::render {

template <class Store>
void PathSampler::draw_set(const uint32_t* pixel_seed, const uint32_t* sample_index,
                           const int* vertex, int n, Purpose purpose, int dimensions,
                           Store&& store) {
  constexpr int kChunk = 64;  // draws at a time, from arrays on the stack
  uint32_t reversed[kChunk], seed[kChunk];
  float x[kChunk], y[kChunk] = {};  // (y stays 0 for one coordinate)
  for (int first = 0; first < n; first += kChunk) {
    const int m = std::min(kChunk, n - first);
    for (int i = 0; i < m; ++i) {
      reversed[i] = sobol::reverse_bits(sample_index[first + i]);
      seed[i] = set(pixel_seed[first + i], purpose, vertex ? vertex[first + i] : 0);
    }
    if (dimensions == 2) sobol::sample_reversed_2d(reversed, seed, m, x, y);
    else sobol::sample_reversed_1d(reversed, seed, m, x);
    for (int i = 0; i < m; ++i) store(first + i, x[i], y[i]);
  }
}

void PathSampler::draw_filters(const uint32_t* pixel_seed, const uint32_t* sample_index, int n,
                               Point2* out) {
  draw_set(pixel_seed, sample_index, nullptr, n, kFilter, 2,
           [out](int i, float x, float y) { out[i] = Point2(x, y); });
}

void PathSampler::draw_vertices(const uint32_t* pixel_seed, const uint32_t* sample_index,
                                const int* vertex, int n, bool light, VertexNumbers* out) {
  draw_set(pixel_seed, sample_index, vertex, n, kBsdf, 2, [&](int i, float x, float y) {
    out[i].vertex = vertex[i];
    out[i].bsdf = Point2(x, y);
    out[i].has_light = light;
    out[i].has_roulette = false;
  });
  if (light)
    draw_set(pixel_seed, sample_index, vertex, n, kLight, 2,
             [out](int i, float x, float y) { out[i].light = Point2(x, y); });
}

void PathSampler::draw_roulette(const uint32_t* pixel_seed, const uint32_t* sample_index,
                                const int* vertex, int n, float* out) {
  draw_set(pixel_seed, sample_index, vertex, n, kRussianRoulette, 1,
           [out](int i, float x, float) { out[i] = x; });
}

}  // namespace bxdf::render

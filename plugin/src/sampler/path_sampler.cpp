#include "sampler/path_sampler.h"

#include <algorithm>

#include "sampler/sobol_burley_batch.h"

namespace bxdf::render {

namespace {
// Draws are made this many at a time, from arrays on the stack.
constexpr int kChunk = 64;
}  // namespace

void PathSampler::draw_filters(const uint32_t* pixel_seed, const uint32_t* sample_index, int n,
                               Point2* out) {
  uint32_t reversed[kChunk], seed[kChunk];
  float x[kChunk], y[kChunk];
  for (int first = 0; first < n; first += kChunk) {
    const int m = std::min(kChunk, n - first);
    for (int i = 0; i < m; ++i) {
      reversed[i] = sobol::reverse_bits(sample_index[first + i]);
      seed[i] = set(pixel_seed[first + i], kFilter, 0);
    }
    sobol::sample_reversed_2d(reversed, seed, m, x, y);
    for (int i = 0; i < m; ++i) out[first + i] = Point2(x[i], y[i]);
  }
}

void PathSampler::draw_vertices(const uint32_t* pixel_seed, const uint32_t* sample_index,
                                const int* vertex, int n, bool light, VertexNumbers* out) {
  uint32_t reversed[kChunk], seed[kChunk];
  float x[kChunk], y[kChunk];
  for (int first = 0; first < n; first += kChunk) {
    const int m = std::min(kChunk, n - first);
    VertexNumbers* o = out + first;
    for (int i = 0; i < m; ++i) reversed[i] = sobol::reverse_bits(sample_index[first + i]);
    const auto draw = [&](Purpose purpose) {
      for (int i = 0; i < m; ++i) seed[i] = set(pixel_seed[first + i], purpose, vertex[first + i]);
      sobol::sample_reversed_2d(reversed, seed, m, x, y);
    };
    draw(kBsdf);
    for (int i = 0; i < m; ++i) {
      o[i].vertex = vertex[first + i];
      o[i].bsdf = Point2(x[i], y[i]);
      o[i].has_light = light;
      o[i].has_roulette = false;
    }
    if (!light) continue;
    draw(kLight);
    for (int i = 0; i < m; ++i) o[i].light = Point2(x[i], y[i]);
  }
}

void PathSampler::draw_roulette(const uint32_t* pixel_seed, const uint32_t* sample_index,
                                const int* vertex, int n, float* out) {
  uint32_t reversed[kChunk], seed[kChunk];
  for (int first = 0; first < n; first += kChunk) {
    const int m = std::min(kChunk, n - first);
    for (int i = 0; i < m; ++i) {
      reversed[i] = sobol::reverse_bits(sample_index[first + i]);
      seed[i] = set(pixel_seed[first + i], kRussianRoulette, vertex[first + i]);
    }
    sobol::sample_reversed_1d(reversed, seed, m, out + first);
  }
}

}  // namespace bxdf::render

// Many Sobol-Burley draws at once: the first one or two coordinates of n (index, seed) pairs,
// the same bits as sobol::sample_reversed<1> / <2> for each. A draw is integer hashing and
// multiplying with no branch, so on a CPU with AVX2 eight go through the vector unit together
// (checked once, at run time: the module itself is built for baseline x86-64, as Cycles builds
// its kernels for several instruction sets and picks one when it starts). There Sobol
// dimension 1 is computed with bit operations (its generator matrix is Pascal's triangle mod 2)
// instead of the four table lookups of sobol_burley.h, which a vector unit cannot do.
#pragma once

#include <cstdint>

namespace bxdf::render::sobol {

// x[i], y[i] = sample_reversed<2>(reversed_index[i], seed[i]) for i < n.
void sample_reversed_2d(const uint32_t* reversed_index, const uint32_t* seed, int n, float* x,
                        float* y);
// x[i] = sample_reversed<1>(reversed_index[i], seed[i])[0] for i < n.
void sample_reversed_1d(const uint32_t* reversed_index, const uint32_t* seed, int n, float* x);

// reverse_bits(sobol(index, 1)) by bit operations: bit j of the result is the parity of the
// index bits i whose positions contain j's (i & j == j; Lucas' theorem), a superset sum over
// the five bits of a position, one shift-and-mask step per bit.
constexpr uint32_t reversed_sobol_dimension1(uint32_t index) {
  uint32_t g = index;
  g ^= (g >> 1) & 0x55555555u;
  g ^= (g >> 2) & 0x33333333u;
  g ^= (g >> 4) & 0x0f0f0f0fu;
  g ^= (g >> 8) & 0x00ff00ffu;
  g ^= (g >> 16) & 0x0000ffffu;
  return g;
}

}  // namespace bxdf::render::sobol

#include "sampler/sobol_burley_batch.h"

#include <immintrin.h>

#include "sampler/sobol_burley.h"

namespace bxdf::render::sobol {

namespace {

#define BXDF_AVX2 __attribute__((target("avx2")))

BXDF_AVX2 inline __m256i splat(uint32_t v) { return _mm256_set1_epi32(static_cast<int>(v)); }

BXDF_AVX2 inline __m256i hash8(__m256i x) {  // hash(), lane by lane
  x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
  x = _mm256_mullo_epi32(x, splat(0x7feb352du));
  x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 15));
  x = _mm256_mullo_epi32(x, splat(0x846ca68bu));
  return _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
}

BXDF_AVX2 inline __m256i owen_scramble_reversed8(__m256i n, __m256i seed) {
  n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, splat(0x3d20adeau)));
  n = _mm256_add_epi32(n, seed);
  n = _mm256_mullo_epi32(n, _mm256_or_si256(_mm256_srli_epi32(seed, 16), splat(1u)));
  n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, splat(0x05526c56u)));
  return _mm256_xor_si256(n, _mm256_mullo_epi32(n, splat(0x53a22864u)));
}

BXDF_AVX2 inline __m256i reverse_bits8(__m256i x) {
  // Each nibble reversed by a 16-entry lookup, the two nibbles of a byte swapped, then the
  // bytes of each 32-bit lane in reverse order.
  const __m256i nibbles = _mm256_setr_epi8(0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5,
                                           0xd, 0x3, 0xb, 0x7, 0xf, 0x0, 0x8, 0x4, 0xc, 0x2, 0xa,
                                           0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf);
  const __m256i low = _mm256_set1_epi8(0x0f);
  const __m256i lo = _mm256_shuffle_epi8(nibbles, _mm256_and_si256(x, low));
  const __m256i hi = _mm256_shuffle_epi8(nibbles, _mm256_and_si256(_mm256_srli_epi16(x, 4), low));
  const __m256i bytes = _mm256_or_si256(_mm256_slli_epi16(lo, 4), hi);
  const __m256i swap = _mm256_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 3, 2,
                                        1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
  return _mm256_shuffle_epi8(bytes, swap);
}

BXDF_AVX2 inline __m256i reversed_sobol_dimension1_8(__m256i g) {
  g = _mm256_xor_si256(g, _mm256_and_si256(_mm256_srli_epi32(g, 1), splat(0x55555555u)));
  g = _mm256_xor_si256(g, _mm256_and_si256(_mm256_srli_epi32(g, 2), splat(0x33333333u)));
  g = _mm256_xor_si256(g, _mm256_and_si256(_mm256_srli_epi32(g, 4), splat(0x0f0f0f0fu)));
  g = _mm256_xor_si256(g, _mm256_and_si256(_mm256_srli_epi32(g, 8), splat(0x00ff00ffu)));
  return _mm256_xor_si256(g, _mm256_srli_epi32(g, 16));
}

// reversed_to_unit_float(), lane by lane: the top 24 bits of the unreversed value.
BXDF_AVX2 inline __m256 reversed_to_unit_float8(__m256i reversed) {
  const __m256i top24 = _mm256_srli_epi32(reverse_bits8(reversed), 8);
  return _mm256_mul_ps(_mm256_cvtepi32_ps(top24), _mm256_set1_ps(0x1p-24f));
}

// Coordinates 0 (and 1) of eight draws, as sample_reversed computes them: the shuffled index,
// whose bit reversal is both dimension 0's reversed coordinate and dimension 1's argument.
template <int N>
BXDF_AVX2 void sample8(const uint32_t* reversed_index, const uint32_t* seed, float* x, float* y) {
  const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(seed));
  const __m256i ri = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(reversed_index));
  const __m256i shuffled =
      reverse_bits8(owen_scramble_reversed8(ri, hash8(_mm256_xor_si256(s, splat(kSalt[kDimensions])))));
  const __m256i o0 = owen_scramble_reversed8(shuffled, hash8(_mm256_xor_si256(s, splat(kSalt[0]))));
  _mm256_storeu_ps(x, reversed_to_unit_float8(o0));
  if constexpr (N == 2) {
    const __m256i o1 = owen_scramble_reversed8(reversed_sobol_dimension1_8(shuffled),
                                               hash8(_mm256_xor_si256(s, splat(kSalt[1]))));
    _mm256_storeu_ps(y, reversed_to_unit_float8(o1));
  }
}

bool has_avx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}

template <int N>
void sample_batch(const uint32_t* reversed_index, const uint32_t* seed, int n, float* x, float* y) {
  int i = 0;
  if (has_avx2())
    for (; i + 8 <= n; i += 8) sample8<N>(reversed_index + i, seed + i, x + i, N == 2 ? y + i : nullptr);
  for (; i < n; ++i) {
    const std::array<float, N> u = sample_reversed<N>(reversed_index[i], seed[i]);
    x[i] = u[0];
    if constexpr (N == 2) y[i] = u[1];
  }
}

}  // namespace

void sample_reversed_2d(const uint32_t* reversed_index, const uint32_t* seed, int n, float* x,
                        float* y) {
  sample_batch<2>(reversed_index, seed, n, x, y);
}

void sample_reversed_1d(const uint32_t* reversed_index, const uint32_t* seed, int n, float* x) {
  sample_batch<1>(reversed_index, seed, n, x, nullptr);
}

}  // namespace bxdf::render::sobol

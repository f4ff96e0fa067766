// Owen-scrambled, shuffled Sobol points (Burley 2020, "Practical Hash-based Owen Scrambling"),
// the sequence Cycles 3.4 calls Sobol-Burley. Each call gives one coordinate set of one sample:
// the sample index is shuffled by a nested uniform scramble and every coordinate is Owen-scrambled,
// both seeded, so that any seed gives points that are uniformly distributed (unbiased) and keep
// the Sobol net's stratification: every power-of-two prefix of a 1D coordinate has one point per
// stratum, and the first two coordinates together form a (0, m, 2)-net. Higher dimensions of a
// path come from independent seeds (padding), not from higher Sobol dimensions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace bxdf::render::sobol {

// The Sobol coordinates this sampler draws from (Joe and Kuo's first four dimensions).
constexpr int kDimensions = 4;

// Generator-matrix columns of Sobol dimension `d` (0 = van der Corput): column i is the
// contribution of index bit i, as a 32-bit binary fraction.
const std::array<uint32_t, 32>& directions(int d);

constexpr uint32_t reverse_bits(uint32_t x) {
  // Bits within each byte, then the bytes with one byte swap (one instruction on x86).
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(x);
}

// An integer hash with good avalanche (Wellons' lowbias32): turns structured seeds (pixel
// numbers, dimension numbers) into unrelated ones.
constexpr uint32_t hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Base-2 Owen scrambling of a bit-reversed value: each bit is flipped depending only on the bits
// below it (the more significant bits of the unreversed value), which is what Owen's nested
// scrambling requires. The hash is Vegdahl's improved Laine-Karras permutation (psychopath.io,
// 2021), the one Cycles uses.
inline uint32_t owen_scramble_reversed(uint32_t n, uint32_t seed) {
  n ^= n * 0x3d20adeau;
  n += seed;
  n *= (seed >> 16) | 1u;
  n ^= n * 0x05526c56u;
  n ^= n * 0x53a22864u;
  return n;
}

// Nested uniform (Owen) scramble of a 32-bit binary fraction.
inline uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(owen_scramble_reversed(reverse_bits(x), seed));
}

// The generator matrix of dimension `d` applied to each byte value of each index byte: the
// product with a 32-bit index is then four lookups (indices are full 32-bit numbers after
// shuffling, so a loop over their bits would take 32 steps).
using ByteTables = std::array<std::array<uint32_t, 256>, 4>;
const ByteTables& byte_tables(int d);

// The same products in the bit-reversed domain: table j maps byte j of reverse_bits(index) to
// the bit-reversed contribution of that byte, so reverse_bits(sobol(index, d)) =
// XOR over j of table[j][byte j of reverse_bits(index)]. sample() works there, where Owen
// scrambling does, and so skips two bit reversals per coordinate.
const ByteTables& reversed_byte_tables(int d);

// Unscrambled Sobol coordinate `d` (< kDimensions) of point `index`, as a 32-bit fraction.
inline uint32_t sobol(uint32_t index, int d) {
  if (d == 0) return reverse_bits(index);  // van der Corput
  const ByteTables& t = byte_tables(d);
  return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^
         t[3][index >> 24];
}

// [0, 1): the top 24 bits, so that the float is never rounded up to 1.
inline float to_unit_float(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

// Every byte value with its bits reversed.
inline constexpr std::array<uint8_t, 256> kReversedBytes = [] {
  std::array<uint8_t, 256> t{};
  for (uint32_t v = 0; v < 256; ++v) t[v] = static_cast<uint8_t>(reverse_bits(v) >> 24);
  return t;
}();

// to_unit_float(reverse_bits(x)), from the three low bytes of x, the only ones that reach the
// float's 24 bits: a table lookup per byte is cheaper than reversing all 32 bits (a sample's
// draws do this once per coordinate).
inline float reversed_to_unit_float(uint32_t x) {
  const uint32_t top24 = (uint32_t(kReversedBytes[x & 0xffu]) << 16) |
                         (uint32_t(kReversedBytes[(x >> 8) & 0xffu]) << 8) |
                         kReversedBytes[(x >> 16) & 0xffu];
  return static_cast<float>(top24) * 0x1p-24f;
}

// Per-coordinate seeds of sample() (entry kDimensions: the index shuffle): arbitrary distinct
// constants mixed with the seed through the hash.
inline constexpr uint32_t kSalt[kDimensions + 1] = {0x9e78e391u, 0x67c33241u, 0x78c395c5u,
                                                    0x39468210u, 0xcaa726acu};

// Coordinates 0..N-1 of sample `index` of the sequence seeded by `seed` (N <= kDimensions),
// from the index's bit reversal: a path reverses its sample index once for all its sets.
// Different seeds give statistically independent sequences.
template <int N>
std::array<float, N> sample_reversed(uint32_t reversed_index, uint32_t seed) {
  static_assert(N >= 1 && N <= kDimensions, "Sobol-Burley draws up to kDimensions coordinates");
  // Equal, bit for bit, to
  //   shuffled = owen_scramble(index, hash(seed ^ kSalt[kDimensions]));
  //   out[d] = to_unit_float(owen_scramble(sobol(shuffled, d), hash(seed ^ kSalt[d])));
  // computed in the bit-reversed domain (reversed_shuffled = reverse_bits(shuffled)).
  const uint32_t reversed_shuffled =
      owen_scramble_reversed(reversed_index, hash(seed ^ kSalt[kDimensions]));
  std::array<float, N> out{};
  for (int d = 0; d < N; ++d) {
    uint32_t reversed;  // reverse_bits(sobol(shuffled, d))
    if (d == 0) {
      reversed = reverse_bits(reversed_shuffled);  // van der Corput is the reversal itself
    } else {
      const ByteTables& t = reversed_byte_tables(d);
      reversed = t[0][reversed_shuffled & 0xffu] ^ t[1][(reversed_shuffled >> 8) & 0xffu] ^
                 t[2][(reversed_shuffled >> 16) & 0xffu] ^ t[3][reversed_shuffled >> 24];
    }
    out[static_cast<std::size_t>(d)] =
        reversed_to_unit_float(owen_scramble_reversed(reversed, hash(seed ^ kSalt[d])));
  }
  return out;
}

template <int N>
std::array<float, N> sample(uint32_t index, uint32_t seed) {
  return sample_reversed<N>(reverse_bits(index), seed);
}

}  // namespace bxdf::render::sobol

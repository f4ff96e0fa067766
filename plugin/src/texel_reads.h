// How texels are read and weighted, shared by single images (texture.cpp) and interleaved
// image groups (texture_group.cpp): four channels as one SIMD value, the storages' readers,
// and the weighted sum of a footprint's texels in Cycles' order.
#pragma once

#include <cstdint>
#include <cstring>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "bxdf/render/texture.h"

namespace bxdf::render {

// Four channels as one SIMD value (GCC/Clang vector extensions: SSE on x86-64, scalar code
// elsewhere). The arithmetic is Cycles' own, channel by channel and in its order, so a lookup
// is the same float result as the scalar formula; only the instructions are fewer.
typedef float Float4 __attribute__((vector_size(16)));
typedef int32_t Int4 __attribute__((vector_size(16)));
typedef unsigned char Byte4 __attribute__((vector_size(4)));

inline Float4 splat4(float v) { return Float4{v, v, v, v}; }
inline RGBA to_rgba(Float4 c) { return {c[0], c[1], c[2], c[3]}; }

// The three storages' texels as Cycles reads them (bytes as byte · (1/255)), decoded from their
// first byte: in an image's own array and in interleaved records alike.
inline Float4 decode_floats(const unsigned char* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);  // an RGBA of floats
  return v;
}
inline Float4 decode_bytes(const unsigned char* p) {
#ifdef __SSE2__
  // Widened by unpacking with zeros and converted in one instruction: baseline x86-64 has no
  // byte-to-int conversion, and the generic form below converts channel by channel.
  int32_t word;
  std::memcpy(&word, p, sizeof word);
  const __m128i zero = _mm_setzero_si128();
  const __m128i ints = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(word), zero), zero);
  return Float4(_mm_cvtepi32_ps(ints)) * splat4(1.0f / 255.0f);
#else
  Byte4 b;
  std::memcpy(&b, p, sizeof b);
  return __builtin_convertvector(b, Float4) * splat4(1.0f / 255.0f);
#endif
}
inline Float4 decode_grey_byte(const unsigned char* p) {
  const float v = float(*p) * (1.0f / 255.0f);
  return Float4{v, v, v, 1.0f};
}

// Texel i of a storage whose texels lie `stride` bytes apart from `base` on.
template <Float4 (*Decode)(const unsigned char*)>
struct StridedTexels {
  const unsigned char* base;
  size_t stride;
  Float4 operator[](size_t i) const { return Decode(base + i * stride); }
};
using FloatTexels = StridedTexels<decode_floats>;
using ByteTexels = StridedTexels<decode_bytes>;
using GreyByteTexels = StridedTexels<decode_grey_byte>;

// Texel (x, y), or zero outside the grid (only Clip reaches outside).
template <class Texels>
Float4 read_clip(int width, int height, const Texels& t, int x, int y) {
  if (x < 0 || x >= width || y < 0 || y >= height) return Float4{};
  return t[size_t(y) * size_t(width) + size_t(x)];
}

// Texel (i, j) of the footprint: unchecked when all of it is inside the grid, else zero
// outside (only Clip reaches outside).
template <bool kInside, class Texels>
Float4 footprint_texel(int width, int height, const Texels& t, const TexelFootprint& f, int i,
                       int j) {
  if constexpr (kInside) return t[f.rows[j] + size_t(f.xs[i])];
  else return read_clip(width, height, t, f.xs[i], f.ys[j]);
}

// A bilinear footprint's four weights (w10: column 1 of row 0), as Float4s.
struct BilinearWeights {
  Float4 w00, w10, w01, w11;
};
inline BilinearWeights bilinear_weights(const TexelFootprint& f) {
  return {splat4(f.wy[0] * f.wx[0]), splat4(f.wy[0] * f.wx[1]), splat4(f.wy[1] * f.wx[0]),
          splat4(f.wy[1] * f.wx[1])};
}
// Cycles' bilinear sum: the two rows' pairs, then their sum.
inline Float4 bilinear_sum(const BilinearWeights& w, Float4 t00, Float4 t10, Float4 t01,
                           Float4 t11) {
  return (t00 * w.w00 + t10 * w.w10) + (t01 * w.w01 + t11 * w.w11);
}

// The weighted sum of the footprint's texels, in Cycles' order (bilinear: the two rows'
// pairs, then their sum; cubic: each row, then the rows).
template <bool kInside, class Texels>
Float4 gather(int width, int height, const Texels& t, const TexelFootprint& f) {
  auto at = [&](int i, int j) { return footprint_texel<kInside>(width, height, t, f, i, j); };
  switch (f.n) {
    case 0: return Float4{};
    case 1: return at(0, 0);
    case 2: return bilinear_sum(bilinear_weights(f), at(0, 0), at(1, 0), at(0, 1), at(1, 1));
    default: {
      Float4 out{};
      for (int j = 0; j < 4; ++j) {
        Float4 row{};
        for (int i = 0; i < 4; ++i) row += at(i, j) * splat4(f.wx[i]);
        out += row * splat4(f.wy[j]);
      }
      return out;
    }
  }
}

template <class Texels>
Float4 gather(int width, int height, const Texels& t, const TexelFootprint& f) {
  return f.inside ? gather<true>(width, height, t, f) : gather<false>(width, height, t, f);
}

// A grid's texels as one array: its storage, first byte and bytes per texel.
struct TexelArray {
  TexelStorage storage;
  const unsigned char* base;
  size_t size;
};
inline TexelArray texel_array(const TexelGrid& g) {
  if (!g.grey_bytes.empty()) return {TexelStorage::GreyBytes, g.grey_bytes.data(), 1};
  if (!g.bytes.empty()) return {TexelStorage::Bytes, g.bytes.front().data(), 4};
  return {TexelStorage::Floats, reinterpret_cast<const unsigned char*>(g.texels.data()), sizeof(RGBA)};
}

// gather() over texels of `storage` lying `stride` bytes apart from `base` on (an image's own
// array, or its place in interleaved records).
inline Float4 gather_stored(int width, int height, TexelStorage storage, const unsigned char* base,
                            size_t stride, const TexelFootprint& f) {
  switch (storage) {
    case TexelStorage::GreyBytes: return gather(width, height, GreyByteTexels{base, stride}, f);
    case TexelStorage::Bytes: return gather(width, height, ByteTexels{base, stride}, f);
    case TexelStorage::Floats: break;
  }
  return gather(width, height, FloatTexels{base, stride}, f);
}

// The image node's conversion of gathered texels: alpha unassociated when asked, then sRGB to
// linear for sRGB images (Cycles' order).
Float4 image_node_convert(const TextureSettings& settings, Float4 texels, bool unassociate);
// The node's outputs as a graph's registers hold them: colour in out[0], alpha in out[1].
inline void store_node_outputs(Float4 c, Vec3* out) {
  out[0] = Vec3(c[0], c[1], c[2]);
  out[1] = Vec3(c[3], c[3], c[3]);
}

}  // namespace bxdf::render

// Running the core's batch (structure-of-arrays) API over numpy's array-of-structures rows:
// chunks small enough to stay in L1 are gathered into SoA buffers on the stack, and large
// batches are split over all cores with TBB. Callers release the GIL around these.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>

#include "array_args.h"
#include "bxdf/bxdf.h"

namespace bxdf::python {

// Directions per SoA buffer: 3 buffers of 3 × 512 floats = 18 KiB, inside L1.
constexpr size_t kChunk = 512;
// Directions per TBB task: large enough that scheduling costs nothing, small enough that two
// cores share a 100 k batch evenly. Batches up to this size stay on the calling thread.
constexpr size_t kTaskGrain = 4096;

// Calls fn(begin, end) over [0, n) in pieces of at most kChunk, in parallel for large n.
template <class Fn>
void for_each_chunk(size_t n, const Fn& fn) {
  auto run = [&fn](size_t begin, size_t end) {
    for (size_t b = begin; b < end; b += kChunk) fn(b, std::min(end, b + kChunk));
  };
  if (n <= kTaskGrain) {
    run(0, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kTaskGrain),
                    [&run](const tbb::blocked_range<size_t>& r) { run(r.begin(), r.end()); });
}

// Three float lanes of one chunk (x/y/z of directions, or r/g/b of colours).
struct SoA3 {
  alignas(64) float a[kChunk];
  alignas(64) float b[kChunk];
  alignas(64) float c[kChunk];
  DirectionsIn in() const { return {a, b, c}; }
  DirectionsOut out() { return {a, b, c}; }
  RGBOut rgb() { return {a, b, c}; }
};

// Two float lanes of one chunk (the u1, u2 of sample_f).
struct SoA2 {
  alignas(64) float a[kChunk];
  alignas(64) float b[kChunk];
};

// Rows [begin, begin + count) of a (N, 3) argument (broadcasting a single row) into SoA lanes.
inline void gather3(const VectorRows& v, size_t begin, size_t count, SoA3& dst) {
  if (v.rows == 1) {
    const float* p = v.data;
    std::fill_n(dst.a, count, p[0]);
    std::fill_n(dst.b, count, p[1]);
    std::fill_n(dst.c, count, p[2]);
    return;
  }
  const float* p = v.data + begin * 3;
  for (size_t i = 0; i < count; ++i) {
    dst.a[i] = p[3 * i];
    dst.b[i] = p[3 * i + 1];
    dst.c[i] = p[3 * i + 2];
  }
}

// Rows of an (N, 2) argument into two lanes.
inline void gather2(const VectorRows& v, size_t begin, size_t count, SoA2& dst) {
  if (v.rows == 1) {
    std::fill_n(dst.a, count, v.data[0]);
    std::fill_n(dst.b, count, v.data[1]);
    return;
  }
  const float* p = v.data + begin * 2;
  for (size_t i = 0; i < count; ++i) {
    dst.a[i] = p[2 * i];
    dst.b[i] = p[2 * i + 1];
  }
}

// SoA lanes back into rows [begin, begin + count) of a C-contiguous (N, 3) output.
inline void scatter3(const SoA3& src, size_t begin, size_t count, float* out) {
  float* p = out + begin * 3;
  for (size_t i = 0; i < count; ++i) {
    p[3 * i] = src.a[i];
    p[3 * i + 1] = src.b[i];
    p[3 * i + 2] = src.c[i];
  }
}

}  // namespace bxdf::python

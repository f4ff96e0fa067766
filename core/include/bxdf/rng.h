// PCG32 (O'Neill 2014): small, fast, seedable, with independent streams, so that every
// tile, thread and test draws a reproducible sequence.
#pragma once

#include <cstdint>

namespace bxdf {

class PCG32 {
 public:
  PCG32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  explicit PCG32(uint64_t seq_index, uint64_t init_state = 0x853c49e6748fea9bULL) {
    seed(init_state, seq_index);
  }
  void seed(uint64_t init_state, uint64_t seq_index) {
    state_ = 0u;
    inc_ = (seq_index << 1u) | 1u;
    next_u32();
    state_ += init_state;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 0x5851f42d4c957f2dULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  // Uniform in [0, 1): the top 24 bits, so the result is never rounded up to 1.
  float uniform() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  double uniform_double() {
    const uint64_t hi = next_u32(), lo = next_u32();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53;
  }
  uint32_t bounded(uint32_t bound) {  // uniform in [0, bound), unbiased
    const uint32_t threshold = (~bound + 1u) % bound;
    for (;;) {
      const uint32_t r = next_u32();
      if (r >= threshold) return r % bound;
    }
  }

 private:
  uint64_t state_ = 0, inc_ = 0;
};

}  // namespace bxdf

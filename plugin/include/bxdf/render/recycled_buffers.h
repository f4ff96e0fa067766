// Mesh arrays kept from one scene for the next. Inside Blender, whose malloc (jemalloc) hands
// freed pages back to the kernel within a fraction of a second, each new scene's arrays were
// fresh memory, faulted in 4 KB at a time: ~1000 page faults, 11 ms of the conversion of a
// 242k-triangle harness scene on a VM where a fault costs ~9 µs, against 3 ms in the same
// process with the pages kept. A Scene gives its meshes' arrays back when it is destroyed; the
// next scene's conversion takes them (a buffer of about the same size, or a new one).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace bxdf::render::recycled {

// At most this many bytes are kept between scenes; past it the largest buffers are freed.
inline constexpr size_t kMaxKeptBytes = size_t(64) << 20;

// An empty vector with room for `n` elements: a kept buffer of capacity n to 1.25 n if there
// is one, else a new one. Thread-safe.
std::vector<float> floats(size_t n);
std::vector<uint32_t> indices(size_t n);

// The n values at `first` (converted to T: float or uint32_t) in a buffer from floats() or
// indices() with room for `room` >= n elements.
template <typename T, typename From>
std::vector<T> copied(const From* first, size_t n, size_t room) {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, uint32_t>);
  std::vector<T> v;
  if constexpr (std::is_same_v<T, float>) {
    v = floats(room);
  } else {
    v = indices(room);
  }
  v.assign(first, first + n);
  return v;
}

// Keeps `v`'s buffer (emptied) for a later request, or frees it past kMaxKeptBytes.
void keep(std::vector<float>&& v);
void keep(std::vector<uint32_t>&& v);

// Bytes kept now, and the kept buffers freed (tests; a process might call it to give memory
// back).
size_t kept_bytes();
void release_all();

}  // namespace bxdf::render::recycled

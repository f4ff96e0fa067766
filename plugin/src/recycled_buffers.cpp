#include "bxdf/render/recycled_buffers.h"

#include <map>
#include <mutex>
#include <utility>

namespace bxdf::render::recycled {

namespace {

std::mutex g_mutex;
size_t g_kept_bytes = 0;  // both pools', under g_mutex

// Kept buffers of one element type, by capacity in elements. Never destroyed: a scene may be
// destroyed during the process's exit, after the static objects.
template <typename T>
std::multimap<size_t, std::vector<T>>& pool() {
  static auto* buffers = new std::multimap<size_t, std::vector<T>>;
  return *buffers;
}

template <typename T>
std::vector<T> take(size_t n) {
  if (n > 0) {
    std::lock_guard<std::mutex> lock(g_mutex);
    auto& buffers = pool<T>();
    // The smallest kept buffer that holds n, unless it is much larger (it would sit unused in
    // a small mesh while a large one allocates anew).
    const auto it = buffers.lower_bound(n);
    if (it != buffers.end() && it->first <= n + n / 4) {
      std::vector<T> v = std::move(it->second);
      g_kept_bytes -= it->first * sizeof(T);
      buffers.erase(it);
      return v;
    }
  }
  std::vector<T> v;
  v.reserve(n);
  return v;
}

// Frees the largest kept buffers of either type until the total is within the bound.
void trim_locked() {
  while (g_kept_bytes > kMaxKeptBytes) {
    auto& f = pool<float>();
    auto& u = pool<uint32_t>();
    const size_t f_bytes = f.empty() ? 0 : f.rbegin()->first * sizeof(float);
    const size_t u_bytes = u.empty() ? 0 : u.rbegin()->first * sizeof(uint32_t);
    if (f_bytes == 0 && u_bytes == 0) break;
    if (f_bytes >= u_bytes) {
      f.erase(std::prev(f.end()));
      g_kept_bytes -= f_bytes;
    } else {
      u.erase(std::prev(u.end()));
      g_kept_bytes -= u_bytes;
    }
  }
}

template <typename T>
void keep_buffer(std::vector<T>&& v) {
  const size_t capacity = v.capacity();
  if (capacity == 0 || capacity * sizeof(T) > kMaxKeptBytes) return;  // v frees its own
  v.clear();
  std::lock_guard<std::mutex> lock(g_mutex);
  pool<T>().emplace(capacity, std::move(v));
  g_kept_bytes += capacity * sizeof(T);
  trim_locked();
}

}  // namespace

std::vector<float> floats(size_t n) { return take<float>(n); }
std::vector<uint32_t> indices(size_t n) { return take<uint32_t>(n); }
void keep(std::vector<float>&& v) { keep_buffer(std::move(v)); }
void keep(std::vector<uint32_t>&& v) { keep_buffer(std::move(v)); }

size_t kept_bytes() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_kept_bytes;
}

void release_all() {
  std::lock_guard<std::mutex> lock(g_mutex);
  pool<float>().clear();
  pool<uint32_t>().clear();
  g_kept_bytes = 0;
}

}  // namespace bxdf::render::recycled

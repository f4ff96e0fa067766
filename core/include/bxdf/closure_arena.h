// Fixed storage for the models one shading point builds from per-hit values (a material
// graph's closures): the renderer keeps one per thread, resets it at every hit, and nothing in
// it touches the heap. The registry's ModelInfo::place builds a model here.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include "bxdf/bxdf.h"

namespace bxdf {

class ClosureArena {
 public:
  static constexpr size_t kCapacity = 8192;  // bytes; a Principled closure set fits many times
  static constexpr int kMaxObjects = 16;

  ClosureArena() = default;
  ~ClosureArena() { reset(); }
  ClosureArena(const ClosureArena&) = delete;
  ClosureArena& operator=(const ClosureArena&) = delete;

  // Builds a T in the arena; nullptr when it is full (material set-up checks that a material's
  // closures fit, so a renderer never sees that).
  template <class T, class... Args>
  T* make(Args&&... args) {
    static_assert(std::is_base_of_v<BxDF, T>, "the arena holds BxDFs");
    static_assert(alignof(T) <= kAlignment, "over-aligned model");
    const size_t offset = (used_ + alignof(T) - 1) & ~(alignof(T) - 1);
    if (offset + sizeof(T) > kCapacity || count_ == kMaxObjects) return nullptr;
    T* object = new (storage_ + offset) T(std::forward<Args>(args)...);
    used_ = offset + sizeof(T);
    objects_[count_++] = object;
    return object;
  }
  // Destroys everything made since the last reset.
  void reset() {
    for (int i = 0; i < count_; ++i) objects_[i]->~BxDF();
    count_ = 0;
    used_ = 0;
  }
  size_t used() const { return used_; }

 private:
  static constexpr size_t kAlignment = 64;
  alignas(kAlignment) unsigned char storage_[kCapacity];
  BxDF* objects_[kMaxObjects] = {};
  int count_ = 0;
  size_t used_ = 0;
};

}  // namespace bxdf

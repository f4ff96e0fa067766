// N objects of a trivially copyable type whose members have initialisers, left uninitialised:
// per-hit scratch (a BSDF's component slots, a material graph's parameter values) that would
// otherwise be written in full at every path vertex, and whose used part is written before it
// is read.
#pragma once

#include <cstddef>
#include <type_traits>

namespace bxdf {

template <class T, size_t N>
union Uninitialised {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "only plain data may be left uninitialised");
  Uninitialised() {}
  T items[N];
  T& operator[](size_t i) { return items[i]; }
  const T& operator[](size_t i) const { return items[i]; }
};

}  // namespace bxdf

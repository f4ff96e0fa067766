// Small conversions used by the models' factories.
#pragma once

#include <memory>

#include "bxdf/closure_arena.h"
#include "bxdf/fresnel.h"
#include "bxdf/params.h"
#include "bxdf/spectrum.h"

namespace bxdf {

inline RGB to_rgb(const RGBValue& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}
inline RGBValue to_rgb_value(const RGB& c) { return {c.r, c.g, c.b}; }

// For a model whose factory picks a class at run time (a template over the distribution): one
// builder serves create() and place() by passing the chosen class as Type<T> to an `emit`
// that is make_from (heap) or place_from (a ClosureArena).
template <class T>
struct Type {};

template <class T, class... Args>
std::unique_ptr<BxDF> make_from(Type<T>, const Args&... args) {
  return std::make_unique<T>(args...);
}
template <class T, class... Args>
const BxDF* place_from(ClosureArena& arena, Type<T>, const Args&... args) {
  return arena.make<T>(args...);
}

}  // namespace bxdf

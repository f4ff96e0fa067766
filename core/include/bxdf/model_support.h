// Small conversions used by the models' factories.
#pragma once

#include "bxdf/fresnel.h"
#include "bxdf/params.h"
#include "bxdf/spectrum.h"

namespace bxdf {

inline RGB to_rgb(const RGBValue& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}
inline RGBValue to_rgb_value(const RGB& c) { return {c.r, c.g, c.b}; }

}  // namespace bxdf

// CIE 1931 2° colour matching functions at the Cornell wavelengths (400–700 nm, 10 nm) and the
// conversion of such a 31-sample spectrum to linear Rec.709 RGB.
#pragma once

#include "bxdf/spectrum.h"

namespace bxdf {

constexpr int kCieSamples = 31;           // 400, 410, ..., 700 nm
constexpr float kCieFirstWavelength = 400.0f;
constexpr float kCieWavelengthStep = 10.0f;

// x̄, ȳ, z̄ at 400 + 10 i nm.
struct CieSample {
  float x, y, z;
};
const CieSample& cie1931_2deg(int i);

// Linear Rec.709 RGB of a spectrum sampled at the 31 wavelengths above. Normalised so that a
// spectrally flat spectrum of value v gives exactly (v, v, v); see cie1931.cpp.
RGB spectrum_to_rgb(const float* values31);

}  // namespace bxdf

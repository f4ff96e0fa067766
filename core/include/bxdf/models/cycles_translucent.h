// Cycles 3.4's Translucent BSDF (closure/bsdf_diffuse.h, bsdf_translucent_*): eval =
// max(−N·L, 0)/π with N turned to the viewer, cosine-sampled about −N; times the colour. In the
// local frame that is colour/π for wi on the side opposite to wo, whichever side wo is on,
// which is exactly LambertianTransmission; this model is that class with Cycles' parameter name.
#pragma once

#include "bxdf/models/lambertian_transmission.h"

namespace bxdf {

using CyclesTranslucent = LambertianTransmission;

}  // namespace bxdf

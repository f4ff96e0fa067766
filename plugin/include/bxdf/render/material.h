// A surface material: one registry model or several combined into one BSDF, plus an optional
// emitted radiance (which turns the triangles using it into an area light).
#pragma once

#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/spectrum.h"

namespace bxdf::render {

struct Material {
  std::vector<BxDFPtr> components;  // shared, immutable models (at most BSDF::kMaxComponents)
  RGB emission;                     // W/(m² sr), emitted from both sides
};

}  // namespace bxdf::render

// A surface material: one registry model or several combined into one BSDF, plus an optional
// emitted radiance (which turns the triangles using it into an area light), or a material graph.
#pragma once

#include <memory>
#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/render/material_graph.h"
#include "bxdf/spectrum.h"

namespace bxdf::render {

struct Material {
  std::vector<BxDFPtr> components;  // shared, immutable models (at most BSDF::kMaxComponents)
  RGB emission;                     // W/(m² sr), emitted from both sides
  // A node material: closures and emission evaluated per hit (components is then empty, and
  // emission holds the graph's emission when that is a constant, so that it is an area light).
  std::shared_ptr<const MaterialGraph> graph = nullptr;

  // Whether a hit on it may add emitted light: a nonzero constant, or a graph's emission that
  // varies per hit.
  bool may_emit() const { return !emission.is_black() || (graph && !graph->emission_is_constant()); }
};

}  // namespace bxdf::render

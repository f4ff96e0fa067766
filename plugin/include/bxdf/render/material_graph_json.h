// Reads a material graph (docs/material-graph.md) from JSON: the shared reader behind scene
// files, material files and bxdf.render. Every error names the field's path inside the graph.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "bxdf/params.h"
#include "bxdf/render/material_graph.h"
#include "bxdf/render/texture.h"

namespace bxdf::render {

// A bad graph: `field` is the path below the graph's owner ("graph.nodes[4].vector"),
// `problem` what is wrong; what() joins them.
struct GraphFieldError : ParameterError {
  GraphFieldError(std::string field_, std::string problem_)
      : ParameterError(field_ + ": " + problem_), field(std::move(field_)),
        problem(std::move(problem_)) {}
  std::string field, problem;
};

// `graph` is the value of a material's "graph" key; `field` its path ("graph"); relative
// texture paths resolve against `base_dir`.
std::shared_ptr<const MaterialGraph> read_material_graph(const nlohmann::json& graph,
                                                         const std::string& field,
                                                         const std::string& base_dir,
                                                         TextureStore& textures);

}  // namespace bxdf::render

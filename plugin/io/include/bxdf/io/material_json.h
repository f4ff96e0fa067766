// JSON material files. A file holds one model and its parameters:
//
//   {"format": "bxdf-material", "version": 1, "name": "red clay",
//    "model": "oren_nayar", "params": {"reflectance": [0.8, 0.3, 0.2], "sigma": 20}}
//
// "params" may leave parameters out (they take their defaults). Instead of "model", a file may
// name a preset ({"preset": "gold", "params": {...overrides}}). The parameter schema comes from
// the model registry; nothing here knows any model by name.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "bxdf/registry.h"

namespace bxdf::io {

constexpr const char* kMaterialFormat = "bxdf-material";
constexpr int kMaterialVersion = 1;

struct MaterialDesc {
  std::string name;   // optional, free text
  std::string model;  // registry name
  ParamSet params;    // validated: every parameter of the model is present
  // A node material instead ({"graph": {...}}, docs/material-graph.md): model and params are then
  // empty; the renderer reads and checks the graph (read_material_graph).
  nlohmann::json graph = nullptr;
};

// Parameters as JSON: numbers, [r, g, b], strings, booleans, lists of objects.
nlohmann::json params_to_json(const ParamSet& params);

// JSON → parameters of `model` (interpreted through its ParamSpecs, then validated).
// `where` prefixes every message (e.g. "scene.json: materials[2]").
ParamSet params_from_json(const std::string& model, const nlohmann::json& j, const std::string& where);

nlohmann::json material_to_json(const MaterialDesc& material);
// Reads a material object (as in a file, or embedded in a scene file). Throws ParameterError
// naming `where`, the field and what was expected.
MaterialDesc material_from_json(const nlohmann::json& j, const std::string& where);

// Files. save writes atomically; load reports the file name and the field on any error.
void save_material(const MaterialDesc& material, const std::string& path);
void save_material(const BxDF& model, const std::string& path, const std::string& name = "");
MaterialDesc load_material_desc(const std::string& path);
// make(m.model, m.params); a failure (e.g. a measured model's missing data file) names `where`.
BxDFPtr make_material(const MaterialDesc& m, const std::string& where);
// Refuses a node material (a graph is not one model) with a message saying so.
BxDFPtr load_material(const std::string& path);

}  // namespace bxdf::io

// The model registry: the single list of models, their parameter declarations and their
// factories. make() is the only way the Python API, JSON files and the renderer build a model.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/params.h"

namespace bxdf {

struct ModelInfo {
  std::string name;
  std::string doc;  // one line
  std::vector<ParamSpec> params;
  // Builds the model from parameters that validate_params() has already checked.
  std::function<std::unique_ptr<BxDF>(const ParamSet& validated)> create;
};

// All registered models, in a stable order.
const std::vector<ModelInfo>& models();
// nullptr when there is no such model.
const ModelInfo* find_model(const std::string& name);

// Validates `params` against the model's declarations, builds it and records its identity.
// Throws ParameterError (unknown model, unknown parameter, wrong kind, out of range, NaN).
BxDFPtr make(const std::string& name, const ParamSet& params = {});

// Each model's source file defines its declaration; builtin_models.cpp lists them.
ModelInfo lambertian_model();
ModelInfo lambertian_transmission_model();
ModelInfo oren_nayar_model();
ModelInfo specular_reflection_model();
ModelInfo specular_transmission_model();
ModelInfo fresnel_specular_model();
ModelInfo microfacet_model();
ModelInfo microfacet_transmission_model();
ModelInfo lafortune_model();
ModelInfo cycles_oren_nayar_model();
ModelInfo cycles_glossy_model();
ModelInfo cycles_glass_model();
ModelInfo cycles_refraction_model();
ModelInfo cycles_translucent_model();
ModelInfo cycles_transparent_model();
ModelInfo cycles_velvet_model();
ModelInfo measured_model();

}  // namespace bxdf

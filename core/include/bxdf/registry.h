// The model registry: the single list of models, their parameter declarations and their
// factories. make() is the only way the Python API, JSON files and the renderer build a model.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/closure_arena.h"
#include "bxdf/params.h"

namespace bxdf {

// A parameter as a plain value, for building a model per hit without a ParamSet: Float in x,
// RGB in (x, y, z), Enum as the index of the choice in x, Bool as 0/1 in x. The caller has
// already brought it into the declared range (see clamp_plain).
struct PlainValue {
  float x = 0.0f, y = 0.0f, z = 0.0f;
};
// Builds the model from one PlainValue per declared parameter (in declaration order) into the
// arena; nullptr when the arena is full. No validation, no allocation.
using PlaceModel = std::function<const BxDF*(const PlainValue* values, ClosureArena& arena)>;

struct ModelInfo {
  std::string name;
  std::string doc;  // one line
  std::vector<ParamSpec> params;
  // Builds the model from parameters that validate_params() has already checked.
  std::function<std::unique_ptr<BxDF>(const ParamSet& validated)> create;
  // Set by models that a material graph may bind per hit (all parameters Float, RGB, Enum or
  // Bool); empty otherwise.
  PlaceModel place;
  size_t place_size = 0;  // upper bound of the arena bytes one place() call uses
};

// Index of a declared parameter (for a model's place function); throws ParameterError.
size_t param_index(const std::vector<ParamSpec>& params, const std::string& name);
// The plain values of a validated parameter set, in declaration order (throws ParameterError
// for a String or List parameter).
std::vector<PlainValue> plain_values(const ModelInfo& model, const ParamSet& validated);
// Brings a per-hit value into the declared range of `spec` (NaN to the lower bound), as Cycles
// clamps its closure inputs; Enum and Bool values pass unchanged.
PlainValue clamp_plain(const ParamSpec& spec, PlainValue v);
inline RGB plain_rgb(const PlainValue& v) { return RGB(v.x, v.y, v.z); }

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
ModelInfo cycles_principled_model();
ModelInfo cycles_glass_model();
ModelInfo cycles_refraction_model();
ModelInfo cycles_translucent_model();
ModelInfo cycles_transparent_model();
ModelInfo cycles_velvet_model();
ModelInfo measured_model();

}  // namespace bxdf

#include "bxdf/registry.h"

namespace bxdf {

namespace {

std::vector<ModelInfo> builtin_models() {
  // One line per model; each declaration lives in the model's own source file.
  return {
      lambertian_model(),
      lambertian_transmission_model(),
      oren_nayar_model(),
      specular_reflection_model(),
      specular_transmission_model(),
      fresnel_specular_model(),
      microfacet_model(),
      microfacet_transmission_model(),
      lafortune_model(),
      cycles_oren_nayar_model(),
      cycles_glossy_model(),
      cycles_glass_model(),
      cycles_refraction_model(),
      cycles_translucent_model(),
      cycles_transparent_model(),
      cycles_velvet_model(),
      measured_model(),
  };
}

}  // namespace

const std::vector<ModelInfo>& models() {
  static const std::vector<ModelInfo> all = builtin_models();
  return all;
}

const ModelInfo* find_model(const std::string& name) {
  for (const auto& m : models())
    if (m.name == name) return &m;
  return nullptr;
}

BxDFPtr make(const std::string& name, const ParamSet& params) {
  const ModelInfo* info = find_model(name);
  if (!info) {
    std::string known;
    for (const auto& m : models()) known += (known.empty() ? "" : ", ") + m.name;
    throw ParameterError("unknown model '" + name + "'; known models: " + known);
  }
  ParamSet validated = validate_params(name, info->params, params);
  std::unique_ptr<BxDF> model = info->create(validated);
  model->set_identity(name, std::move(validated));
  return BxDFPtr(std::move(model));
}

}  // namespace bxdf

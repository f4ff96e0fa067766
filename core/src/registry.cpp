#include "bxdf/registry.h"

#include <cmath>

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
      cycles_principled_model(),
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

namespace bxdf {

size_t param_index(const std::vector<ParamSpec>& params, const std::string& name) {
  for (size_t i = 0; i < params.size(); ++i)
    if (params[i].name == name) return i;
  throw ParameterError("no parameter '" + name + "' is declared");
}

std::vector<PlainValue> plain_values(const ModelInfo& model, const ParamSet& validated) {
  std::vector<PlainValue> out(model.params.size());
  for (size_t i = 0; i < model.params.size(); ++i) {
    const ParamSpec& spec = model.params[i];
    PlainValue& v = out[i];
    switch (spec.kind) {
      case ParamKind::Float:
        v.x = static_cast<float>(validated.number(spec.name));
        break;
      case ParamKind::RGB: {
        const RGBValue c = validated.rgb(spec.name);
        v = {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
        break;
      }
      case ParamKind::Enum: {
        const std::string& s = validated.string(spec.name);
        for (size_t c = 0; c < spec.choices.size(); ++c)
          if (spec.choices[c] == s) v.x = static_cast<float>(c);
        break;
      }
      case ParamKind::Bool:
        v.x = validated.boolean(spec.name) ? 1.0f : 0.0f;
        break;
      default:
        throw ParameterError(model.name + ": parameter '" + spec.name + "' (" +
                             to_string(spec.kind) + ") has no plain value");
    }
  }
  return out;
}

namespace {

float clamp_to_spec(const ParamSpec& spec, float x) {
  float lo = static_cast<float>(spec.min), hi = static_cast<float>(spec.max);
  if (spec.min_exclusive) lo = std::nextafter(lo, hi);
  if (spec.max_exclusive) hi = std::nextafter(hi, lo);
  if (!(x >= lo)) return lo;  // also NaN
  return x > hi ? hi : x;
}

}  // namespace

PlainValue clamp_plain(const ParamSpec& spec, PlainValue v) {
  if (spec.kind == ParamKind::Float) {
    v.x = clamp_to_spec(spec, v.x);
  } else if (spec.kind == ParamKind::RGB) {
    v.x = clamp_to_spec(spec, v.x);
    v.y = clamp_to_spec(spec, v.y);
    v.z = clamp_to_spec(spec, v.z);
  }
  return v;
}

}  // namespace bxdf

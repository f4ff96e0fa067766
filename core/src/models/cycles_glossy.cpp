#include "bxdf/models/cycles_glossy.h"

#include <algorithm>

#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

namespace {

// Cycles 3.4's roughness → (αx, αy) (svm_closure.h and the microfacet setup): r = roughness²,
// anisotropy clamped to ±0.99, a >= 0: (r(1 − a), r/(1 − a)); a < 0: (r/(1 + a), r(1 + a));
// each α then clamped to [0, 1].
void cycles_alphas(float roughness, float anisotropy, float* alpha_x, float* alpha_y) {
  const float r = roughness * roughness;
  const float a = clamp(anisotropy, -0.99f, 0.99f);
  if (a < 0.0f) {
    *alpha_x = r / (1.0f + a);
    *alpha_y = r * (1.0f + a);
  } else {
    *alpha_x = r * (1.0f - a);
    *alpha_y = r / (1.0f - a);
  }
  *alpha_x = clamp(*alpha_x, 0.0f, 1.0f);
  *alpha_y = clamp(*alpha_y, 0.0f, 1.0f);
}

// create and place share this builder: `emit` makes the model in the caller's storage.
template <class Emit>
auto build_cycles_glossy(const RGB& color, bool beckmann, float roughness, float anisotropy,
                         Emit&& emit) {
  float ax = 0.0f, ay = 0.0f;
  cycles_alphas(roughness, anisotropy, &ax, &ay);
  const bool mirror = ax * ay <= kCyclesSingularAlpha2;
  // Above the singular threshold a single α can still be below microfacet::kMinAlpha
  // (strong anisotropy at low roughness); the distribution raises it to 1e-4, which only
  // changes lobes narrower than float directions can resolve.
  if (beckmann)
    return emit(Type<CyclesGlossy<microfacet::Beckmann>>{}, color, microfacet::Beckmann(ax, ay),
                mirror);
  return emit(Type<CyclesGlossy<microfacet::GGX>>{}, color, microfacet::GGX(ax, ay), mirror);
}

}  // namespace

ModelInfo cycles_glossy_model() {
  ModelInfo m;
  m.name = "cycles_glossy";
  m.doc = "Cycles 3.4 Glossy/Anisotropic BSDF: GGX or Beckmann, separable Smith G, no Fresnel";
  m.params = {
      rgb_param("color", {0.8, 0.8, 0.8}, 0.0, 1.0, "Colour: a plain factor (no Fresnel)"),
      enum_param("distribution", "ggx", {"ggx", "beckmann"},
                 "Microfacet distribution (Cycles' GGX or Beckmann)"),
      float_param("roughness", 0.5, 0.0, 1.0, "",
                  "Cycles roughness; alpha = roughness^2 (a mirror when alpha_x*alpha_y <= 1e-7)"),
      float_param("anisotropy", 0.0, -1.0, 1.0, "",
                  "Cycles anisotropy, clamped to [-0.99, 0.99]; > 0 stretches along the bitangent"),
  };
  m.create = [](const ParamSet& p) -> std::unique_ptr<BxDF> {
    return build_cycles_glossy(to_rgb(p.rgb("color")), p.string("distribution") == "beckmann",
                               static_cast<float>(p.number("roughness")),
                               static_cast<float>(p.number("anisotropy")),
                               [](auto type, const auto&... args) -> std::unique_ptr<BxDF> {
                                 return make_from(type, args...);
                               });
  };
  const size_t color = param_index(m.params, "color"),
               distribution = param_index(m.params, "distribution"),
               roughness = param_index(m.params, "roughness"),
               anisotropy = param_index(m.params, "anisotropy");
  const auto& choices = m.params[distribution].choices;
  const float beckmann_choice =
      float(std::find(choices.begin(), choices.end(), "beckmann") - choices.begin());
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return build_cycles_glossy(plain_rgb(v[color]), v[distribution].x == beckmann_choice,
                               v[roughness].x, v[anisotropy].x,
                               [&](auto type, const auto&... args) -> const BxDF* {
                                 return place_from(arena, type, args...);
                               });
  };
  m.place_size = std::max(sizeof(CyclesGlossy<microfacet::GGX>),
                          sizeof(CyclesGlossy<microfacet::Beckmann>));
  return m;
}

}  // namespace bxdf

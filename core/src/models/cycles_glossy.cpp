#include "bxdf/models/cycles_glossy.h"

#include <algorithm>

#include "bxdf/models/cycles_glossy_ashikhmin_shirley.h"
#include "bxdf/models/cycles_multiscatter.h"

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

// The distribution choices, in the order the registry declares them.
enum class GlossyDistribution { GGX, Beckmann, Sharp, AshikhminShirley, MultiGGX };
const char* const kGlossyDistributions[] = {"ggx", "beckmann", "sharp", "ashikhmin_shirley",
                                            "multi_ggx"};

GlossyDistribution glossy_distribution(const std::string& name) {
  for (int i = 0; i < 5; ++i)
    if (name == kGlossyDistributions[i]) return static_cast<GlossyDistribution>(i);
  return GlossyDistribution::GGX;  // unreachable: the registry validated the choice
}

// create and place share this builder: `emit` makes the model in the caller's storage.
template <class Emit>
auto build_cycles_glossy(const RGB& color, GlossyDistribution distribution, float roughness,
                         float anisotropy, Emit&& emit) {
  float ax = 0.0f, ay = 0.0f;
  cycles_alphas(roughness, anisotropy, &ax, &ay);
  const auto sharp = [&] {
    return emit(Type<CyclesGlossy<microfacet::GGX>>{}, color, microfacet::GGX(), true);
  };
  if (distribution == GlossyDistribution::AshikhminShirley) {
    // Cycles clamps this distribution's α to [1e-4, 1] and calls it singular at the floor.
    using AS = CyclesGlossyAshikhminShirley;
    ax = clamp(ax, AS::kMinAlpha, AS::kMaxAlpha);
    ay = clamp(ay, AS::kMinAlpha, AS::kMaxAlpha);
    if (std::max(ax, ay) > AS::kMinAlpha) return emit(Type<AS>{}, color, ax, ay);
    return sharp();
  }
  if (distribution == GlossyDistribution::MultiGGX) {
    // Blender compiles roughness <= 1e-4 as Sharp; above, Cycles' setup clamps α to
    // [1e-4, 1] and the walk has no singular case.
    if (roughness <= 1e-4f) return sharp();
    microfacet::MultiscatterSetup setup;
    setup.alpha_x = clamp(ax, 1e-4f, 1.0f);
    setup.alpha_y = clamp(ay, 1e-4f, 1.0f);
    return emit(Type<CyclesMultiscatterGlossy>{}, uint32_t(kReflection | kGlossy), color, setup);
  }
  const bool mirror = distribution == GlossyDistribution::Sharp || ax * ay <= kCyclesSingularAlpha2;
  // Above the singular threshold a single α can still be below microfacet::kMinAlpha
  // (strong anisotropy at low roughness); the distribution raises it to 1e-4, which only
  // changes lobes narrower than float directions can resolve.
  if (distribution == GlossyDistribution::Beckmann)
    return emit(Type<CyclesGlossy<microfacet::Beckmann>>{}, color, microfacet::Beckmann(ax, ay),
                mirror);
  return emit(Type<CyclesGlossy<microfacet::GGX>>{}, color, microfacet::GGX(ax, ay), mirror);
}

}  // namespace

ModelInfo cycles_glossy_model() {
  ModelInfo m;
  m.name = "cycles_glossy";
  m.doc =
      "Cycles 3.4 Glossy/Anisotropic BSDF: GGX, Beckmann, Ashikhmin-Shirley, multiscatter GGX or "
      "sharp, no Fresnel";
  m.params = {
      rgb_param("color", {0.8, 0.8, 0.8}, 0.0, 1.0, "Colour: a plain factor (no Fresnel)"),
      enum_param("distribution", "ggx",
                 {"ggx", "beckmann", "sharp", "ashikhmin_shirley", "multi_ggx"},
                 "Cycles' distribution: GGX, Beckmann, Ashikhmin-Shirley, multiscatter GGX, or "
                 "sharp (a mirror)"),
      float_param("roughness", 0.5, 0.0, 1.0, "",
                  "Cycles roughness; alpha = roughness^2 (a mirror when alpha_x*alpha_y <= 1e-7)"),
      float_param("anisotropy", 0.0, -1.0, 1.0, "",
                  "Cycles anisotropy, clamped to [-0.99, 0.99]; > 0 stretches along the bitangent"),
  };
  m.create = [](const ParamSet& p) -> std::unique_ptr<BxDF> {
    return build_cycles_glossy(to_rgb(p.rgb("color")), glossy_distribution(p.string("distribution")),
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
  // An enum's plain value is the index of its choice in the declaration; the names are
  // matched once here, not at every hit.
  std::vector<GlossyDistribution> by_choice;
  for (const std::string& choice : m.params[distribution].choices)
    by_choice.push_back(glossy_distribution(choice));
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return build_cycles_glossy(plain_rgb(v[color]),
                               by_choice[static_cast<size_t>(v[distribution].x)],
                               v[roughness].x, v[anisotropy].x,
                               [&](auto type, const auto&... args) -> const BxDF* {
                                 return place_from(arena, type, args...);
                               });
  };
  m.place_size = std::max({sizeof(CyclesGlossy<microfacet::GGX>),
                           sizeof(CyclesGlossy<microfacet::Beckmann>),
                           sizeof(CyclesGlossyAshikhminShirley), sizeof(CyclesMultiscatterGlossy)});
  return m;
}

}  // namespace bxdf

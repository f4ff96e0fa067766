#include "bxdf/models/cycles_glass.h"

#include <algorithm>

#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/model_support.h"
#include "bxdf/models/cycles_multiscatter.h"
#include "bxdf/registry.h"

namespace bxdf {

CyclesDielectricInputs cycles_dielectric_inputs(const std::string& distribution, float roughness,
                                                float ior) {
  CyclesDielectricInputs in;
  in.alpha = roughness * roughness;
  in.ior = std::max(ior, 1e-5f);
  // Blender compiles roughness <= 1e-4 as the Sharp closures; the microfacet closures are
  // singular at αx·αy <= 1e-7 and (refraction) when the index is within 1e-4 of 1, on either
  // face (the back face sees 1/ior).
  const bool index_one = std::fabs(in.ior - 1.0f) < 1e-4f || std::fabs(1.0f / in.ior - 1.0f) < 1e-4f;
  const bool single_scatter_singular =
      in.alpha * in.alpha <= cycles::kSingularAlpha2 || index_one;
  in.sharp = distribution == "sharp" || roughness <= 1e-4f ||
             (distribution != "multi_ggx" && single_scatter_singular);
  return in;
}

namespace {

// create and place share this builder: `emit` makes the model in the caller's storage.
template <class Emit>
auto build_cycles_dielectric(CyclesDielectricNode node, const RGB& color,
                             const std::string& distribution, float roughness, float ior,
                             Emit&& emit) {
  const CyclesDielectricInputs in = cycles_dielectric_inputs(distribution, roughness, ior);
  if (in.sharp) return emit(Type<CyclesSharpDielectric>{}, node, color, in.ior);
  if (distribution == "multi_ggx") {
    microfacet::MultiscatterSetup setup;
    setup.alpha_x = setup.alpha_y = in.alpha;
    setup.eta = in.ior;
    if (node == CyclesDielectricNode::kRefraction)
      return emit(Type<CyclesMultiscatterRefraction>{}, uint32_t(kTransmission | kGlossy), color,
                  setup);
    return emit(Type<CyclesMultiscatterGlass>{}, uint32_t(kReflection | kTransmission | kGlossy),
                color, setup);
  }
  if (distribution == "beckmann")
    return emit(Type<CyclesRoughDielectric<microfacet::Beckmann>>{}, node, color,
                microfacet::Beckmann(in.alpha, in.alpha), in.ior);
  return emit(Type<CyclesRoughDielectric<microfacet::GGX>>{}, node, color,
              microfacet::GGX(in.alpha, in.alpha), in.ior);
}

}  // namespace

std::unique_ptr<BxDF> make_cycles_dielectric(CyclesDielectricNode node, const ParamSet& p) {
  return build_cycles_dielectric(node, to_rgb(p.rgb("color")), p.string("distribution"),
                                 static_cast<float>(p.number("roughness")),
                                 static_cast<float>(p.number("ior")),
                                 [](auto type, const auto&... args) -> std::unique_ptr<BxDF> {
                                   return make_from(type, args...);
                                 });
}

void set_cycles_dielectric_place(ModelInfo& m, CyclesDielectricNode node) {
  const size_t color = param_index(m.params, "color"),
               distribution = param_index(m.params, "distribution"),
               roughness = param_index(m.params, "roughness"), ior = param_index(m.params, "ior");
  const auto& choices = m.params[distribution].choices;
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    // An enum's plain value is the index of its choice in the declaration.
    const std::string& choice = choices[static_cast<size_t>(v[distribution].x)];
    return build_cycles_dielectric(node, plain_rgb(v[color]), choice, v[roughness].x, v[ior].x,
                                   [&](auto type, const auto&... args) -> const BxDF* {
                                     return place_from(arena, type, args...);
                                   });
  };
  // Every class the builder can emit (an upper bound for either node).
  m.place_size = std::max({sizeof(CyclesSharpDielectric), sizeof(CyclesMultiscatterGlass),
                           sizeof(CyclesMultiscatterRefraction),
                           sizeof(CyclesRoughDielectric<microfacet::Beckmann>),
                           sizeof(CyclesRoughDielectric<microfacet::GGX>)});
}

std::vector<ParamSpec> cycles_dielectric_surface_params() {
  return {
      float_param("roughness", 0.0, 0.0, 1.0, "",
                  "Cycles roughness; alpha = roughness^2 (sharp at roughness <= 1e-4)"),
      float_param("ior", 1.45, 0.0, 1000.0, "",
                  "Index of refraction below the surface over above (Cycles uses max(ior, 1e-5))"),
  };
}

ModelInfo cycles_glass_model() {
  ModelInfo m;
  m.name = "cycles_glass";
  m.doc = "Cycles 3.4 Glass BSDF: reflection weighted by F(N.V), refraction by max(1e-4, 1 - F)";
  m.params = {
      rgb_param("color", {1.0, 1.0, 1.0}, 0.0, 1.0, "Colour: a factor on both lobes"),
      enum_param("distribution", "beckmann", {"sharp", "beckmann", "ggx", "multi_ggx"},
                 "Cycles' distribution: sharp (delta), Beckmann, GGX or multiscatter GGX"),
  };
  for (ParamSpec& spec : cycles_dielectric_surface_params()) m.params.push_back(std::move(spec));
  m.create = [](const ParamSet& p) {
    return make_cycles_dielectric(CyclesDielectricNode::kGlass, p);
  };
  set_cycles_dielectric_place(m, CyclesDielectricNode::kGlass);
  return m;
}

}  // namespace bxdf

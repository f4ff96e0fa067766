#include "bxdf/models/cycles_glossy.h"

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
    float ax = 0.0f, ay = 0.0f;
    cycles_alphas(static_cast<float>(p.number("roughness")),
                  static_cast<float>(p.number("anisotropy")), &ax, &ay);
    const std::string& distribution = p.string("distribution");
    const RGB color = to_rgb(p.rgb("color"));
    if (distribution == "ashikhmin_shirley") {
      // Cycles clamps this distribution's α to [1e-4, 1] and calls it singular at the floor.
      using AS = CyclesGlossyAshikhminShirley;
      ax = clamp(ax, AS::kMinAlpha, AS::kMaxAlpha);
      ay = clamp(ay, AS::kMinAlpha, AS::kMaxAlpha);
      if (std::max(ax, ay) > AS::kMinAlpha) return std::make_unique<AS>(color, ax, ay);
      return std::make_unique<CyclesGlossy<microfacet::GGX>>(color, microfacet::GGX(), true);
    }
    if (distribution == "multi_ggx") {
      // Blender compiles roughness <= 1e-4 as Sharp; above, Cycles' setup clamps α to
      // [1e-4, 1] and the walk has no singular case.
      if (p.number("roughness") <= 1e-4)
        return std::make_unique<CyclesGlossy<microfacet::GGX>>(color, microfacet::GGX(), true);
      microfacet::MultiscatterSetup setup;
      setup.alpha_x = clamp(ax, 1e-4f, 1.0f);
      setup.alpha_y = clamp(ay, 1e-4f, 1.0f);
      return std::make_unique<CyclesMultiscatterGlossy>(kReflection | kGlossy, color, setup);
    }
    const bool mirror = distribution == "sharp" || ax * ay <= kCyclesSingularAlpha2;
    // Above the singular threshold a single α can still be below microfacet::kMinAlpha
    // (strong anisotropy at low roughness); the distribution raises it to 1e-4, which only
    // changes lobes narrower than float directions can resolve.
    if (distribution == "beckmann")
      return std::make_unique<CyclesGlossy<microfacet::Beckmann>>(
          color, microfacet::Beckmann(ax, ay), mirror);
    return std::make_unique<CyclesGlossy<microfacet::GGX>>(color, microfacet::GGX(ax, ay), mirror);
  };
  return m;
}

}  // namespace bxdf

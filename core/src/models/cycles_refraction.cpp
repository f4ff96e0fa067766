#include "bxdf/model_support.h"
#include "bxdf/models/cycles_glass.h"
#include "bxdf/registry.h"

namespace bxdf {

// The Refraction node is the Glass node's refraction closure alone (cycles_glass.h). Blender
// 3.4's Refraction node offers no multiscatter GGX and Cycles has no such closure: multi_ggx
// here is Cycles' multiscatter glass walk restricted to transmission (MultiscatterGGX-
// Refraction in microfacet/multiscatter_ggx.h), Fresnel included, unlike the other
// distributions; Blender's closest node is the Refraction node with GGX (approximate).
ModelInfo cycles_refraction_model() {
  ModelInfo m;
  m.name = "cycles_refraction";
  m.doc = "Cycles 3.4 Refraction BSDF: the glass refraction lobe alone, weight 1, no Fresnel";
  m.params = {
      rgb_param("color", {1.0, 1.0, 1.0}, 0.0, 1.0, "Colour: a factor on the lobe"),
      enum_param("distribution", "beckmann", {"sharp", "beckmann", "ggx", "multi_ggx"},
                 "Cycles' distribution: sharp (delta), Beckmann, GGX, or multiscatter GGX "
                 "(the glass walk's transmitted part, Fresnel included; no Cycles node)"),
      float_param("roughness", 0.0, 0.0, 1.0, "",
                  "Cycles roughness; alpha = roughness^2 (sharp at roughness <= 1e-4)"),
      float_param("ior", 1.45, 0.0, 1000.0, "",
                  "Index of refraction below the surface over above (Cycles uses max(ior, 1e-5))"),
  };
  m.create = [](const ParamSet& p) {
    return make_cycles_dielectric(CyclesDielectricNode::kRefraction, p);
  };
  set_cycles_dielectric_place(m, CyclesDielectricNode::kRefraction);
  return m;
}

}  // namespace bxdf

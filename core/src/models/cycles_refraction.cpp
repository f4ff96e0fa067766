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
  };
  for (ParamSpec& spec : cycles_dielectric_surface_params()) m.params.push_back(std::move(spec));
  m.create = [](const ParamSet& p) {
    return make_cycles_dielectric(CyclesDielectricNode::kRefraction, p);
  };
  set_cycles_dielectric_place(m, CyclesDielectricNode::kRefraction);
  return m;
}

}  // namespace bxdf

#include "bxdf/models/cycles_velvet.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo cycles_velvet_model() {
  ModelInfo m;
  m.name = "cycles_velvet";
  m.doc = "Cycles 3.4 Velvet BSDF: Ashikhmin's velvet lobe, uniform-hemisphere sampling";
  m.params = {
      rgb_param("color", {0.8, 0.8, 0.8}, 0.0, 1.0, "Colour: a plain factor"),
      float_param("sigma", 1.0, 0.0, 1.0, "",
                  "Width of the sheen; Cycles uses max(sigma, 0.01)"),
  };
  m.create = [](const ParamSet& p) {
    return std::make_unique<CyclesVelvet>(to_rgb(p.rgb("color")),
                                          static_cast<float>(p.number("sigma")));
  };
  const size_t color = param_index(m.params, "color"), sigma = param_index(m.params, "sigma");
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return arena.make<CyclesVelvet>(plain_rgb(v[color]), v[sigma].x);
  };
  m.place_size = sizeof(CyclesVelvet);
  return m;
}

}  // namespace bxdf

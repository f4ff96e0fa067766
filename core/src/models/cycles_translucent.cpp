#include "bxdf/models/cycles_translucent.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo cycles_translucent_model() {
  ModelInfo m;
  m.name = "cycles_translucent";
  m.doc = "Cycles 3.4 Translucent BSDF: colour/pi into the hemisphere opposite the viewer";
  m.params = {rgb_param("color", {0.8, 0.8, 0.8}, 0.0, 1.0,
                        "Colour: the fraction of light passed diffusely to the other side")};
  m.create = [](const ParamSet& p) {
    return std::make_unique<CyclesTranslucent>(to_rgb(p.rgb("color")));
  };
  const size_t color = param_index(m.params, "color");
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return arena.make<CyclesTranslucent>(plain_rgb(v[color]));
  };
  m.place_size = sizeof(CyclesTranslucent);
  return m;
}

}  // namespace bxdf

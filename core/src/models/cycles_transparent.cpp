#include "bxdf/models/cycles_transparent.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo cycles_transparent_model() {
  ModelInfo m;
  m.name = "cycles_transparent";
  m.doc = "Cycles 3.4 Transparent BSDF: a straight pass-through weighted by the colour (delta)";
  m.params = {rgb_param("color", {1.0, 1.0, 1.0}, 0.0, 1.0,
                        "Colour: the fraction of light that passes straight through")};
  m.create = [](const ParamSet& p) {
    return std::make_unique<CyclesTransparent>(to_rgb(p.rgb("color")));
  };
  const size_t color = param_index(m.params, "color");
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return arena.make<CyclesTransparent>(plain_rgb(v[color]));
  };
  m.place_size = sizeof(CyclesTransparent);
  return m;
}

}  // namespace bxdf

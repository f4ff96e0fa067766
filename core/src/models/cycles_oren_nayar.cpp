#include "bxdf/models/cycles_oren_nayar.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo cycles_oren_nayar_model() {
  ModelInfo m;
  m.name = "cycles_oren_nayar";
  m.doc = "Cycles 3.4 Diffuse BSDF with roughness (Fujii's improved Oren-Nayar), to match Cycles";
  m.params = {
      rgb_param("color", {0.8, 0.8, 0.8}, 0.0, 1.0, "Diffuse BSDF Color"),
      float_param("roughness", 0.5, 0.0, 1.0, "",
                  "Diffuse BSDF Roughness, used directly as sigma; 0 is Lambertian"),
  };
  m.create = [](const ParamSet& p) {
    return std::make_unique<CyclesOrenNayar>(to_rgb(p.rgb("color")),
                                             static_cast<float>(p.number("roughness")));
  };
  const size_t color = param_index(m.params, "color"),
               roughness = param_index(m.params, "roughness");
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return arena.make<CyclesOrenNayar>(plain_rgb(v[color]), v[roughness].x);
  };
  m.place_size = sizeof(CyclesOrenNayar);
  return m;
}

}  // namespace bxdf

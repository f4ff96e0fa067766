#include "bxdf/models/lambertian.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo lambertian_model() {
  ModelInfo m;
  m.name = "lambertian";
  m.doc = "Ideal diffuse reflection, f = R/pi";
  m.params = {rgb_param("reflectance", {0.8, 0.8, 0.8}, 0.0, 1.0, "Diffuse reflectance R (albedo)")};
  m.create = [](const ParamSet& p) {
    return std::make_unique<Lambertian>(to_rgb(p.rgb("reflectance")));
  };
  const size_t reflectance = param_index(m.params, "reflectance");
  m.place = [=](const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return arena.make<Lambertian>(plain_rgb(v[reflectance]));
  };
  m.place_size = sizeof(Lambertian);
  return m;
}

}  // namespace bxdf

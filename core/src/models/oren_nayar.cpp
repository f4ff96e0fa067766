#include "bxdf/models/oren_nayar.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo oren_nayar_model() {
  ModelInfo m;
  m.name = "oren_nayar";
  m.doc = "Oren-Nayar rough diffuse reflection (the seed's / pbrt's qualitative model)";
  m.params = {
      rgb_param("reflectance", {0.8, 0.8, 0.8}, 0.0, 1.0, "Diffuse reflectance R"),
      float_param("sigma", 20.0, 0.0, 90.0, "degrees",
                  "Standard deviation of the microfacet slope angle; 0 is Lambertian"),
  };
  m.create = [](const ParamSet& p) {
    return std::make_unique<OrenNayar>(to_rgb(p.rgb("reflectance")),
                                       static_cast<float>(p.number("sigma")));
  };
  return m;
}

}  // namespace bxdf

#include "bxdf/models/lambertian_transmission.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo lambertian_transmission_model() {
  ModelInfo m;
  m.name = "lambertian_transmission";
  m.doc = "Ideal diffuse transmission, f = T/pi into the opposite hemisphere";
  m.params = {rgb_param("transmittance", {0.8, 0.8, 0.8}, 0.0, 1.0,
                        "Diffuse transmittance T: the fraction of light passed to the other side")};
  m.create = [](const ParamSet& p) {
    return std::make_unique<LambertianTransmission>(to_rgb(p.rgb("transmittance")));
  };
  return m;
}

}  // namespace bxdf

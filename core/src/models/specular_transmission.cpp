#include "bxdf/models/specular_transmission.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo specular_transmission_model() {
  ModelInfo m;
  m.name = "specular_transmission";
  m.doc = "Perfect refraction through a smooth dielectric, weighted by T (1 - F) (delta lobe)";
  m.params = {
      rgb_param("transmittance", {1.0, 1.0, 1.0}, 0.0, 1.0, "Transmittance T, a factor on 1 - F"),
      positive_param("eta_i", 1.0, 10.0, "", "Index of refraction outside (above the surface)"),
      positive_param("eta_t", 1.5, 10.0, "", "Index of refraction inside (below the surface)"),
  };
  m.create = [](const ParamSet& p) {
    return std::make_unique<SpecularTransmission>(to_rgb(p.rgb("transmittance")),
                                                  static_cast<float>(p.number("eta_i")),
                                                  static_cast<float>(p.number("eta_t")));
  };
  return m;
}

}  // namespace bxdf

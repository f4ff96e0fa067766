#include "bxdf/models/fresnel_specular.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo fresnel_specular_model() {
  ModelInfo m;
  m.name = "fresnel_specular";
  m.doc =
      "Smooth glass: reflects with probability F, refracts with probability 1 - F (delta lobes)";
  m.params = {
      rgb_param("reflectance", {1.0, 1.0, 1.0}, 0.0, 1.0, "Reflectance R, a factor on F"),
      rgb_param("transmittance", {1.0, 1.0, 1.0}, 0.0, 1.0, "Transmittance T, a factor on 1 - F"),
      positive_param("eta_i", 1.0, 10.0, "", "Index of refraction outside (above the surface)"),
      positive_param("eta_t", 1.5, 10.0, "", "Index of refraction inside (below the surface)"),
  };
  m.create = [](const ParamSet& p) {
    return std::make_unique<FresnelSpecular>(
        to_rgb(p.rgb("reflectance")), to_rgb(p.rgb("transmittance")),
        static_cast<float>(p.number("eta_i")), static_cast<float>(p.number("eta_t")));
  };
  return m;
}

}  // namespace bxdf

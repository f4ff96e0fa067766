#include "bxdf/models/specular_reflection.h"

#include "bxdf/fresnel_params.h"
#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo specular_reflection_model() {
  ModelInfo m;
  m.name = "specular_reflection";
  m.doc = "Perfect mirror reflection weighted by R and a Fresnel term (delta lobe)";
  m.params = {
      rgb_param("reflectance", {1.0, 1.0, 1.0}, 0.0, 1.0, "Reflectance R, a factor on Fresnel"),
  };
  for (ParamSpec& s : fresnel_params("dielectric")) m.params.push_back(std::move(s));
  m.create = [](const ParamSet& p) {
    return std::make_unique<SpecularReflection>(to_rgb(p.rgb("reflectance")),
                                                fresnel_from_params(p));
  };
  return m;
}

}  // namespace bxdf

#include "bxdf/models/specular_reflection.h"

#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

namespace {

ParamSpec positive_rgb_param(std::string name, RGBValue def, double max, std::string doc) {
  ParamSpec s = rgb_param(std::move(name), def, 0.0, max, std::move(doc));
  s.min_exclusive = true;
  return s;
}

}  // namespace

ModelInfo specular_reflection_model() {
  ModelInfo m;
  m.name = "specular_reflection";
  m.doc = "Perfect mirror reflection weighted by R and a Fresnel term (delta lobe)";
  m.params = {
      rgb_param("reflectance", {1.0, 1.0, 1.0}, 0.0, 1.0, "Reflectance R, a factor on Fresnel"),
      enum_param("fresnel", "dielectric", {"none", "dielectric", "conductor"},
                 "Fresnel term: none (F = 1), dielectric (eta_i, eta_t) or conductor (eta, k)"),
      only_when(
          positive_param("eta_i", 1.0, 10.0, "", "Index of refraction outside (incident side)"),
          "fresnel", {"dielectric"}),
      only_when(positive_param("eta_t", 1.5, 10.0, "", "Index of refraction of the dielectric"),
                "fresnel", {"dielectric"}),
      // Defaults: the seed's gold (eta 0.370, k 2.820) as a grey.
      only_when(positive_rgb_param("eta", {0.370, 0.370, 0.370}, 10.0,
                                   "Conductor index of refraction eta per channel"),
                "fresnel", {"conductor"}),
      only_when(rgb_param("k", {2.820, 2.820, 2.820}, 0.0, 20.0,
                          "Conductor absorption coefficient k per channel"),
                "fresnel", {"conductor"}),
  };
  m.create = [](const ParamSet& p) {
    const std::string& kind = p.string("fresnel");
    Fresnel fresnel = Fresnel::none();
    if (kind == "dielectric")
      fresnel = Fresnel::dielectric(static_cast<float>(p.number("eta_i")),
                                    static_cast<float>(p.number("eta_t")));
    else if (kind == "conductor")
      fresnel = Fresnel::conductor(to_rgb(p.rgb("eta")), to_rgb(p.rgb("k")));
    return std::make_unique<SpecularReflection>(to_rgb(p.rgb("reflectance")), fresnel);
  };
  return m;
}

}  // namespace bxdf

#include "bxdf/fresnel_params.h"

#include "bxdf/model_support.h"

namespace bxdf {

std::vector<ParamSpec> fresnel_params(const std::string& default_kind) {
  ParamSpec eta = per_channel(rgb_param("eta", {0.370, 0.370, 0.370}, 0.0, 10.0,
                            "Conductor index of refraction eta per channel (default: the seed's gold)"));
  eta.min_exclusive = true;  // η = 0 would make the conductor a perfect mirror at every angle
  return {
      enum_param("fresnel", default_kind, {"none", "dielectric", "conductor"},
                 "Fresnel term F: none (F = 1), dielectric (eta_i, eta_t) or conductor (eta, k)"),
      only_when(positive_param("eta_i", 1.0, 10.0, "", "Index of refraction outside (incident side)"),
                "fresnel", {"dielectric"}),
      only_when(positive_param("eta_t", 1.5, 10.0, "", "Index of refraction of the dielectric"),
                "fresnel", {"dielectric"}),
      only_when(eta, "fresnel", {"conductor"}),
      only_when(per_channel(rgb_param("k", {2.820, 2.820, 2.820}, 0.0, 20.0,
                          "Conductor absorption coefficient k per channel (default: the seed's gold)")),
                "fresnel", {"conductor"}),
  };
}

Fresnel fresnel_from_params(const ParamSet& p) {
  const std::string& kind = p.string("fresnel");
  if (kind == "dielectric")
    return Fresnel::dielectric(static_cast<float>(p.number("eta_i")),
                               static_cast<float>(p.number("eta_t")));
  if (kind == "conductor") return Fresnel::conductor(to_rgb(p.rgb("eta")), to_rgb(p.rgb("k")));
  return Fresnel::none();
}

}  // namespace bxdf

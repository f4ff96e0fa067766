#include "bxdf/models/microfacet_transmission.h"

#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

ModelInfo microfacet_transmission_model() {
  ModelInfo m;
  m.name = "microfacet_transmission";
  m.doc = "Rough dielectric transmission (Walter 2007), the refracted part of rough glass";
  m.params = {
      rgb_param("transmittance", {1.0, 1.0, 1.0}, 0.0, 1.0, "Transmittance T that scales the lobe"),
      enum_param("distribution", "ggx", {"beckmann", "ggx"}, "Microfacet normal distribution D"),
      positive_param("alpha_x", 0.3, 10.0, "",
                     "Roughness alpha along the tangent x (values below 1e-4 act as 1e-4)"),
      positive_param("alpha_y", 0.3, 10.0, "",
                     "Roughness alpha along the bitangent y (values below 1e-4 act as 1e-4)"),
      positive_param("eta_i", 1.0, 10.0, "", "Index of refraction above the surface (z > 0)"),
      positive_param("eta_t", 1.5, 10.0, "", "Index of refraction below the surface (z < 0)"),
  };
  m.create = [](const ParamSet& p) -> std::unique_ptr<BxDF> {
    const float eta_i = static_cast<float>(p.number("eta_i"));
    const float eta_t = static_cast<float>(p.number("eta_t"));
    // Equal indices make the interface invisible: all light goes straight through, a delta
    // this glossy lobe cannot represent (f would be 0 everywhere).
    if (eta_i == eta_t)
      throw ParameterError(
          "microfacet_transmission: parameter 'eta_t' = " + Value(p.number("eta_t")).to_string() +
          " equals 'eta_i' = " + Value(p.number("eta_i")).to_string() +
          "; valid: (0, 10] and different from eta_i");
    const RGB t = to_rgb(p.rgb("transmittance"));
    const float ax = static_cast<float>(p.number("alpha_x"));
    const float ay = static_cast<float>(p.number("alpha_y"));
    if (p.string("distribution") == "beckmann")
      return std::make_unique<MicrofacetTransmission<microfacet::Beckmann>>(
          t, microfacet::Beckmann(ax, ay), eta_i, eta_t);
    return std::make_unique<MicrofacetTransmission<microfacet::GGX>>(t, microfacet::GGX(ax, ay),
                                                                     eta_i, eta_t);
  };
  return m;
}

}  // namespace bxdf

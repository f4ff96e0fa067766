#include "bxdf/models/microfacet.h"

#include "bxdf/microfacet/ashikhmin_shirley.h"
#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/blinn.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/fresnel_params.h"
#include "bxdf/model_support.h"
#include "bxdf/registry.h"

namespace bxdf {

namespace {

template <class Distribution>
std::unique_ptr<BxDF> make_torrance_sparrow(const ParamSet& p, const Distribution& d) {
  const MicrofacetShadowing g =
      p.string("shadowing") == "smith" ? MicrofacetShadowing::Smith : MicrofacetShadowing::VGroove;
  return std::make_unique<TorranceSparrow<Distribution>>(to_rgb(p.rgb("reflectance")), d, g,
                                                         fresnel_from_params(p),
                                                         to_rgb(p.rgb("diffuse")));
}

float number(const ParamSet& p, const char* name) { return static_cast<float>(p.number(name)); }

}  // namespace

ModelInfo microfacet_model() {
  ModelInfo m;
  m.name = "microfacet";
  m.doc = "Torrance-Sparrow microfacet reflection over an optional Lambertian term, "
          "f = diffuse/pi + R D G F / (4 cos_i cos_o)";
  const std::vector<std::string> alpha_kinds = {"beckmann", "ggx"};
  m.params = {
      rgb_param("reflectance", {0.8, 0.8, 0.8}, 0.0, 1.0, "Reflectance R that scales the lobe"),
      rgb_param("diffuse", {0.0, 0.0, 0.0}, 0.0, 1.0,
                "Reflectance of a Lambertian term diffuse/pi added under the lobe (pbrt's plastic, "
                "Ngan et al.'s fits); black: none"),
      enum_param("distribution", "ggx", {"blinn", "ashikhmin_shirley", "beckmann", "ggx"},
                 "Microfacet normal distribution D"),
      only_when(float_param("exponent", 20.0, 0.0, 1e6, "", "Blinn exponent e: larger is smoother"),
                "distribution", {"blinn"}),
      only_when(float_param("exponent_x", 10.0, 0.0, 1e6, "",
                            "Ashikhmin-Shirley exponent along the tangent x"),
                "distribution", {"ashikhmin_shirley"}),
      only_when(float_param("exponent_y", 100.0, 0.0, 1e6, "",
                            "Ashikhmin-Shirley exponent along the bitangent y"),
                "distribution", {"ashikhmin_shirley"}),
      only_when(
          positive_param("alpha_x", 0.3, 10.0, "",
                         "Roughness alpha along the tangent x (values below 1e-4 act as 1e-4)"),
          "distribution", alpha_kinds),
      only_when(
          positive_param("alpha_y", 0.3, 10.0, "",
                         "Roughness alpha along the bitangent y (values below 1e-4 act as 1e-4)"),
          "distribution", alpha_kinds),
      enum_param("shadowing", "smith", {"v_groove", "smith"},
                 "Shadowing-masking G: the seed's V-groove, or height-correlated Smith"),
  };
  for (ParamSpec& s : fresnel_params("none")) m.params.push_back(std::move(s));
  m.create = [](const ParamSet& p) -> std::unique_ptr<BxDF> {
    const std::string& d = p.string("distribution");
    if (d == "blinn") return make_torrance_sparrow(p, microfacet::Blinn(number(p, "exponent")));
    if (d == "ashikhmin_shirley")
      return make_torrance_sparrow(
          p, microfacet::AshikhminShirley(number(p, "exponent_x"), number(p, "exponent_y")));
    // alpha below kMinAlpha is raised to it by the distributions (see microfacet/common.h).
    if (d == "beckmann")
      return make_torrance_sparrow(
          p, microfacet::Beckmann(number(p, "alpha_x"), number(p, "alpha_y")));
    return make_torrance_sparrow(p, microfacet::GGX(number(p, "alpha_x"), number(p, "alpha_y")));
  };
  return m;
}

}  // namespace bxdf

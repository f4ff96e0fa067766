#include "model_grid.h"

#include <cmath>
#include <map>
#include <utility>

#include "bxdf/registry.h"

namespace bxdf::test {

namespace {

ParamSet params(std::initializer_list<std::pair<const char*, Value>> items) {
  ParamSet p;
  for (const auto& [name, value] : items) p.set(name, value);
  return p;
}

GridEntry entry(std::string label, ParamSet p, double recorded_max_albedo = 0.0) {
  return {std::move(label), std::move(p), recorded_max_albedo, {}, false, {}};
}

// One Lafortune lobe with the same coefficients in every channel.
ParamSet lobe(double cx, double cy, double cz, double exponent) {
  return params({{"cx", cx}, {"cy", cy}, {"cz", cz}, {"exponent", exponent}});
}

// The seed's grey conductor constants (η, k) for gold.
const RGBValue kGoldEta{0.370, 0.370, 0.370}, kGoldK{2.820, 2.820, 2.820};
// pbrt's RGB fit for copper, so that the conductor path sees different channels.
const RGBValue kCopperEta{0.200, 0.924, 1.102}, kCopperK{3.912, 2.452, 2.142};

// Lobe widths are chosen so that a 50 × 101 (φ, cosθ) histogram of 10⁶ samples still resolves
// them (GGX α ≥ 0.1, Blinn exponent ≤ 200), while the narrowest ones are sharp enough to put
// most of their mass into a few dozen cells.
std::map<std::string, std::vector<GridEntry>> build_grid() {
  std::map<std::string, std::vector<GridEntry>> g;

  g["lambertian"] = {
      entry("grey", params({{"reflectance", 0.8}})),
      entry("tinted", params({{"reflectance", RGBValue{0.9, 0.5, 0.1}}})),
      entry("white", params({{"reflectance", 1.0}})),
  };
  g["lambertian_transmission"] = {
      entry("grey", params({{"transmittance", 0.8}})),
      entry("tinted_white", params({{"transmittance", RGBValue{1.0, 0.6, 0.2}}})),
  };
  g["oren_nayar"] = {
      entry("sigma0_is_lambert", params({{"reflectance", 0.8}, {"sigma", 0.0}})),
      entry("sigma20", params({{"reflectance", RGBValue{0.9, 0.6, 0.3}}, {"sigma", 20.0}})),
      entry("sigma60_white", params({{"reflectance", 1.0}, {"sigma", 60.0}})),
      entry("sigma90_white", params({{"reflectance", 1.0}, {"sigma", 90.0}})),
  };
  g["specular_reflection"] = {
      entry("none", params({{"reflectance", 1.0}, {"fresnel", "none"}})),
      entry("dielectric_glass",
            params({{"fresnel", "dielectric"}, {"eta_i", 1.0}, {"eta_t", 1.5}})),
      entry("dielectric_from_inside",
            params({{"fresnel", "dielectric"}, {"eta_i", 1.5}, {"eta_t", 1.0}})),
      entry("conductor_gold",
            params({{"reflectance", 1.0}, {"fresnel", "conductor"}, {"eta", kGoldEta},
                    {"k", kGoldK}})),
  };
  g["specular_transmission"] = {
      entry("air_to_glass", params({{"transmittance", 1.0}, {"eta_i", 1.0}, {"eta_t", 1.5}})),
      entry("glass_to_air_tinted",
            params({{"transmittance", RGBValue{0.9, 0.7, 0.5}}, {"eta_i", 1.5}, {"eta_t", 1.0}})),
  };
  g["fresnel_specular"] = {
      entry("glass", params({{"eta_i", 1.0}, {"eta_t", 1.5}})),
      entry("diamond_tinted", params({{"reflectance", RGBValue{1.0, 0.9, 0.8}},
                                      {"transmittance", RGBValue{0.7, 0.8, 1.0}},
                                      {"eta_i", 1.0}, {"eta_t", 2.42}})),
      entry("water_from_inside", params({{"eta_i", 1.333}, {"eta_t", 1.0}})),
  };
  g["microfacet"] = {
      entry("blinn_e20_vgroove", params({{"distribution", "blinn"}, {"exponent", 20.0},
                                         {"shadowing", "v_groove"}, {"fresnel", "none"},
                                         {"reflectance", 1.0}})),
      entry("blinn_e200_vgroove_dielectric",
            params({{"distribution", "blinn"}, {"exponent", 200.0}, {"shadowing", "v_groove"},
                    {"fresnel", "dielectric"}, {"eta_i", 1.0}, {"eta_t", 1.5}})),
      entry("ashikhmin_shirley_aniso_conductor",
            params({{"distribution", "ashikhmin_shirley"}, {"exponent_x", 10.0},
                    {"exponent_y", 100.0}, {"shadowing", "v_groove"}, {"fresnel", "conductor"},
                    {"eta", kCopperEta}, {"k", kCopperK}})),
      entry("ashikhmin_shirley_iso_smith",
            params({{"distribution", "ashikhmin_shirley"}, {"exponent_x", 50.0},
                    {"exponent_y", 50.0}, {"shadowing", "smith"}, {"fresnel", "none"},
                    {"reflectance", 1.0}})),
      entry("beckmann_rough_smith", params({{"distribution", "beckmann"}, {"alpha_x", 0.5},
                                            {"alpha_y", 0.5}, {"shadowing", "smith"},
                                            {"fresnel", "none"}, {"reflectance", 1.0}})),
      entry("beckmann_aniso_dielectric",
            params({{"distribution", "beckmann"}, {"alpha_x", 0.1}, {"alpha_y", 0.4},
                    {"shadowing", "smith"}, {"fresnel", "dielectric"}, {"eta_i", 1.0},
                    {"eta_t", 1.5}})),
      entry("ggx_smooth_conductor",
            params({{"distribution", "ggx"}, {"alpha_x", 0.1}, {"alpha_y", 0.1},
                    {"shadowing", "smith"}, {"fresnel", "conductor"}, {"eta", kGoldEta},
                    {"k", kGoldK}})),
      entry("ggx_aniso_none", params({{"distribution", "ggx"}, {"alpha_x", 0.35},
                                      {"alpha_y", 0.12}, {"shadowing", "smith"},
                                      {"fresnel", "none"}, {"reflectance", 1.0}})),
      // Blinn with the Smith term (Beckmann's Λ at α = √(2/(e+2))) is not energy-conserving at a
      // low exponent: measured max ρhd 1.346 at θo = 89°. The V-groove term does not gain.
      entry("blinn_e1_smith_gains",
            params({{"distribution", "blinn"}, {"exponent", 1.0}, {"shadowing", "smith"},
                    {"fresnel", "none"}, {"reflectance", 1.0}}),
            1.3463),
      entry("ggx_very_rough_vgroove",
            params({{"distribution", "ggx"}, {"alpha_x", 1.0}, {"alpha_y", 1.0},
                    {"shadowing", "v_groove"}, {"fresnel", "none"}, {"reflectance", 1.0}})),
  };
  g["microfacet_transmission"] = {
      entry("beckmann_glass", params({{"distribution", "beckmann"}, {"alpha_x", 0.3},
                                      {"alpha_y", 0.3}, {"eta_i", 1.0}, {"eta_t", 1.5}})),
      entry("ggx_glass", params({{"distribution", "ggx"}, {"alpha_x", 0.2}, {"alpha_y", 0.2},
                                 {"eta_i", 1.0}, {"eta_t", 1.5}})),
      entry("ggx_aniso_water",
            params({{"distribution", "ggx"}, {"alpha_x", 0.15}, {"alpha_y", 0.45},
                    {"eta_i", 1.0}, {"eta_t", 1.333}, {"transmittance", RGBValue{1.0, 0.8, 0.6}}})),
      entry("ggx_rough_from_inside", params({{"distribution", "ggx"}, {"alpha_x", 0.6},
                                             {"alpha_y", 0.6}, {"eta_i", 1.5}, {"eta_t", 1.0}})),
  };
  g["lafortune"] = {
      entry("diffuse_only", params({{"diffuse", 0.7}, {"lobes", std::vector<ParamSet>{}}})),
      entry("phong_lobe", params({{"diffuse", 0.2},
                                  {"lobes", std::vector<ParamSet>{lobe(-1, -1, 1, 20)}}})),
      entry("retroreflective_aniso",
            params({{"diffuse", 0.1},
                    {"lobes", std::vector<ParamSet>{lobe(0.8, 0.5, 0.7, 8)}}})),
      // Coefficients above 1 make the lobe's peak (C·ω)ⁿ exceed 1: measured max ρhd 1.92 at
      // normal incidence (the model does not normalise its lobes).
      entry("large_c_gains", params({{"diffuse", 0.0},
                                     {"lobes", std::vector<ParamSet>{lobe(-1.1, -1.1, 1.1, 20)}}}),
            1.9214),
      // The grey felt fit of Lafortune et al. 1997 (three lobes, one back-scattering).
      entry("felt_fit", params({{"diffuse", 0.025865},
                                {"lobes", std::vector<ParamSet>{lobe(-0.304075, -0.304075,
                                                                     -0.065992, 3.047892),
                                                                lobe(-0.749561, -0.749561,
                                                                     -1.167929, 6.931827),
                                                                lobe(1.004921, 1.004921,
                                                                     -0.205529, 94.117332)}}})),
  };
  g["cycles_oren_nayar"] = {
      entry("rough0_is_lambert", params({{"color", 0.8}, {"roughness", 0.0}})),
      entry("rough05_tinted", params({{"color", RGBValue{0.9, 0.6, 0.3}}, {"roughness", 0.5}})),
      entry("rough1_white", params({{"color", 1.0}, {"roughness", 1.0}})),
  };
  // Cycles' α = roughness²: 0.35 gives α ≈ 0.12, the sharpest lobe here.
  g["cycles_glossy"] = {
      entry("ggx_smooth", params({{"distribution", "ggx"}, {"roughness", 0.35}, {"color", 1.0}})),
      entry("ggx_aniso", params({{"distribution", "ggx"}, {"roughness", 0.6}, {"anisotropy", 0.5},
                                 {"color", RGBValue{1.0, 0.8, 0.5}}})),
      entry("beckmann_rough", params({{"distribution", "beckmann"}, {"roughness", 0.7},
                                      {"color", 1.0}})),
      entry("beckmann_aniso_negative", params({{"distribution", "beckmann"}, {"roughness", 0.5},
                                               {"anisotropy", -0.6}, {"color", 1.0}})),
      entry("ggx_singular_mirror", params({{"distribution", "ggx"}, {"roughness", 0.0},
                                           {"color", 1.0}})),
      entry("sharp", params({{"distribution", "sharp"}, {"roughness", 0.5},
                             {"color", RGBValue{1.0, 0.7, 0.4}}})),
      // n = 2/α² − 2: roughness 0.45 gives n ≈ 48, roughness 0.6 with anisotropy 0.5 gives
      // nx ≈ 60, ny ≈ 1.9.
      entry("ashikhmin_shirley_iso", params({{"distribution", "ashikhmin_shirley"},
                                             {"roughness", 0.45}, {"color", 1.0}})),
      entry("ashikhmin_shirley_aniso", params({{"distribution", "ashikhmin_shirley"},
                                               {"roughness", 0.6}, {"anisotropy", 0.5},
                                               {"color", RGBValue{0.9, 0.8, 1.0}}})),
      entry("ashikhmin_shirley_rough1", params({{"distribution", "ashikhmin_shirley"},
                                                {"roughness", 1.0}, {"color", 1.0}})),
      entry("multi_ggx_aniso", params({{"distribution", "multi_ggx"}, {"roughness", 0.7},
                                       {"anisotropy", 0.3}, {"color", RGBValue{0.9, 0.7, 0.5}}})),
  };
  // Glass and refraction: α = roughness², ior below over above (inverted seen from below).
  // The rough ones gain energy through Cycles' refraction lobe (see cycles_refraction below)
  // and its weight max(1e-4, 1 − F); measured maxima recorded.
  GridEntry multi_glass = entry("multi_ggx", params({{"distribution", "multi_ggx"},
                                                     {"roughness", 0.7}, {"ior", 1.45}}));
  multi_glass.stochastic_f = true;
  multi_glass.furnace_unchecked = "heavy-tailed walk estimator (see GridEntry::furnace_unchecked)";
  g["cycles_glass"] = {
      entry("ggx", params({{"distribution", "ggx"}, {"roughness", 0.5}, {"ior", 1.5}}), 1.0751),
      entry("beckmann_tinted", params({{"distribution", "beckmann"}, {"roughness", 0.6},
                                       {"ior", 1.33}, {"color", RGBValue{0.9, 0.7, 1.0}}}),
            1.1405),
      entry("ggx_ior_below_one", params({{"distribution", "ggx"}, {"roughness", 0.7},
                                         {"ior", 0.7}}),
            1.1082),
      multi_glass,
      entry("sharp", params({{"distribution", "sharp"}, {"ior", 1.5}})),
      entry("ggx_singular", params({{"distribution", "ggx"}, {"roughness", 0.01}, {"ior", 2.4},
                                    {"color", RGBValue{1.0, 0.9, 0.8}}})),
  };
  // Cycles' rough refraction (weight 1, no Fresnel) gains energy: without a facet side check
  // its f is not zero for pairs no facet refracts into, which adds up to 0.7 at grazing wo
  // (measured maxima at θo = 89°: 1.717 for GGX α 0.25, 1.843 for Beckmann α 0.36).
  // The glass walk's transmitted part: the glass's walk and its heavy tail.
  GridEntry multi_refraction = entry("multi_ggx", params({{"distribution", "multi_ggx"},
                                                          {"roughness", 0.6}, {"ior", 1.33}}));
  multi_refraction.stochastic_f = true;
  multi_refraction.furnace_unchecked = multi_glass.furnace_unchecked;
  multi_refraction.not_reciprocal = "the multiscatter glass walk is not reciprocal for "
                                    "transmission (as cycles_glass's multi_ggx)";
  g["cycles_refraction"] = {
      entry("ggx", params({{"distribution", "ggx"}, {"roughness", 0.5}, {"ior", 1.5}}), 1.7171),
      entry("beckmann", params({{"distribution", "beckmann"}, {"roughness", 0.6},
                                {"ior", 1.45}, {"color", RGBValue{0.8, 1.0, 0.6}}}),
            1.8425),
      entry("sharp", params({{"distribution", "sharp"}, {"ior", 1.33}})),
      entry("index_one_passes_through", params({{"distribution", "ggx"}, {"roughness", 0.5},
                                                {"ior", 1.0}})),
      multi_refraction,
  };
  g["cycles_translucent"] = {
      entry("default", ParamSet()),
      entry("tinted", params({{"color", RGBValue{1.0, 0.5, 0.2}}})),
  };
  g["cycles_transparent"] = {
      entry("white", params({{"color", 1.0}})),
      entry("tinted", params({{"color", RGBValue{0.2, 0.6, 1.0}}})),
  };
  g["cycles_velvet"] = {
      entry("sigma1", params({{"sigma", 1.0}})),
      entry("sigma03_tinted", params({{"sigma", 0.3}, {"color", RGBValue{0.9, 0.3, 0.5}}})),
      entry("sigma0_clamped", params({{"sigma", 0.0}, {"color", 1.0}})),
  };
  // Cycles' Principled BSDF: every closure, roughness ≥ 0.35 so that the grid resolves the
  // lobes; the singular (delta) cases are tested in test_cycles_principled.cpp, except the
  // pure mirror, which is a delta model here. The multiscatter glass (its f gains energy and is
  // heavy-tailed noise, so the furnace estimates disagree beyond 2%) is tested as a lobe in
  // test_multiscatter_ggx.cpp. With transmission the glass weights depend on
  // F(cos θo), so f is not reciprocal.
  const std::string glass_weights = "Cycles weights the glass closures by F(cos θo)";
  GridEntry all_lobes =
      entry("all_lobes", params({{"base_color", RGBValue{0.8, 0.3, 0.2}}, {"metallic", 0.2},
                                 {"specular", 0.6}, {"specular_tint", 0.5}, {"roughness", 0.45},
                                 {"sheen", 1.0}, {"sheen_tint", 0.7}, {"clearcoat", 1.0},
                                 {"clearcoat_roughness", 0.35}, {"transmission", 0.5},
                                 {"transmission_roughness", 0.2}, {"ior", 1.45}}));
  all_lobes.not_reciprocal = glass_weights;
  // Cycles' refraction does not check which side a microfacet faces, so white rough glass
  // reflects and transmits more than it receives: measured max ρhd 1.047 at θo = 85°.
  GridEntry glass = entry("rough_glass", params({{"base_color", 1.0}, {"transmission", 1.0},
                                                 {"roughness", 0.4}, {"ior", 1.5}}),
                          1.0474);
  glass.not_reciprocal = glass_weights;
  GridEntry multi_metal = entry("multi_ggx_metal", params({{"distribution", "multi_ggx"},
                                                           {"metallic", 0.7}, {"roughness", 0.6},
                                                           {"base_color", RGBValue{0.9, 0.8, 0.5}}}));
  multi_metal.stochastic_f = true;
  g["cycles_principled"] = {
      entry("defaults", ParamSet()),
      entry("metal_aniso_rotated",
            params({{"base_color", RGBValue{0.9, 0.6, 0.3}}, {"metallic", 1.0}, {"roughness", 0.6},
                    {"anisotropic", 0.8}, {"anisotropic_rotation", 0.2}})),
      all_lobes,
      glass,
      multi_metal,
      // Burley's diffuse with retro-reflection at roughness 0.9, plus sheen, gains energy at
      // grazing incidence: measured max ρhd 1.312 (red) at θo = 89°.
      entry("subsurface_sheen_rough",
            params({{"subsurface", 0.6}, {"subsurface_color", RGBValue{0.9, 0.2, 0.1}},
                    {"sheen", 0.5}, {"roughness", 0.9}, {"specular", 0.2}}),
            1.3116),
      entry("mirror_metal", params({{"metallic", 1.0}, {"roughness", 0.0},
                                    {"base_color", RGBValue{0.95, 0.7, 0.4}}})),
  };
  // Cornell measurements shipped in data/measured (the model's default is acryl_blue).
  g["measured"] = {
      entry("acryl_blue_interpolated",
            params({{"path", BXDF_TEST_DATA_DIR "/measured/acryl_blue.brdf"}, {"interpolate", true}})),
      entry("garnet_red_nearest",
            params({{"path", BXDF_TEST_DATA_DIR "/measured/garnet_red.brdf"}, {"interpolate", false}})),
  };
  return g;
}

const std::map<std::string, std::vector<GridEntry>>& grid() {
  static const auto g = build_grid();
  return g;
}

IncidentDirection direction(float theta_deg, float phi_deg) {
  const float t = radians(theta_deg), p = radians(phi_deg);
  const Vec3 w(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
  return {"theta" + std::to_string(static_cast<int>(theta_deg)) + "_phi" +
              std::to_string(static_cast<int>(phi_deg)),
          normalize(w)};
}

}  // namespace

const std::vector<GridEntry>* curated_grid(const std::string& model) {
  const auto it = grid().find(model);
  return it == grid().end() ? nullptr : &it->second;
}

std::vector<GridEntry> grid_for(const std::string& model) {
  if (const auto* g = curated_grid(model)) return *g;
  return {entry("defaults", ParamSet())};
}

std::vector<std::string> uncurated_models() {
  std::vector<std::string> out;
  for (const ModelInfo& m : models())
    if (!curated_grid(m.name)) out.push_back(m.name);
  return out;
}

const std::vector<IncidentDirection>& incident_directions() {
  static const std::vector<IncidentDirection> dirs = {
      {"normal", Vec3(0.0f, 0.0f, 1.0f)},
      direction(30, 10),  direction(50, 130), direction(70, 250), direction(85, 45),
      direction(89, 300),  // near-grazing
      direction(120, 60), direction(165, 200),  // below the horizon
  };
  return dirs;
}

std::vector<std::string> registered_model_names() {
  std::vector<std::string> out;
  for (const ModelInfo& m : models()) out.push_back(m.name);
  return out;
}

std::vector<std::string> models_with_entries(bool delta) {
  std::vector<std::string> out;
  for (const ModelInfo& m : models()) {
    for (const GridEntry& e : grid_for(m.name)) {
      bool is_delta;
      try {
        is_delta = make(m.name, e.params)->is_delta();
      } catch (const std::exception&) {
        continue;  // ModelGrid.EveryCuratedEntryBuildsAndLabelsAreUnique reports it
      }
      if (is_delta == delta) {
        out.push_back(m.name);
        break;
      }
    }
  }
  return out;
}

BxDFPtr make_entry(const std::string& model, const GridEntry& entry) {
  return make(model, entry.params);
}

bool refractive_indices(const BxDF& model, float* eta_outside, float* eta_inside) {
  const ParamSet& p = model.params();
  if (!p.has("eta_i") || !p.has("eta_t")) return false;
  *eta_outside = static_cast<float>(p.number("eta_i"));
  *eta_inside = static_cast<float>(p.number("eta_t"));
  return true;
}

bool cycles_refractive_indices(const BxDF& model, float* eta_outside, float* eta_inside) {
  const ParamSet& p = model.params();
  if (!p.has("ior") || !(model.flags() & kTransmission)) return false;
  *eta_outside = 1.0f;
  *eta_inside = std::max(static_cast<float>(p.number("ior")), 1e-5f);
  return true;
}

const char* non_reciprocal_reason(const std::string& model) {
  if (model == "cycles_glass")
    return "Cycles weights the glass lobes by the Fresnel term at N.V alone (F(wo) for "
           "reflection, max(1e-4, 1 - F(wo)) for refraction), and the multiscatter walk is "
           "not reciprocal for transmission";
  return nullptr;
}

std::string describe(const std::string& model, const GridEntry& entry) {
  return model + "[" + entry.label + "]";
}

}  // namespace bxdf::test

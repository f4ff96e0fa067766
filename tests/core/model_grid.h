// The curated test grid: for every registered model a few parameter sets that together cover
// its behaviour (smooth and rough, isotropic and anisotropic, every enum choice, every Fresnel
// kind), and the incident directions every model-wide test visits. The χ², reciprocity,
// energy and fuzz tests all iterate over this one grid.
#pragma once

#include <string>
#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/math.h"
#include "bxdf/params.h"

namespace bxdf::test {

struct GridEntry {
  std::string label;  // short, unique within the model: "ggx_aniso_conductor"
  ParamSet params;    // given to make(); unnamed parameters take their defaults
  // 0 for entries that conserve energy (ρhd ≤ 1.01 everywhere). Entries known to gain energy
  // (the seed's unnormalised models) record here the largest ρhd over incident_directions()
  // that we measured, so that the energy test notices when the gain changes.
  double recorded_max_albedo = 0.0;
  // Why f(wo, wi) ≠ f(wi, wo) by the model's own formula (e.g. weights that depend on wo);
  // empty for entries the reciprocity test checks.
  std::string not_reciprocal;
  // f averages a few random walks (multiple-scattering GGX): a fixed function, but noisy at
  // the scale adaptive quadrature refines to, so the energy test integrates it by sampling only.
  bool stochastic_f = false;
  // Why the white-furnace comparison cannot hold this entry to its tolerance (empty: it does).
  // Multiscatter glass: f/pdf is heavy-tailed (single walks through the dielectric), so two
  // 64k-sample estimates of the same albedo differ by up to 5%; its lobe's energy is checked
  // against a long walk average in test_multiscatter_ggx.cpp instead.
  std::string furnace_unchecked;
  bool energy_conserving() const { return recorded_max_albedo == 0.0; }
};

// The curated entries for `model`, or nullptr when the model has none.
const std::vector<GridEntry>* curated_grid(const std::string& model);
// The curated entries, or a single "defaults" entry for a model without any.
std::vector<GridEntry> grid_for(const std::string& model);
// Registered models that have no curated entries (a test asserts this is empty).
std::vector<std::string> uncurated_models();

// Unit directions in the local frame: several θo from normal to near-grazing, several φo, and
// two below the horizon (a BSDF is hit from both sides).
struct IncidentDirection {
  std::string label;  // "theta85_phi45"
  Vec3 wo;
};
const std::vector<IncidentDirection>& incident_directions();

// Names of all registered models, for parameterised tests.
std::vector<std::string> registered_model_names();
// Registered models with at least one grid entry that is a delta model (delta = true) or
// that is not (delta = false); entries that do not build are left out.
std::vector<std::string> models_with_entries(bool delta);
// make(model, entry.params).
BxDFPtr make_entry(const std::string& model, const GridEntry& entry);

// For models that refract (parameters eta_i, the index on the +z side, and eta_t, the index
// on the −z side): the two indices. False for models without them.
bool refractive_indices(const BxDF& model, float* eta_outside, float* eta_inside);

// For Cycles' refracting models (parameter ior: the index below over the index above):
// outside 1, inside max(ior, 1e-5). Their transmission carries no radiance scaling:
// f(wi, wo) = (η_wo/η_wi)² f(wo, wi), the inverse of the pbrt convention above.
bool cycles_refractive_indices(const BxDF& model, float* eta_outside, float* eta_inside);

// Why a model's f is not reciprocal, or nullptr when it is. The reciprocity test checks that
// such a model is indeed non-reciprocal somewhere (the reason must stay true).
const char* non_reciprocal_reason(const std::string& model);

// "model[label]" for messages.
std::string describe(const std::string& model, const GridEntry& entry);

}  // namespace bxdf::test

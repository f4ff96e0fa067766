// Fresnel reflectance: the exact dielectric formula (both sides, total internal
// reflection), the seed's conductor formula, the exact conductor-under-dielectric formula,
// and the seed's normal-incidence inversions.
#pragma once

#include "bxdf/spectrum.h"

namespace bxdf {

// Unpolarised dielectric reflectance. cos_i < 0 means the light arrives from inside
// (the eta_t side): the indices swap. Returns 1 on total internal reflection.
float fresnel_dielectric(float cos_i, float eta_i, float eta_t);

// The seed's conductor formula (r∥², r⊥² in terms of η, k), evaluated at |cos_i|.
float fresnel_conductor_seed(float cos_i, float eta, float k);
RGB fresnel_conductor_seed(float cos_i, const RGB& eta, const RGB& k);

// Exact conductor under a dielectric of index eta_i: η = eta/eta_i, ηk = k/eta_i.
float fresnel_conductor_exact(float cos_i, float eta_i, float eta, float k);
RGB fresnel_conductor_exact(float cos_i, float eta_i, const RGB& eta, const RGB& k);

// The seed's inversions of F0 (reflectance at normal incidence): k = 0 → η; η = 1 → k.
// F0 is clamped to [0, 0.999999] so that the results stay finite.
float eta_from_f0(float f0);
float k_from_f0(float f0);

// The Fresnel term a model holds: none (F = 1), dielectric, or conductor.
struct Fresnel {
  enum class Kind { None, Dielectric, Conductor };
  Kind kind = Kind::None;
  float eta_i = 1.0f, eta_t = 1.5f;  // dielectric
  RGB eta{1.0f}, k{0.0f};           // conductor, relative to eta_i (the outside medium)
  bool exact_conductor = false;     // seed form by default, as in the lecture

  static Fresnel none() { return {}; }
  static Fresnel dielectric(float ei, float et) {
    Fresnel f;
    f.kind = Kind::Dielectric;
    f.eta_i = ei;
    f.eta_t = et;
    return f;
  }
  static Fresnel conductor(const RGB& eta, const RGB& k, float eta_i = 1.0f, bool exact = false) {
    Fresnel f;
    f.kind = Kind::Conductor;
    f.eta = eta;
    f.k = k;
    f.eta_i = eta_i;
    f.exact_conductor = exact;
    return f;
  }
  RGB evaluate(float cos_i) const {
    switch (kind) {
      case Kind::Dielectric: return RGB(fresnel_dielectric(cos_i, eta_i, eta_t));
      case Kind::Conductor:
        return exact_conductor ? fresnel_conductor_exact(cos_i, eta_i, eta, k)
                               : fresnel_conductor_seed(cos_i, eta, k);
      case Kind::None: break;
    }
    return RGB(1.0f);
  }
};

}  // namespace bxdf

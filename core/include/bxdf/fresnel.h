// Fresnel reflectance: the exact dielectric formula (both sides, total internal
// reflection), the seed's conductor formula, the exact conductor-under-dielectric formula,
// and the seed's normal-incidence inversions.
#pragma once

#include <cmath>
#include <limits>

#include "bxdf/spectrum.h"

namespace bxdf {

// The functions are inline and written with selects rather than early returns, so that a
// batch loop over a model that calls them vectorises. A non-finite cos_i gives 0.

// True for a finite number (NaN fails the comparison); a plain comparison vectorises.
BXDF_KERNEL bool is_finite_number(float x) {
  return std::fabs(x) <= std::numeric_limits<float>::max();
}

// The two sides of a dielectric interface for light arriving at cos_i: the indices of the
// incident (ei) and transmitted (et) sides, |cos θi|, cos θt, and total internal reflection.
// cos_i < 0 means the light arrives from inside (the eta_t side): the indices swap.
struct DielectricAngles {
  float ei, et, c, cos_t;
  bool total_internal_reflection;
};
BXDF_KERNEL DielectricAngles dielectric_angles(float cos_i, float eta_i, float eta_t) {
  const float c_signed = clamp(cos_i, -1.0f, 1.0f);
  const bool inside = c_signed < 0.0f;  // arriving from the eta_t side
  DielectricAngles a;
  a.ei = inside ? eta_t : eta_i;
  a.et = inside ? eta_i : eta_t;
  a.c = inside ? -c_signed : c_signed;
  const float sin_i = safe_sqrt(1.0f - a.c * a.c);
  const float sin_t = a.ei / a.et * sin_i;
  a.total_internal_reflection = sin_t >= 1.0f;
  a.cos_t = safe_sqrt(1.0f - sin_t * sin_t);
  return a;
}

// Unpolarised dielectric reflectance. cos_i < 0 means the light arrives from inside
// (the eta_t side): the indices swap. Returns 1 on total internal reflection.
BXDF_KERNEL float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
  const DielectricAngles a = dielectric_angles(cos_i, eta_i, eta_t);
  const float ei = a.ei, et = a.et, c = a.c, cos_t = a.cos_t;
  const bool total_internal_reflection = a.total_internal_reflection;
  const float r_par = (et * c - ei * cos_t) / (et * c + ei * cos_t);
  const float r_perp = (ei * c - et * cos_t) / (ei * c + et * cos_t);
  const float f = 0.5f * (r_par * r_par + r_perp * r_perp);
  const float f_clamped = is_finite_number(f) ? clamp(f, 0.0f, 1.0f) : 1.0f;  // 0/0: grazing
  return !is_finite_number(cos_i) ? 0.0f : (total_internal_reflection ? 1.0f : f_clamped);
}

// 1 − fresnel_dielectric(cos_i, eta_i, eta_t), computed without the cancellation of 1 − F
// where F is close to 1 (grazing incidence): 1 − r² = 4ab/(a + b)² for r = (a − b)/(a + b).
// 0 on total internal reflection.
BXDF_KERNEL float fresnel_dielectric_transmittance(float cos_i, float eta_i, float eta_t) {
  const DielectricAngles a = dielectric_angles(cos_i, eta_i, eta_t);
  const float ei = a.ei, et = a.et, c = a.c, cos_t = a.cos_t;
  const bool total_internal_reflection = a.total_internal_reflection;
  const float par = et * c + ei * cos_t, perp = ei * c + et * cos_t;
  const float t = 2.0f * ei * et * c * cos_t * (1.0f / (par * par) + 1.0f / (perp * perp));
  const float t_clamped = is_finite_number(t) ? clamp(t, 0.0f, 1.0f) : 0.0f;  // 0/0: grazing
  return !is_finite_number(cos_i) || total_internal_reflection ? 0.0f : t_clamped;
}

// The seed's conductor formula (r∥², r⊥² in terms of η, k), evaluated at |cos_i|.
BXDF_KERNEL float fresnel_conductor_seed(float cos_i, float eta, float k) {
  const float c = std::min(std::fabs(cos_i), 1.0f);
  const float c2 = c * c;
  const float ek = eta * eta + k * k;
  const float two_eta_c = 2.0f * eta * c;
  const float r_par2 = (ek * c2 - two_eta_c + 1.0f) / (ek * c2 + two_eta_c + 1.0f);
  const float r_perp2 = (ek - two_eta_c + c2) / (ek + two_eta_c + c2);
  const float f = clamp(0.5f * (r_par2 + r_perp2), 0.0f, 1.0f);
  return is_finite_number(cos_i) ? f : 0.0f;
}
BXDF_KERNEL RGB fresnel_conductor_seed(float cos_i, const RGB& eta, const RGB& k) {
  return {fresnel_conductor_seed(cos_i, eta.r, k.r), fresnel_conductor_seed(cos_i, eta.g, k.g),
          fresnel_conductor_seed(cos_i, eta.b, k.b)};
}

// Exact conductor under a dielectric of index eta_i: η = eta/eta_i, ηk = k/eta_i.
BXDF_KERNEL float fresnel_conductor_exact(float cos_i, float eta_i, float eta_in, float k_in) {
  const float c = std::min(std::fabs(cos_i), 1.0f);
  const float eta = eta_in / eta_i, eta_k = k_in / eta_i;
  const float c2 = c * c;
  const float s2 = 1.0f - c2;
  const float eta2 = eta * eta, eta_k2 = eta_k * eta_k;
  const float t0 = eta2 - eta_k2 - s2;
  const float a2b2 = std::sqrt(t0 * t0 + 4.0f * eta2 * eta_k2);
  const float a = safe_sqrt(0.5f * (a2b2 + t0));
  const float t1 = a2b2 + c2;
  const float t2 = 2.0f * a * c;
  const float rs = (t1 - t2) / (t1 + t2);
  const float t3 = c2 * a2b2 + s2 * s2;
  const float t4 = t2 * s2;
  const float rp = rs * (t3 - t4) / (t3 + t4);
  const float f = 0.5f * (rs + rp);
  const float f_clamped = is_finite_number(f) ? clamp(f, 0.0f, 1.0f) : 1.0f;
  return is_finite_number(cos_i) ? f_clamped : 0.0f;
}
BXDF_KERNEL RGB fresnel_conductor_exact(float cos_i, float eta_i, const RGB& eta, const RGB& k) {
  return {fresnel_conductor_exact(cos_i, eta_i, eta.r, k.r),
          fresnel_conductor_exact(cos_i, eta_i, eta.g, k.g),
          fresnel_conductor_exact(cos_i, eta_i, eta.b, k.b)};
}

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
  // The four forms as compile-time choices, for kernels specialised once per batch.
  enum class Form { None, Dielectric, ConductorSeed, ConductorExact };
  Form form() const {
    switch (kind) {
      case Kind::Dielectric: return Form::Dielectric;
      case Kind::Conductor: return exact_conductor ? Form::ConductorExact : Form::ConductorSeed;
      case Kind::None: break;
    }
    return Form::None;
  }
  template <Form F>
  BXDF_KERNEL RGB evaluate_as(float cos_i) const {
    if constexpr (F == Form::Dielectric) return RGB(fresnel_dielectric(cos_i, eta_i, eta_t));
    if constexpr (F == Form::ConductorSeed) return fresnel_conductor_seed(cos_i, eta, k);
    if constexpr (F == Form::ConductorExact) return fresnel_conductor_exact(cos_i, eta_i, eta, k);
    return RGB(1.0f);
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

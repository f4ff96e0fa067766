// The fitted BRDF formulas, templated on the scalar type so Ceres can differentiate them.
// Parameters live in an unconstrained or simply bounded form: exponents and roughnesses as
// logarithms (their useful range spans decades), Lafortune lobes as (log K, ψ, log n) with
// lobe = K · max(0, cos ψ · dot_xy + sin ψ · dot_z)^n, i.e. Cxy = K^(1/n) cos ψ, Cz = K^(1/n) sin ψ.
#pragma once

#include <cmath>

#include "fit_geometry.h"

namespace bxdf::fit {

constexpr double kPiD = 3.14159265358979323846;

// x^n for x > 0 (0 otherwise), safe for automatic differentiation at x = 0.
template <class T>
T positive_pow(const T& x, const T& n) {
  using std::exp;
  using std::log;
  if (!(x > T(1e-300))) return T(0.0);
  return exp(n * log(x));
}

// One channel of a Lafortune model: p = [ρd, (log K, ψ, log n) × lobes], with
// lobe = K · max(0, √2 (cos ψ · dot_xy + sin ψ · dot_z))^n, so ψ = 135° is a Phong lobe about the
// mirror direction whose peak value is K. In the registry's terms Cxy = √2 K^(1/n) cos ψ,
// Cz = √2 K^(1/n) sin ψ.
template <class T, int kLobes>
struct LafortuneChannel {
  T diffuse, log_k[kLobes], cxy[kLobes], cz[kLobes], n[kLobes];
  explicit LafortuneChannel(const T* p) {
    using std::cos;
    using std::exp;
    using std::sin;
    diffuse = p[0] / kPiD;
    for (int l = 0; l < kLobes; ++l) {
      const T* q = p + 1 + 3 * l;
      log_k[l] = q[0];
      cxy[l] = std::sqrt(2.0) * cos(q[1]);
      cz[l] = std::sqrt(2.0) * sin(q[1]);
      n[l] = exp(q[2]);
    }
  }
  T operator()(const FitSample& s) const {
    T f = diffuse;
    using std::exp;
    using std::log;
    for (int l = 0; l < kLobes; ++l) {
      const T base = cxy[l] * s.dot_xy + cz[l] * s.dot_z;
      if (!(base > T(1e-300))) continue;
      // log K + n log(base), capped: a tilted lobe has base > 1 at grazing angles and a large
      // n would overflow; the cap keeps the residual finite (and huge) so Ceres just rejects
      // such a step.
      T e = log_k[l] + n[l] * log(base);
      if (e > T(60.0)) e = T(60.0);
      f += exp(e);
    }
    return f;
  }
};

enum class Distribution { Blinn, AshikhminShirley, Beckmann, GGX };

// Normal distributions D(h) of reference/models.md, with roughness parameters r (logs).
template <class T>
T distribution(Distribution d, const T* r, const FitSample& s) {
  using std::exp;
  using std::sqrt;
  switch (d) {
    case Distribution::Blinn: {
      const T e = exp(r[0]);
      return (e + 2.0) / (2.0 * kPiD) * positive_pow(T(s.cos_h), e);
    }
    case Distribution::AshikhminShirley: {
      const T ex = exp(r[0]), ey = exp(r[1]);
      const T power = ex * s.cos2_phi_h + ey * (1.0 - s.cos2_phi_h);
      return sqrt((ex + 2.0) * (ey + 2.0)) / (2.0 * kPiD) * positive_pow(T(s.cos_h), power);
    }
    case Distribution::Beckmann: {
      const T a2 = exp(2.0 * r[0]);
      const double c4 = s.cos_h * s.cos_h * s.cos_h * s.cos_h;
      return exp(-s.tan2_h / a2) / (kPiD * a2 * c4);
    }
    case Distribution::GGX: {
      const T a2 = exp(2.0 * r[0]);
      const double c4 = s.cos_h * s.cos_h * s.cos_h * s.cos_h;
      const T t = 1.0 + s.tan2_h / a2;
      return 1.0 / (kPiD * a2 * c4 * t * t);
    }
  }
  return T(0.0);
}

// Unpolarised dielectric Fresnel from air (η_i = 1) into η at cos θ = c.
template <class T>
T fresnel_dielectric(double c, const T& eta) {
  using std::sqrt;
  const T sin2_t = (1.0 - c * c) / (eta * eta);
  const T cos_t = sqrt(1.0 - sin2_t);  // η > 1: never total internal reflection
  const T r_par = (eta * c - cos_t) / (eta * c + cos_t);
  const T r_perp = (c - eta * cos_t) / (c + eta * cos_t);
  return 0.5 * (r_par * r_par + r_perp * r_perp);
}

// Height-correlated Smith masking-shadowing for GGX (pbrt-v3): 1 / (1 + Λ(wo) + Λ(wi)).
template <class T>
T smith_ggx(const T* r, const FitSample& s) {
  using std::exp;
  using std::sqrt;
  const T a2 = exp(2.0 * r[0]);
  const T lo = (-1.0 + sqrt(1.0 + a2 * s.tan2_o)) * 0.5;
  const T li = (-1.0 + sqrt(1.0 + a2 * s.tan2_i)) * 0.5;
  return 1.0 / (1.0 + lo + li);
}

}  // namespace bxdf::fit

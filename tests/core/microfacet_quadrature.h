// Numerical integration over the hemisphere of half vectors for the microfacet tests, in
// double precision and independent of the library's sampling code.
//
// ∫ g(ω) dω is computed in the variables (τ, ψ): φ = atan2(k sin τ, cos τ) spreads the
// azimuths of an anisotropic lobe evenly (k = the lobe's width ratio y/x), and
// tan θ = a(φ) tan ψ puts the lobe's width a(φ) in the middle of ψ ∈ [0, π/2). Midpoint
// rule in both (periodic in τ). This resolves lobes from 1e-4 to 10 wide with a fixed grid.
#pragma once

#include <cmath>
#include <functional>

#include "bxdf/math.h"

namespace bxdf_test {

constexpr double kPiD = 3.14159265358979323846;

struct HemisphereQuadrature {
  double k = 1.0;                                                        // azimuthal width ratio
  std::function<double(double phi)> width = [](double) { return 1.0; };  // a(φ) in tan θ
  int n_tau = 128;
  int n_psi = 512;

  double integrate(const std::function<double(const bxdf::Vec3&)>& g) const {
    double total = 0.0;
    const double d_tau = 2.0 * kPiD / n_tau, d_psi = 0.5 * kPiD / n_psi;
    for (int i = 0; i < n_tau; ++i) {
      const double tau = (i + 0.5) * d_tau;
      const double phi = std::atan2(k * std::sin(tau), std::cos(tau));
      const double c = std::cos(tau), s = std::sin(tau);
      const double dphi_dtau = k / (c * c + k * k * s * s);
      const double a = width(phi);
      double inner = 0.0;
      for (int j = 0; j < n_psi; ++j) {
        const double psi = (j + 0.5) * d_psi;
        const double t = a * std::tan(psi);  // tan θ
        const double dt_dpsi = a / (std::cos(psi) * std::cos(psi));
        const double cos_t = 1.0 / std::sqrt(1.0 + t * t);
        const double sin_t = t * cos_t;
        const bxdf::Vec3 w(static_cast<float>(sin_t * std::cos(phi)),
                           static_cast<float>(sin_t * std::sin(phi)), static_cast<float>(cos_t));
        // dω = sin θ dθ dφ = t/(1 + t²)^(3/2) dt dφ
        inner += g(w) * sin_t * cos_t * cos_t * dt_dpsi;
      }
      total += inner * d_psi * dphi_dtau;
    }
    return total * d_tau;
  }
};

// The lobe width of an anisotropic Beckmann/GGX surface in azimuth φ (slope scale).
inline HemisphereQuadrature quadrature_for_alphas(double ax, double ay) {
  HemisphereQuadrature q;
  q.k = ay / ax;
  q.width = [ax, ay](double phi) {
    const double c = std::cos(phi), s = std::sin(phi);
    return 1.0 / std::sqrt(c * c / (ax * ax) + s * s / (ay * ay));
  };
  return q;
}

// Blinn/Ashikhmin–Shirley exponents behave like Beckmann α = sqrt(2/(e + 2)) per axis.
inline HemisphereQuadrature quadrature_for_exponents(double ex, double ey) {
  return quadrature_for_alphas(std::sqrt(2.0 / (ex + 2.0)), std::sqrt(2.0 / (ey + 2.0)));
}

}  // namespace bxdf_test

// The Beckmann distribution, anisotropic:
// D = exp(−tan²θh (cos²φ/αx² + sin²φ/αy²)) / (π αx αy cos⁴θh).
// Sampling draws the normals visible from wo (Heitz and d'Eon 2014, with Jakob's numerical
// inversion of the slope CDF, as Mitsuba does), density D G1(wo) max(0, wo·wh) / cos θo with
// Smith's exact G1: fewer samples on facets wo cannot see than D cos θh drew, as Cycles' own
// Beckmann sampler does. lambda() stays Walter's rational fit, which the models' f use (Cycles'
// formula); the pdf needs the exact one, whose density integrates to 1.
#pragma once

#include <cmath>

#include "bxdf/microfacet/common.h"

namespace bxdf {
namespace microfacet {

// Slopes (x, y) of a unit-roughness Beckmann normal drawn from the normals visible from a
// direction at polar angle θ in the xz plane (beckmann_visible_slopes.cpp).
void beckmann_visible_slopes(float cos_theta, float sin_theta, Point2 u, float* slope_x,
                             float* slope_y);

struct Beckmann {
  float alpha_x = 0.3f, alpha_y = 0.3f;

  Beckmann() = default;
  Beckmann(float ax, float ay) : alpha_x(clamp_alpha(ax)), alpha_y(clamp_alpha(ay)) {}

  BXDF_KERNEL float D(const Vec3& wh) const {
    // tan²θ(cos²φ/αx² + sin²φ/αy²) = (x²/αx² + y²/αy²)/z².
    const float sx = wh.x / alpha_x, sy = wh.y / alpha_y;
    const float z2 = wh.z * wh.z;
    const float e = (sx * sx + sy * sy) / z2;
    // exp(−80) ≈ 2e−35: past this D is far below anything a renderer adds up, and near the
    // horizon the quotient would be a denormal divided by a denormal.
    // exp_poly rather than std::exp so that batch loops over D vectorise; its argument is kept
    // in range (e >= 80 and NaN become 80, whose result is not used).
    const float e_in_range = e < 80.0f ? e : 80.0f;
    const float d = exp_poly(-e_in_range) / (kPi * alpha_x * alpha_y * z2 * z2);
    const float d_in_range = e < 80.0f ? d : 0.0f;
    return wh.z > 0.0f ? d_in_range : 0.0f;
  }
  BXDF_KERNEL float lambda(const Vec3& w) const { return beckmann_lambda(w, alpha_x, alpha_y); }
  BXDF_KERNEL float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }

  Vec3 sample_wh(const Vec3& wo, Point2 u) const {
    // Stretch wo to the configuration where the roughness is 1, sample the slopes visible from
    // it there, then rotate and unstretch them (Heitz and d'Eon 2014, §4).
    Vec3 vh(alpha_x * wo.x, alpha_y * wo.y, wo.z);
    if (!normalize_direction(vh) || !(vh.z > 0.0f)) return {0.0f, 0.0f, 1.0f};
    const float sin_theta = safe_sqrt(1.0f - vh.z * vh.z);
    float cos_phi = 1.0f, sin_phi = 0.0f;
    if (sin_theta > 0.0f) {
      cos_phi = vh.x / sin_theta;
      sin_phi = vh.y / sin_theta;
    }
    float sx, sy;
    beckmann_visible_slopes(vh.z, sin_theta, u, &sx, &sy);
    const float x = (cos_phi * sx - sin_phi * sy) * alpha_x;
    const float y = (sin_phi * sx + cos_phi * sy) * alpha_y;
    Vec3 wh(-x, -y, 1.0f);
    normalize_direction(wh);
    return wh;
  }
  // The density of sample_wh: D(wh) G1(wo) max(0, wo·wh) / cos θo with the exact G1.
  float pdf_wh(const Vec3& wo, const Vec3& wh) const {
    if (!(wo.z > 0.0f)) return 0.0f;
    return D(wh) * exact_G1(wo) * std::max(0.0f, dot(wo, wh)) / wo.z;
  }
  // Smith's masking for the Beckmann distribution, exactly: Λ = (erf(a) − 1)/2 + e^{−a²}/(2a√π)
  // with a = 1/(α tan θ).
  float exact_G1(const Vec3& w) const {
    const float t = projected_alpha2_tan2(w, alpha_x, alpha_y);
    if (!(t > 0.0f)) return w.z == 0.0f ? 0.0f : 1.0f;
    const float a = 1.0f / std::sqrt(t);
    const float lambda = 0.5f * (std::erf(a) - 1.0f) + std::exp(-a * a) / (2.0f * a * kSqrtPi);
    return 1.0f / (1.0f + std::max(lambda, 0.0f));
  }
};

}  // namespace microfacet
}  // namespace bxdf

// What the four microfacet distributions share: the α floor, slopes written from vector
// components, the Smith Λ of the Beckmann and GGX profiles, the seed's V-groove G and the
// height-correlated Smith G.
//
// Every distribution (blinn.h, ashikhmin_shirley.h, beckmann.h, ggx.h) is a plain struct with
// inline D(wh), lambda(w), G1(w), sample_wh(wo, u) and pdf_wh(wo, wh), so that a model can be
// a template over it with no virtual call per sample. Conventions: directions are unit
// vectors in the shading frame; D and pdf_wh are 0 for wh.z <= 0; sample_wh and pdf_wh take
// wo in the upper hemisphere (models mirror their directions there first); Λ depends on
// |cos θ| only, so it serves directions below the surface too (transmission).
#pragma once

#include <cmath>
#include <limits>

#include "bxdf/frame.h"
#include "bxdf/math.h"

namespace bxdf {
namespace microfacet {

// Smallest roughness a distribution accepts; smaller values are raised to it. A half vector
// normalize(wo + wi) computed in float carries an absolute error of ~6e-8 per component, so
// the slope x/α that D and Λ need is only good to ~1e-3 down to α ≈ 1e-4; below that D
// (which grows as 1/α²) would be noise. Lobes that narrow are mirrors for all practical use.
constexpr float kMinAlpha = 1e-4f;
inline float clamp_alpha(float alpha) { return std::max(alpha, kMinAlpha); }

// tan²θ of a unit direction from its components: (x² + y²)/z². Near the pole this keeps the
// precision that 1 − cos²θ loses (cos θ rounds to 1 in float for θ < ~3e-4).
inline float tan2_theta_of(const Vec3& w) { return (w.x * w.x + w.y * w.y) / (w.z * w.z); }

// The standard mapping between a Phong/Blinn exponent and a Beckmann roughness,
// α = sqrt(2/(e + 2)) (the two lobes agree to second order about the normal). Blinn and
// Ashikhmin–Shirley have no Smith Λ of their own; they use the Beckmann Λ at this α.
inline float beckmann_alpha_from_exponent(float e) { return std::sqrt(2.0f / (e + 2.0f)); }

// α² tan²θ for an anisotropic surface: the roughness projected on the azimuth of w,
// α(φ)² = cos²φ αx² + sin²φ αy², times tan²θ, from the components.
BXDF_KERNEL float projected_alpha2_tan2(const Vec3& w, float alpha_x, float alpha_y) {
  return (alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y) / (w.z * w.z);
}

// Smith Λ for the GGX (Trowbridge–Reitz) profile: (−1 + sqrt(1 + α²tan²θ))/2, written as
// t/(2(1 + sqrt(1 + t))) to avoid cancellation near the normal. ∞ at the horizon.
BXDF_KERNEL float ggx_lambda(const Vec3& w, float alpha_x, float alpha_y) {
  // Selects instead of early returns, so that batch loops vectorise.
  const float t = projected_alpha2_tan2(w, alpha_x, alpha_y);
  const float lambda = t / (2.0f * (1.0f + std::sqrt(1.0f + t)));
  const bool horizon = w.z == 0.0f || !(t < std::numeric_limits<float>::max());
  return horizon ? std::numeric_limits<float>::infinity() : lambda;
}

// Smith Λ for the Beckmann profile: the rational fit of Walter et al. 2007 in
// a = 1/(α tanθ): 0 for a >= 1.6, else (1 − 1.259a + 0.396a²)/(3.535a + 2.181a²).
BXDF_KERNEL float beckmann_lambda(const Vec3& w, float alpha_x, float alpha_y) {
  const float t = projected_alpha2_tan2(w, alpha_x, alpha_y);
  const float a = 1.0f / std::sqrt(t);
  const float lambda = (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
  // t = 0 (along the normal) gives a = ∞ and lands in the a >= 1.6 case.
  // (Nested selects rather than ||: GCC 12 vectorises those.)
  const float lambda_or_0 = a >= 1.6f ? 0.0f : lambda;
  const float finite_part = t > 0.0f ? lambda_or_0 : 0.0f;
  return w.z == 0.0f ? std::numeric_limits<float>::infinity() : finite_part;
}

// The seed's V-groove shadowing-masking (Torrance–Sparrow / Blinn):
// min(1, 2(n·h)(n·wo)/(wo·h), 2(n·h)(n·wi)/(wo·h)). For a reflection half vector
// wo·h = wi·h, so one denominator serves both terms.
BXDF_KERNEL float v_groove_G(const Vec3& wo, const Vec3& wi, const Vec3& wh) {
  const float n_h = std::fabs(wh.z);
  const float wo_h = std::fabs(dot(wo, wh));
  const float g_o = 2.0f * n_h * std::fabs(wo.z) / wo_h;
  const float g_i = 2.0f * n_h * std::fabs(wi.z) / wo_h;
  return wo_h == 0.0f ? 0.0f : std::min(1.0f, std::min(g_o, g_i));
}

// Height-correlated Smith G (pbrt-v3): 1/(1 + Λ(wo) + Λ(wi)).
BXDF_KERNEL float smith_G_correlated(float lambda_o, float lambda_i) {
  return 1.0f / (1.0f + lambda_o + lambda_i);
}

}  // namespace microfacet
}  // namespace bxdf

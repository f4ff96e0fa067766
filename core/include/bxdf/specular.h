// Directions and weights of a perfectly smooth interface, shared by the delta (specular)
// models: the mirror direction and refraction through a dielectric whose outside (z > 0)
// has index eta_i and inside eta_t.
#pragma once

#include "bxdf/frame.h"

namespace bxdf {

// Below this |cos θ| a delta lobe's weight (∝ 1/|cos θ|) could overflow a float, and the
// direction is grazing anyway: the delta models give no sample there.
constexpr float kMinSpecularCos = 1e-30f;

// Mirror direction about the normal (0, 0, 1) in the local frame.
inline Vec3 specular_reflect(const Vec3& wo) { return {-wo.x, -wo.y, wo.z}; }

// Refraction of wo through the interface (wo on either side). On success writes wi (on the
// other side) and radiance_scale = (η_wo/η_wi)², the indices on wo's and on wi's side. Why the
// factor: Snell's law keeps η² cos θ dω invariant across the interface, so radiance
// (flux per area per projected solid angle) is not conserved but L/η² is; light arriving from
// wi's medium leaves into wo's medium with its radiance scaled by (η_wo/η_wi)² (pbrt-v3's
// TransportMode::Radiance; importance transport would omit it).
// Returns false on total internal reflection or when wo or wi is grazing (kMinSpecularCos).
inline bool specular_refract(const Vec3& wo, float eta_i, float eta_t, Vec3* wi,
                             float* radiance_scale) {
  if (std::fabs(wo.z) < kMinSpecularCos) return false;
  const bool entering = wo.z > 0.0f;
  const float eta_wo_side = entering ? eta_i : eta_t;
  const float eta_wi_side = entering ? eta_t : eta_i;
  const Vec3 n(0.0f, 0.0f, entering ? 1.0f : -1.0f);
  if (!refract(wo, n, eta_wo_side / eta_wi_side, wi) || std::fabs(wi->z) < kMinSpecularCos)
    return false;
  const float ratio = eta_wo_side / eta_wi_side;
  *radiance_scale = ratio * ratio;
  return true;
}

}  // namespace bxdf

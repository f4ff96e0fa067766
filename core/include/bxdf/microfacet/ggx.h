// The GGX (Trowbridge–Reitz) distribution, anisotropic:
// D = 1/(π αx αy cos⁴θh (1 + tan²θh (cos²φ/αx² + sin²φ/αy²))²).
// Sampling draws the normals visible from wo (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals"): density D(wh) G1(wo) max(0, wo·wh)/cos θo, which integrates to exactly 1
// because G1 here is GGX's exact Smith term.
#pragma once

#include "bxdf/microfacet/common.h"
#include "bxdf/sampling.h"

namespace bxdf {
namespace microfacet {

struct GGX {
  float alpha_x = 0.3f, alpha_y = 0.3f;

  GGX() = default;
  GGX(float ax, float ay) : alpha_x(clamp_alpha(ax)), alpha_y(clamp_alpha(ay)) {}

  BXDF_KERNEL float D(const Vec3& wh) const {
    // cos⁴θ (1 + tan²θ(...))² = (z² + x²/αx² + y²/αy²)² for a unit vector.
    const float sx = wh.x / alpha_x, sy = wh.y / alpha_y;
    const float s = wh.z * wh.z + sx * sx + sy * sy;
    const float d = 1.0f / (kPi * alpha_x * alpha_y * s * s);
    return wh.z <= 0.0f ? 0.0f : d;  // a select, not a branch: batch loops vectorise
  }
  BXDF_KERNEL float lambda(const Vec3& w) const { return ggx_lambda(w, alpha_x, alpha_y); }
  BXDF_KERNEL float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }

  Vec3 sample_wh(const Vec3& wo, Point2 u) const {
    // Stretch wo to the configuration where the roughness is 1 (a hemisphere of normals).
    Vec3 vh(alpha_x * wo.x, alpha_y * wo.y, wo.z);
    if (!normalize_direction(vh)) return {0.0f, 0.0f, 1.0f};
    // Orthonormal basis around vh (T1 = z × vh, or x at the pole).
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(vh, t1);
    // A uniform point on the disk, squeezed onto the part of it that the projected
    // hemisphere covers. The concentric map keeps the sampler's strata compact where the polar
    // one (r = √u.x, φ = 2π u.y) stretches them into thin rings and wedges, so the
    // Sobol points' stratification survives into the lobe: measured, 27% less MSE at 64 spp on
    // principled_showroom's GGX spheres, the same distribution.
    const Point2 disk = sample_concentric_disk(u);
    const float p1 = disk.x;
    float p2 = disk.y;
    const float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * safe_sqrt(1.0f - p1 * p1) + s * p2;
    // Lift onto the hemisphere and unstretch.
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * safe_sqrt(1.0f - p1 * p1 - p2 * p2);
    Vec3 wh(alpha_x * nh.x, alpha_y * nh.y, std::max(1e-6f, nh.z));
    normalize_direction(wh);
    return wh;
  }
  BXDF_KERNEL float pdf_wh(const Vec3& wo, const Vec3& wh) const {
    const float pdf = D(wh) * G1(wo) * std::max(0.0f, dot(wo, wh)) / wo.z;
    return wo.z <= 0.0f ? 0.0f : pdf;
  }
};

}  // namespace microfacet
}  // namespace bxdf

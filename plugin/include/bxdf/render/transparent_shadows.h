// Cycles' transparent shadows (integrator/intersect_shadow.h, shade_shadow.h): a shadow ray
// passes through a surface whose material has a Transparent BSDF (cycles_transparent, alone or
// in a mix), its throughput multiplied there by the transparent closures' summed weight (their
// colour times the mix weight: Cycles' closure_transparent_extinction). Any other surface
// blocks it, and so does a transparent hit past the budget: Cycles 3.4 lets a shadow ray
// through transparent_max_bounces transparent surfaces and no more (measured with the default
// 8: 8 stacked veils pass, 9 block; tests/blender/test_transparent_shadows.py). The path's own
// transparent bounces so far lower that budget, as in Cycles (integrate_shadow_max_transparent_
// hits: transparent_max_bounces − the path's transparent bounces).
#pragma once

#include <cstdint>
#include <vector>

#include "bxdf/render/scene.h"

namespace bxdf::render {

class TransparentShadows {
 public:
  // Cycles' default transparent_max_bounces.
  static constexpr int kDefaultMaxBounces = 8;

  TransparentShadows(const Scene& scene, int max_transparent_bounces = kDefaultMaxBounces);

  // The light a shadow ray from `origin` along the unit `dir` carries to tmax: 1 when nothing is
  // in the way, the product of the transparent surfaces' weights when only they are, else 0.
  // `path_transparent_bounces`: the transparent surfaces the path passed before this vertex.
  RGB throughput(const Vec3& origin, const Vec3& dir, float tmax,
                 int path_transparent_bounces = 0) const;

  // The summed weight of a BSDF's Transparent components (Cycles' closure_transparent_
  // extinction): what passes straight through the surface.
  static RGB transparent_weight(const BSDF& bsdf);

  // The ray parameter just past a hit at t on `ray`: a relative step well above the hit's
  // rounding, so that the next query along the same ray starts behind the surface.
  static float past_hit(const Ray& ray, float t);

  // Whether a BSDF component is a Transparent BSDF (a pass-through, not a bounce).
  static bool is_transparent(const BxDF* component);

  // Whether material `index` has a Transparent BSDF (in its components or its graph).
  bool transparent(uint32_t index) const { return transparent_[index] != 0; }
  // True when some material has a Transparent BSDF (else a shadow ray is plain occlusion).
  bool any() const { return any_; }

 private:
  // The transparent weight of the surface point sp a shadow ray (direction dir) hits.
  RGB surface_transparency(const Hit& hit, SurfacePoint sp, const Vec3& dir) const;

  const Scene& scene_;
  int max_hits_;
  std::vector<uint8_t> transparent_;  // per material
  bool any_ = false;
};

}  // namespace bxdf::render

#include "bxdf/lone_diffuse.h"

#include <new>

namespace bxdf {

bool LoneDiffuse::of(const BSDF& bsdf, LoneDiffuse* out) {
  // The cheap tests first: most BSDFs that are not one are told by their flags.
  if (bsdf.num_components() != 1 || bsdf.component(0)->flags() != (kReflection | kDiffuse) ||
      !bsdf.in_shading_frame(0))
    return false;
  Vec3 horizon;
  const bool clips = bsdf.sampling_horizon(&horizon);
  return of(*bsdf.component(0), bsdf.weight(0), bsdf.frame(), bsdf.geometric_normal(),
            clips ? &horizon : nullptr, out);
}

bool LoneDiffuse::constant_f(const BxDF& model, const RGB& weight, RGB* f) {
  RGB model_f;
  if (model.flags() != (kReflection | kDiffuse) || !model.constant_cosine_lobe(&model_f))
    return false;
  // A zero sample weight (BSDF::add's) leaves the BSDF nothing to sample and a pdf of 0.
  if (!(weight.average() * model.closure_sample_weight() > 0.0f)) return false;
  *f = weight * model_f;
  return true;
}

bool LoneDiffuse::of(const BxDF& model, const RGB& weight, const Frame& frame, const Vec3& ng,
                     const Vec3* horizon, LoneDiffuse* out) {
  RGB f;
  if (!constant_f(model, weight, &f)) return false;
  ::new (out) LoneDiffuse(f, frame, ng, horizon);  // in place, as the path tracer makes one
  return true;
}

}  // namespace bxdf

#include "bxdf/lone_diffuse.h"

#include "bxdf/cosine_above_plane.h"
#include "bxdf/sampling.h"

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

bool LoneDiffuse::of(const BxDF& model, const RGB& weight, const Frame& frame, const Vec3& ng,
                     const Vec3* horizon, LoneDiffuse* out) {
  RGB f;
  if (model.flags() != (kReflection | kDiffuse) || !model.constant_cosine_lobe(&f)) return false;
  // A zero sample weight (BSDF::add's) leaves the BSDF nothing to sample and a pdf of 0.
  if (!(weight.average() * model.closure_sample_weight() > 0.0f)) return false;
  out->frame_ = frame;
  out->ng_ = ng;
  out->f_ = weight * f;
  // BSDF::set_sampling_horizon and clipped_lobe: a plane within float noise of the frame's
  // clips nothing, nor one the frame's normal is not above.
  out->has_horizon_ = false;
  if (horizon && dot(*horizon, frame.n) < 1.0f - 1e-7f) {
    out->horizon_local_ = frame.to_local(*horizon);
    out->has_horizon_ = out->horizon_local_.z > 0.0f;
  }
  return true;
}

RGB LoneDiffuse::f_cos_pdf(const Vec3& wo, const Vec3& wi, float* pdf) const {
  // The frame's z of each direction (Frame::to_local's third row).
  const float cos_o = dot(wo, frame_.n);
  *pdf = 0.0f;
  if (cos_o == 0.0f) return RGB(0.0f);
  const float cos_i = dot(wi, frame_.n);
  const bool same_side = cos_o * cos_i > 0.0f;
  if (clipped(cos_o)) *pdf = cosine_above_plane_pdf(frame_.to_local(wi), horizon_local_);
  else if (same_side) *pdf = cosine_hemisphere_pdf(std::fabs(cos_i));
  // The geometric normal decides between reflection and transmission (BSDF::f).
  const bool reflects = dot(wi, ng_) * dot(wo, ng_) > 0.0f;
  return reflects && same_side ? f_ * std::fabs(cos_i) : RGB(0.0f);
}

BSDFSample LoneDiffuse::sample_f(const Vec3& wo, Point2 u) const {
  BSDFSample out;
  const float cos_o = dot(wo, frame_.n);
  if (cos_o == 0.0f) return out;
  Vec3 wi;
  float pdf;
  if (clipped(cos_o)) {
    wi = sample_cosine_above_plane(u, horizon_local_);
    pdf = cosine_above_plane_pdf(wi, horizon_local_);
  } else {
    wi = sample_cosine_hemisphere(u);  // sample_cosine_reflection: on wo's side
    if (cos_o < 0.0f) wi.z = -wi.z;
    pdf = cosine_hemisphere_pdf(std::fabs(wi.z));
  }
  if (!(pdf > 0.0f)) return out;
  out.wi = frame_.to_world(wi);
  if (!(dot(out.wi, ng_) * dot(wo, ng_) > 0.0f)) return BSDFSample{};
  out.f = f_;
  out.f_cos = f_ * std::fabs(wi.z);
  out.pdf = pdf;
  out.flags = kReflection | kDiffuse;
  out.component = 0;
  return out;
}

}  // namespace bxdf

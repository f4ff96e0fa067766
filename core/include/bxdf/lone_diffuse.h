// The BSDF most path vertices shade: one diffuse closure of constant albedo (a Lambertian, or
// Cycles' Diffuse BSDF at roughness 0) in the BSDF's own shading frame. LoneDiffuse gives what
// the path tracer asks of such a BSDF (f·cos with and without the pdf, a sample) from the two
// cosines against the shading normal, in world space, where the general BSDF moves both
// directions into the component's frame, weighs the components, and calls the model through
// its checked, virtual interface. The values are the BSDF's up to rounding (test
// LoneDiffuse.AgreesWithTheBSDF): the same geometric-normal test, the same cosine lobe on wo's
// side, and the same lobe clipped at the triangle's plane on smooth surfaces
// (cosine_above_plane.h), where the directions still go through the frame.
#pragma once

#include "bxdf/bsdf.h"
#include "bxdf/cosine_above_plane.h"
#include "bxdf/sampling.h"

namespace bxdf {

class LoneDiffuse {
 public:
  LoneDiffuse() = default;
  // The LoneDiffuse of f (constant_f's) in `frame`, with the geometric normal ng and, where
  // not null, the horizon that clips the lobe (BSDF::set_sampling_horizon's).
  LoneDiffuse(const RGB& f, const Frame& frame, const Vec3& ng, const Vec3* horizon);

  // weight × `model`'s constant f where, alone in a BSDF's own frame, it is a LoneDiffuse, else
  // false: what of() decides of a model, for a caller that decides it once per material.
  static bool constant_f(const BxDF& model, const RGB& weight, RGB* f);
  // The lone diffuse closure of `bsdf` in *out, or false where the BSDF is anything else
  // (several components, a perturbed normal, another model, a zero weight).
  static bool of(const BSDF& bsdf, LoneDiffuse* out);
  // The BSDF that BSDF(frame, ng), set_sampling_horizon(*horizon) where horizon is not null,
  // and add(&model, weight) would build, where it is a LoneDiffuse (without building it).
  static bool of(const BxDF& model, const RGB& weight, const Frame& frame, const Vec3& ng,
                 const Vec3* horizon, LoneDiffuse* out);

  // BSDF::f_cos and BSDF::f_cos_pdf.
  RGB f_cos(const Vec3& wo, const Vec3& wi) const {
    float pdf;
    return f_cos_pdf(wo, wi, &pdf);
  }
  RGB f_cos_pdf(const Vec3& wo, const Vec3& wi, float* pdf) const;
  // BSDF::sample_f; a sample that BSDF::sample_f would return with f = 0 (a direction the
  // geometric normal calls a transmission) is returned invalid.
  BSDFSample sample_f(const Vec3& wo, Point2 u) const;
  // sample_f's direction and pdf, and the estimator's weight f·cos/pdf in place of f and f·cos
  // (one division, not three); false where sample_f's sample is invalid. What the path tracer
  // needs of a sample, without the BSDFSample it would fill and read back.
  bool sample(const Vec3& wo, Point2 u, Vec3* wi, float* pdf, RGB* weight) const;

 private:
  // sample_f's direction in the frame (wi_local) and in the world, and its pdf; false where
  // it is invalid.
  bool draw(const Vec3& wo, Point2 u, Vec3* wi_local, Vec3* wi, float* pdf) const;

  // The clipped lobe's plane in the frame where wo is above the shading normal (BSDF's
  // clipped_lobe); false where the whole lobe is sampled.
  bool clipped(float cos_o) const { return has_horizon_ && cos_o > 0.0f; }

  Frame frame_;
  Vec3 ng_;
  RGB f_;  // the closure's weight × albedo / π
  bool has_horizon_ = false;
  CosineAbovePlane horizon_;  // the lobe above the triangle's plane (its normal in frame_)
};

// Inline: the path tracer makes one and calls them at most path vertices.
inline LoneDiffuse::LoneDiffuse(const RGB& f, const Frame& frame, const Vec3& ng,
                                const Vec3* horizon)
    : frame_(frame), ng_(ng), f_(f) {
  // BSDF::set_sampling_horizon and clipped_lobe: a plane within float noise of the frame's
  // clips nothing, nor one the frame's normal is not above.
  if (horizon && dot(*horizon, frame.n) < 1.0f - 1e-7f) {
    const Vec3 g = frame.to_local(*horizon);
    has_horizon_ = g.z > 0.0f;
    if (has_horizon_) horizon_ = CosineAbovePlane(g);
  }
}

inline RGB LoneDiffuse::f_cos_pdf(const Vec3& wo, const Vec3& wi, float* pdf) const {
  // The frame's z of each direction (Frame::to_local's third row).
  const float cos_o = dot(wo, frame_.n);
  *pdf = 0.0f;
  if (cos_o == 0.0f) return RGB(0.0f);
  const float cos_i = dot(wi, frame_.n);
  const bool same_side = cos_o * cos_i > 0.0f;
  if (clipped(cos_o)) *pdf = horizon_.pdf(frame_.to_local(wi));
  else if (same_side) *pdf = cosine_hemisphere_pdf(std::fabs(cos_i));
  // The geometric normal decides between reflection and transmission (BSDF::f).
  const bool reflects = dot(wi, ng_) * dot(wo, ng_) > 0.0f;
  return reflects && same_side ? f_ * std::fabs(cos_i) : RGB(0.0f);
}

inline bool LoneDiffuse::draw(const Vec3& wo, Point2 u, Vec3* wi_local, Vec3* wi,
                              float* pdf) const {
  const float cos_o = dot(wo, frame_.n);
  if (cos_o == 0.0f) return false;
  Vec3 local;
  if (clipped(cos_o)) {
    local = horizon_.sample(u);
    *pdf = horizon_.pdf(local);
  } else {
    local = sample_cosine_hemisphere(u);  // sample_cosine_reflection: on wo's side
    if (cos_o < 0.0f) local.z = -local.z;
    *pdf = cosine_hemisphere_pdf(std::fabs(local.z));
  }
  if (!(*pdf > 0.0f)) return false;
  *wi_local = local;
  *wi = frame_.to_world(local);
  return dot(*wi, ng_) * dot(wo, ng_) > 0.0f;
}

inline BSDFSample LoneDiffuse::sample_f(const Vec3& wo, Point2 u) const {
  BSDFSample out;
  Vec3 local;
  if (!draw(wo, u, &local, &out.wi, &out.pdf)) return BSDFSample{};
  out.f = f_;
  out.f_cos = f_ * std::fabs(local.z);
  out.flags = kReflection | kDiffuse;
  out.component = 0;
  return out;
}

inline bool LoneDiffuse::sample(const Vec3& wo, Point2 u, Vec3* wi, float* pdf,
                                RGB* weight) const {
  Vec3 local;
  if (!draw(wo, u, &local, wi, pdf)) return false;
  *weight = f_ * (std::fabs(local.z) / *pdf);
  return true;
}

}  // namespace bxdf

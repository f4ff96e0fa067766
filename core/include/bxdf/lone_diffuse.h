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

namespace bxdf {

class LoneDiffuse {
 public:
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

 private:
  // The clipped lobe's plane in the frame where wo is above the shading normal (BSDF's
  // clipped_lobe); false where the whole lobe is sampled.
  bool clipped(float cos_o) const { return has_horizon_ && cos_o > 0.0f; }

  Frame frame_;
  Vec3 ng_;
  RGB f_;  // the closure's weight × albedo / π
  bool has_horizon_ = false;
  Vec3 horizon_local_;  // the triangle's normal in frame_, where has_horizon_
};

}  // namespace bxdf

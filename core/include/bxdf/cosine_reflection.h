// Cosine-weighted sampling on wo's side of the surface: the sampler of every diffuse
// reflection model (lambertian, oren_nayar, cycles_oren_nayar). pdf = |cos θi|/π in wo's
// hemisphere, 0 in the other.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/sampling.h"

namespace bxdf {

inline float cosine_reflection_pdf(const Vec3& wo, const Vec3& wi) {
  return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(std::fabs(wi.z)) : 0.0f;
}

// `model.eval(wo, wi)` gives the sample's f, so the sample agrees with f() exactly.
template <class Model>
inline BxDFSample sample_cosine_reflection(const Model& model, const Vec3& wo, Point2 u) {
  BxDFSample s;
  if (wo.z == 0.0f) return s;
  s.wi = sample_cosine_hemisphere(u);
  if (wo.z < 0.0f) s.wi.z = -s.wi.z;
  s.pdf = cosine_hemisphere_pdf(std::fabs(s.wi.z));
  s.f = model.eval(wo, s.wi);
  s.flags = kReflection | kDiffuse;
  return s;
}

}  // namespace bxdf

// The sum of several models (a fitted diffuse + specular pair). Not a registry model: the
// registry has no way to describe a combination yet.
#pragma once

#include <vector>

#include "bxdf/bxdf.h"

namespace bxdf::fit {

class SumBxDF final : public BxDF {
 public:
  explicit SumBxDF(std::vector<BxDFPtr> parts);

  RGB f(const Vec3& wo, const Vec3& wi) const override;
  // Picks one part uniformly with u.x (remapped), averages the parts' pdfs (pbrt's BSDF).
  BxDFSample sample_f(const Vec3& wo, Point2 u) const override;
  float pdf(const Vec3& wo, const Vec3& wi) const override;

  void f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const override;
  void sample_f_batch(size_t n, DirectionsIn wo, const float* u1, const float* u2,
                      DirectionsOut wi, RGBOut f, float* pdf) const override;
  void pdf_batch(size_t n, DirectionsIn wo, DirectionsIn wi, float* out) const override;

 private:
  std::vector<BxDFPtr> parts_;
};

}  // namespace bxdf::fit

// Cycles 3.4's Transparent BSDF (closure/bsdf_transparent.h): light passes straight through,
// wi = −wo, with weight = colour. Cycles counts it as transparency rather than as a bounce;
// as a BxDF it is a delta transmission lobe (f = colour/|cos θi|, pdf 1 when sampled, f = pdf
// = 0 otherwise) that does not refract.
#pragma once

#include "bxdf/bxdf.h"
#include "bxdf/specular.h"

namespace bxdf {

class CyclesTransparent final : public BxDFImpl<CyclesTransparent> {
 public:
  explicit CyclesTransparent(const RGB& color)
      : BxDFImpl(kTransmission | kSpecular), color_(color) {}

  RGB eval(const Vec3&, const Vec3&) const { return RGB(0.0f); }
  BxDFSample sample(const Vec3& wo, Point2) const {
    BxDFSample s;
    if (std::fabs(wo.z) < kMinSpecularCos) return s;
    s.wi = -wo;
    s.pdf = 1.0f;
    s.f = color_ / std::fabs(wo.z);
    s.flags = kTransmission | kSpecular;
    return s;
  }
  float density(const Vec3&, const Vec3&) const { return 0.0f; }

  const RGB& color() const { return color_; }

  float closure_sample_weight() const override { return color_.average(); }

 private:
  RGB color_;
};

}  // namespace bxdf

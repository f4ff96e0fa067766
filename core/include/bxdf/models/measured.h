// A measured isotropic BRDF (MERL .binary or Cornell .brdf, see bxdf/measured/) as a model:
// f is the table lookup, sampling uses the tabulated importance sampler. Two-sided like the
// other reflection models: both directions below the surface are mirrored above it.
#pragma once

#include <memory>

#include "bxdf/bxdf.h"
#include "bxdf/measured/measured_data.h"

namespace bxdf {

class MeasuredBRDF final : public BxDFImpl<MeasuredBRDF> {
 public:
  MeasuredBRDF(std::shared_ptr<const MeasuredData> data, bool interpolate)
      : BxDFImpl(kReflection | kGlossy), data_(std::move(data)), interpolate_(interpolate) {}

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.0f);
    return data_->lookup(upper(wo), upper(wi), interpolate_);
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    const Vec3 wo_up = upper(wo);
    Vec3 wi = data_->sampler().sample(wo_up, u);
    if (!(wi.z > 0.0f)) return s;
    s.pdf = data_->sampler().pdf(wo_up, wi);
    s.f = data_->lookup(wo_up, wi, interpolate_);
    if (wo.z < 0.0f) wi.z = -wi.z;
    s.wi = wi;
    s.flags = kReflection | kGlossy;
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return 0.0f;
    return data_->sampler().pdf(upper(wo), upper(wi));
  }

  const MeasuredData& data() const { return *data_; }
  const std::shared_ptr<const MeasuredData>& shared_data() const { return data_; }

 private:
  static Vec3 upper(const Vec3& w) { return {w.x, w.y, std::fabs(w.z)}; }
  std::shared_ptr<const MeasuredData> data_;
  bool interpolate_;
};

}  // namespace bxdf

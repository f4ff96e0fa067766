#include "sum_bxdf.h"

namespace bxdf::fit {

namespace {
uint32_t union_flags(const std::vector<BxDFPtr>& parts) {
  uint32_t f = 0;
  for (const auto& p : parts) f |= p->flags();
  return f;
}
}  // namespace

SumBxDF::SumBxDF(std::vector<BxDFPtr> parts) : BxDF(union_flags(parts)), parts_(std::move(parts)) {}

RGB SumBxDF::f(const Vec3& wo, const Vec3& wi) const {
  RGB sum(0.0f);
  for (const auto& p : parts_) sum += p->f(wo, wi);
  return sum;
}

float SumBxDF::pdf(const Vec3& wo, const Vec3& wi) const {
  if (parts_.empty()) return 0.0f;
  float sum = 0.0f;
  for (const auto& p : parts_) sum += p->pdf(wo, wi);
  return sum / static_cast<float>(parts_.size());
}

BxDFSample SumBxDF::sample_f(const Vec3& wo, Point2 u) const {
  BxDFSample none;
  if (parts_.empty()) return none;
  const float n = static_cast<float>(parts_.size());
  const size_t k = std::min(parts_.size() - 1, static_cast<size_t>(u.x * n));
  u.x = std::min(u.x * n - static_cast<float>(k), 0x1.fffffep-1f);
  BxDFSample s = parts_[k]->sample_f(wo, u);
  if (!s.valid()) return none;
  s.f = f(wo, s.wi);
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return none;
  return s;
}

void SumBxDF::f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const {
  for (size_t i = 0; i < n; ++i) {
    const RGB v = f(Vec3(wo.x[i], wo.y[i], wo.z[i]), Vec3(wi.x[i], wi.y[i], wi.z[i]));
    out.r[i] = v.r;
    out.g[i] = v.g;
    out.b[i] = v.b;
  }
}

void SumBxDF::sample_f_batch(size_t n, DirectionsIn wo, const float* u1, const float* u2,
                             DirectionsOut wi, RGBOut f, float* pdf) const {
  for (size_t i = 0; i < n; ++i) {
    const BxDFSample s = sample_f(Vec3(wo.x[i], wo.y[i], wo.z[i]), Point2(u1[i], u2[i]));
    wi.x[i] = s.wi.x;
    wi.y[i] = s.wi.y;
    wi.z[i] = s.wi.z;
    f.r[i] = s.f.r;
    f.g[i] = s.f.g;
    f.b[i] = s.f.b;
    pdf[i] = s.pdf;
  }
}

void SumBxDF::pdf_batch(size_t n, DirectionsIn wo, DirectionsIn wi, float* out) const {
  for (size_t i = 0; i < n; ++i)
    out[i] = pdf(Vec3(wo.x[i], wo.y[i], wo.z[i]), Vec3(wi.x[i], wi.y[i], wi.z[i]));
}

}  // namespace bxdf::fit

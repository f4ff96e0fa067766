// The BxDF interface (the seed's f / Sample_f / Pdf / rho), its flags, and BxDFImpl, the
// CRTP layer that turns a model's three inline kernels into the robust scalar API and the
// batch (structure-of-arrays) API with one virtual call per batch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "bxdf/frame.h"
#include "bxdf/params.h"
#include "bxdf/spectrum.h"

namespace bxdf {

enum BxDFFlags : uint32_t {
  kReflection = 1u << 0,
  kTransmission = 1u << 1,
  kDiffuse = 1u << 2,
  kGlossy = 1u << 3,
  kSpecular = 1u << 4,
  kAllTypes = kDiffuse | kGlossy | kSpecular,
  kAll = kReflection | kTransmission | kAllTypes,
};

// What sample_f returns. pdf == 0 means no sample (f is then 0 and wi undefined).
struct BxDFSample {
  RGB f;
  Vec3 wi;
  float pdf = 0.0f;
  uint32_t flags = 0;  // the lobe that was sampled (e.g. reflection|specular)
  bool valid() const { return pdf > 0.0f; }
};

// Structure-of-arrays views over a batch of directions or colours.
struct DirectionsIn {
  const float* x;
  const float* y;
  const float* z;
};
struct DirectionsOut {
  float* x;
  float* y;
  float* z;
};
struct RGBOut {
  float* r;
  float* g;
  float* b;
};

class BxDF {
 public:
  explicit BxDF(uint32_t flags) : flags_(flags) {}
  virtual ~BxDF() = default;
  BxDF(const BxDF&) = delete;
  BxDF& operator=(const BxDF&) = delete;

  uint32_t flags() const { return flags_; }
  // True when every flag of this BxDF is in `mask` (pbrt's MatchesFlags).
  bool matches(uint32_t mask) const { return (flags_ & mask) == flags_; }
  bool is_delta() const { return (flags_ & (kDiffuse | kGlossy)) == 0 && (flags_ & kSpecular); }

  // Directions in the local frame, both pointing away from the surface, of any length;
  // a zero or non-finite direction gives 0. Never NaN, Inf or negative.
  virtual RGB f(const Vec3& wo, const Vec3& wi) const = 0;
  virtual BxDFSample sample_f(const Vec3& wo, Point2 u) const = 0;
  virtual float pdf(const Vec3& wo, const Vec3& wi) const = 0;

  // ρhd(wo) = ∫ f |cos θi| dωi and ρhh; Monte Carlo (stratified, seeded) unless a model knows better.
  virtual RGB rho_hd(const Vec3& wo, int n_samples, uint64_t seed = 0) const;
  virtual RGB rho_hh(int n_samples, uint64_t seed = 0) const;

  // Batch forms: n directions as separate x/y/z arrays. Same results as the scalar calls.
  virtual void f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const = 0;
  virtual void sample_f_batch(size_t n, DirectionsIn wo, const float* u1, const float* u2,
                              DirectionsOut wi, RGBOut f, float* pdf) const = 0;
  virtual void pdf_batch(size_t n, DirectionsIn wo, DirectionsIn wi, float* out) const = 0;

  // The registry name and validated parameters that rebuild this model (set by make()).
  const std::string& model_name() const { return model_name_; }
  const ParamSet& params() const { return params_; }
  void set_identity(std::string name, ParamSet params) {
    model_name_ = std::move(name);
    params_ = std::move(params);
  }

 private:
  uint32_t flags_;
  std::string model_name_;
  ParamSet params_;
};

std::string flags_to_string(uint32_t flags);  // "reflection|glossy"

// Derived implements, inline and assuming unit-length directions:
//   RGB eval(const Vec3& wo, const Vec3& wi) const;
//   BxDFSample sample(const Vec3& wo, Point2 u) const;
//   float density(const Vec3& wo, const Vec3& wi) const;
// BxDFImpl normalises inputs, refuses degenerate ones and scrubs every output, so a kernel
// only has to be right for well-formed input.
template <class Derived>
class BxDFImpl : public BxDF {
 public:
  using BxDF::BxDF;

  RGB f(const Vec3& wo, const Vec3& wi) const final { return f_one(wo, wi); }
  BxDFSample sample_f(const Vec3& wo, Point2 u) const final { return sample_one(wo, u); }
  float pdf(const Vec3& wo, const Vec3& wi) const final { return pdf_one(wo, wi); }

  void f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const final {
    for (size_t i = 0; i < n; ++i) {
      const RGB v = f_one(Vec3(wo.x[i], wo.y[i], wo.z[i]), Vec3(wi.x[i], wi.y[i], wi.z[i]));
      out.r[i] = v.r;
      out.g[i] = v.g;
      out.b[i] = v.b;
    }
  }
  void sample_f_batch(size_t n, DirectionsIn wo, const float* u1, const float* u2,
                      DirectionsOut wi, RGBOut f, float* pdf) const final {
    for (size_t i = 0; i < n; ++i) {
      const BxDFSample s = sample_one(Vec3(wo.x[i], wo.y[i], wo.z[i]), Point2(u1[i], u2[i]));
      wi.x[i] = s.wi.x;
      wi.y[i] = s.wi.y;
      wi.z[i] = s.wi.z;
      f.r[i] = s.f.r;
      f.g[i] = s.f.g;
      f.b[i] = s.f.b;
      pdf[i] = s.pdf;
    }
  }
  void pdf_batch(size_t n, DirectionsIn wo, DirectionsIn wi, float* out) const final {
    for (size_t i = 0; i < n; ++i)
      out[i] = pdf_one(Vec3(wo.x[i], wo.y[i], wo.z[i]), Vec3(wi.x[i], wi.y[i], wi.z[i]));
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }

  inline RGB f_one(Vec3 wo, Vec3 wi) const {
    if (!normalize_direction(wo) || !normalize_direction(wi)) return RGB(0.0f);
    return sanitize_nonnegative(derived().eval(wo, wi));
  }
  inline float pdf_one(Vec3 wo, Vec3 wi) const {
    if (!normalize_direction(wo) || !normalize_direction(wi)) return 0.0f;
    return sanitize_nonnegative(derived().density(wo, wi));
  }
  inline BxDFSample sample_one(Vec3 wo, Point2 u) const {
    BxDFSample none;
    if (!normalize_direction(wo)) return none;
    // Keep u in [0, 1): NaN or out-of-range numbers would otherwise leak into the warps.
    if (!(u.x >= 0.0f && u.x < 1.0f)) u.x = u.x >= 1.0f ? 0x1.fffffep-1f : 0.0f;
    if (!(u.y >= 0.0f && u.y < 1.0f)) u.y = u.y >= 1.0f ? 0x1.fffffep-1f : 0.0f;
    BxDFSample s = derived().sample(wo, u);
    if (!(s.pdf > 0.0f) || !finite_nonnegative(s.pdf) || !normalize_direction(s.wi) ||
        !finite_nonnegative(s.f))
      return none;
    return s;
  }
};

// Result type of make(): models are immutable once built, so they are shared freely.
using BxDFPtr = std::shared_ptr<const BxDF>;

}  // namespace bxdf

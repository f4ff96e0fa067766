// Lafortune et al. 1997 generalised cosine lobes:
// f = ρd/π + Σ_lobes max(0, Cx ωo.x ωi.x + Cy ωo.y ωi.y + Cz ωo.z ωi.z)^n, per RGB channel.
// Cx = Cy = −1, Cz = 1 is a Phong lobe about the mirror direction, Cx, Cy > 0 retro-reflection;
// a lobe's scale is in C (its peak is at most max|C|^n). Not energy-conserving in general.
//
// Sampling: a mixture of cosine-weighted sampling (the diffuse part) and one cosine-power lobe
// per Lafortune lobe, of the channel-averaged exponent n̄, about normalize(C̄ ⊙ ωo) (C̄ the
// channel-averaged coefficients), reflected into ωo's hemisphere. A lobe sample that falls
// below the horizon is folded back (z mirrored), so no sample is wasted and each lobe's density
// is the sum of its cosine-power density at ωi and at ωi's mirror image. The mixture weights
// are fixed at construction; pdf is the mixture's density, so sample_f and pdf agree.
#pragma once

#include <vector>

#include "bxdf/bxdf.h"
#include "bxdf/sampling.h"

namespace bxdf {

struct LafortuneLobe {
  RGB cx, cy, cz, exponent;
};

class Lafortune final : public BxDFImpl<Lafortune> {
 public:
  // Throws ParameterError when a lobe could overflow: max(|cx|, |cy|, |cz|)^exponent > kMaxPeak.
  Lafortune(const RGB& diffuse, std::vector<LafortuneLobe> lobes);

  static constexpr double kMaxPeak = 1e20;
  // The cosine-weighted part always keeps this share of the samples, so that the mixture's pdf
  // is positive wherever f is (a lobe's sampling axis can differ from where it is non-zero).
  static constexpr float kMinDiffuseProbability = 0.1f;

  RGB eval(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.0f);
    RGB f = diffuse_over_pi_;
    for (const Lobe& l : lobes_) f += lobe_value(l.shape, wo, wi);
    return f;
  }

  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    if (wo.z == 0.0f) return s;
    if (u.x < diffuse_probability_) {
      s.wi = sample_cosine_hemisphere(Point2(u.x / diffuse_probability_, u.y));
      if (wo.z < 0.0f) s.wi.z = -s.wi.z;
      s.flags = kReflection | kDiffuse;
    } else {
      // The first lobe whose slice [cdf_lo, cdf_hi) of [diffuse_probability, 1) holds u.x;
      // u.x is then reused, rescaled to [0, 1), for the lobe's own warp.
      size_t j = 0;
      while (j + 1 < lobes_.size() && !(u.x < lobes_[j].cdf_hi)) ++j;
      const Lobe& l = lobes_[j];
      const float u0 = clamp((u.x - l.cdf_lo) / l.probability, 0.0f, 0x1.fffffep-1f);
      const Vec3 axis = sampling_axis(l, wo);
      Vec3 t1, t2;
      coordinate_system(axis, &t1, &t2);
      const Vec3 local = sample_cosine_power(Point2(u0, u.y), l.mean_exponent);
      s.wi = t1 * local.x + t2 * local.y + axis * local.z;
      s.wi.z = wo.z > 0.0f ? std::fabs(s.wi.z) : -std::fabs(s.wi.z);  // fold into wo's side
      s.flags = kReflection | kGlossy;
    }
    s.pdf = density(wo, s.wi);
    s.f = eval(wo, s.wi);
    return s;
  }

  float density(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return 0.0f;
    float pdf = diffuse_probability_ * cosine_hemisphere_pdf(std::fabs(wi.z));
    const Vec3 wi_folded(wi.x, wi.y, -wi.z);  // where a folded sample came from
    for (const Lobe& l : lobes_) {
      const Vec3 axis = sampling_axis(l, wo);
      pdf += l.probability * (cosine_power_pdf(dot(axis, wi), l.mean_exponent) +
                              cosine_power_pdf(dot(axis, wi_folded), l.mean_exponent));
    }
    return pdf;
  }

  // The share of samples each part gets: the diffuse part, then lobe by lobe.
  float diffuse_probability() const { return diffuse_probability_; }
  float lobe_probability(size_t j) const { return lobes_[j].probability; }

 private:
  struct Lobe {
    LafortuneLobe shape;
    Vec3 mean_c;              // C̄: the channel averages of cx, cy, cz
    float mean_exponent = 0;  // n̄
    // This lobe is chosen for u.x in [cdf_lo, cdf_hi); probability = cdf_hi − cdf_lo.
    float cdf_lo = 0, cdf_hi = 0, probability = 0;
  };

  static RGB lobe_value(const LafortuneLobe& l, const Vec3& wo, const Vec3& wi) {
    const float px = wo.x * wi.x, py = wo.y * wi.y, pz = wo.z * wi.z;
    RGB v;
    for (int c = 0; c < 3; ++c) {
      const float d = l.cx[c] * px + l.cy[c] * py + l.cz[c] * pz;
      // d > 0 first: max(0, d)^0 would otherwise be pow(0, 0) = 1 where the lobe is off.
      v[c] = d > 0.0f ? std::pow(d, l.exponent[c]) : 0.0f;
    }
    return v;
  }

  // normalize(C̄ ⊙ ωo) flipped into ωo's hemisphere; the normal when C̄ ⊙ ωo vanishes.
  static Vec3 sampling_axis(const Lobe& l, const Vec3& wo) {
    Vec3 a(l.mean_c.x * wo.x, l.mean_c.y * wo.y, l.mean_c.z * wo.z);
    if (!normalize_direction(a)) return Vec3(0.0f, 0.0f, wo.z > 0.0f ? 1.0f : -1.0f);
    if (a.z * wo.z < 0.0f) a.z = -a.z;
    return a;
  }

  RGB diffuse_over_pi_;
  std::vector<Lobe> lobes_;
  float diffuse_probability_ = 1.0f;
};

}  // namespace bxdf

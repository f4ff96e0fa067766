// Cosine lobes clipped at the triangle's plane (cosine_above_plane.h, BSDF::set_sampling_horizon):
// the sampler follows its pdf (χ²), never goes below the plane, keeps the lobe's expectation,
// and a BSDF without a tilted horizon samples exactly as before.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/bsdf.h"
#include "bxdf/cosine_above_plane.h"
#include "bxdf/models/lambertian.h"
#include "bxdf/models/oren_nayar.h"
#include "bxdf/rng.h"
#include "sphere_chi2.h"

using namespace bxdf;
using namespace bxdf::test;

namespace {

Vec3 tilted_normal(float degrees, float azimuth_degrees) {
  const float d = degrees * kPi / 180.0f, a = azimuth_degrees * kPi / 180.0f;
  return Vec3(std::sin(d) * std::cos(a), std::sin(d) * std::sin(a), std::cos(d));
}

// The clipped sampler as a model, so that the χ² harness can judge it: f is its own pdf.
class ClippedCosineLobe final : public BxDFImpl<ClippedCosineLobe> {
 public:
  explicit ClippedCosineLobe(const Vec3& g) : BxDFImpl(kReflection | kDiffuse), g_(g) {}
  RGB eval(const Vec3& wo, const Vec3& wi) const { return RGB(density(wo, wi)); }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    if (!(wo.z > 0.0f)) return s;
    s.wi = sample_cosine_above_plane(u, g_);
    s.pdf = density(wo, s.wi);
    s.f = RGB(s.pdf);
    s.flags = kReflection | kDiffuse;
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    return wo.z > 0.0f ? cosine_above_plane_pdf(wi, g_) : 0.0f;
  }

 private:
  Vec3 g_;
};

}  // namespace

TEST(CosineAbovePlane, SamplesFollowTheirPdf) {
  // A strong tilt, so that the squeezed half and the cut-off sliver span many cells.
  for (const Vec3& g : {tilted_normal(35.0f, 20.0f), tilted_normal(8.0f, 200.0f)}) {
    const ClippedCosineLobe lobe(g);
    Chi2Config config;
    config.samples = 400000;
    const Chi2Result r = run_chi2(lobe, Vec3(0.3f, 0.1f, 0.9f), config);
    EXPECT_TRUE(r.hard_failure.empty()) << r.hard_failure;
    EXPECT_GT(r.p_value, 1e-3) << r.statistic << " dof " << r.dof << r.worst_cells;
    EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3);
  }
}

TEST(CosineAbovePlane, NoSampleFallsBelowThePlaneAndTheLostPartIsHalfOneMinusCos) {
  const Vec3 g = tilted_normal(20.0f, 75.0f);
  PCG32 rng(7);
  int squeezed = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const Vec3 wi = sample_cosine_above_plane(Point2(rng.uniform(), rng.uniform()), g);
    ASSERT_GE(dot(wi, g), -1e-6f);
    ASSERT_GE(wi.z, 0.0f);
    if (cosine_above_plane_pdf(wi, g) > cosine_hemisphere_pdf(wi.z) * 1.0001f) ++squeezed;
  }
  EXPECT_NEAR(double(squeezed) / n, 0.5, 0.005);  // half the disk is squeezed
  // The plain lobe's share below the plane, by Monte Carlo, against (1 − cos δ)/2.
  int lost = 0;
  for (int i = 0; i < n; ++i)
    if (dot(sample_cosine_hemisphere(Point2(rng.uniform(), rng.uniform())), g) <= 0.0f) ++lost;
  EXPECT_NEAR(double(lost) / n, 0.5 * (1.0 - g.z), 0.002);
}

TEST(CosineAbovePlane, BsdfSamplesAboveTheHorizonWithTheLobesExpectation) {
  const Lambertian lambert(RGB(0.8f));
  const OrenNayar oren_nayar(RGB(0.6f), 30.0f);
  const Frame shading = Frame::from_normal(normalize(Vec3(0.1f, -0.2f, 1.0f)));
  const Vec3 ng = normalize(shading.n + Vec3(0.15f, 0.05f, 0.0f));
  const Vec3 wo = normalize(Vec3(0.2f, 0.3f, 1.0f));
  for (const BxDF* model : {static_cast<const BxDF*>(&lambert),
                            static_cast<const BxDF*>(&oren_nayar)}) {
    BSDF clipped(shading, shading.n), plain(shading, shading.n);
    clipped.add(model);
    plain.add(model);
    clipped.set_sampling_horizon(ng);
    PCG32 rng(3);
    double clipped_sum = 0.0, plain_sum = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      const Point2 u(rng.uniform(), rng.uniform());
      const BSDFSample s = clipped.sample_f(wo, u);
      ASSERT_TRUE(s.valid());
      ASSERT_GT(dot(s.wi, ng), -1e-6f);
      // The pdf the integrator's MIS reads is the density the direction was drawn with.
      ASSERT_NEAR(clipped.pdf(wo, s.wi), s.pdf, 1e-4f * s.pdf);
      clipped_sum += s.f_cos.r / s.pdf;
      const BSDFSample p = plain.sample_f(wo, u);
      // What a surface can reflect: the plain lobe's samples below the plane are lost.
      if (p.valid() && dot(p.wi, ng) > 0.0f) plain_sum += p.f_cos.r / p.pdf;
    }
    EXPECT_NEAR(clipped_sum / n, plain_sum / n, 0.004 * plain_sum / n);
  }
  // Lambertian: every clipped sample weighs R or R·cos δ, so the lobe above the plane is
  // R (1 + cos δ)/2 with almost no noise.
  BSDF clipped(shading, shading.n);
  clipped.add(&lambert);
  clipped.set_sampling_horizon(ng);
  const float cos_delta = dot(ng, shading.n);
  PCG32 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const BSDFSample s = clipped.sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    const float w = s.f_cos.r / s.pdf;
    EXPECT_TRUE(std::fabs(w - 0.8f) < 1e-4f || std::fabs(w - 0.8f * cos_delta) < 1e-4f) << w;
  }
}

TEST(CosineAbovePlane, HorizonOfTheShadingPlaneChangesNoSample) {
  const Lambertian lambert(RGB(0.5f));
  const Frame shading = Frame::from_normal(normalize(Vec3(0.3f, 0.1f, 1.0f)));
  BSDF with(shading, shading.n), without(shading, shading.n);
  with.add(&lambert);
  without.add(&lambert);
  with.set_sampling_horizon(shading.n);
  const Vec3 wo = normalize(Vec3(-0.2f, 0.4f, 1.0f));
  PCG32 rng(11);
  for (int i = 0; i < 1000; ++i) {
    const Point2 u(rng.uniform(), rng.uniform());
    const BSDFSample a = with.sample_f(wo, u), b = without.sample_f(wo, u);
    ASSERT_EQ(a.wi.x, b.wi.x);
    ASSERT_EQ(a.wi.y, b.wi.y);
    ASSERT_EQ(a.wi.z, b.wi.z);
    ASSERT_EQ(a.pdf, b.pdf);
  }
}

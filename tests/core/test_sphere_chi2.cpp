// The χ² harness must pass a correct sampler and catch wrong ones: test-only models whose
// sample_f and pdf disagree in various ways.
#include <gtest/gtest.h>

#include "bxdf/models/lambertian.h"
#include "bxdf/sampling.h"
#include "sphere_chi2.h"

using namespace bxdf;
using namespace bxdf::test;

namespace {

// Samples cos^n θ lobes about +z on wo's side; claims the pdf of exponent `claimed`, scaled.
class PowerLobe final : public BxDFImpl<PowerLobe> {
 public:
  PowerLobe(float sampled, float claimed, float pdf_scale = 1.0f, bool mirror_samples = false)
      : BxDFImpl(kReflection | kGlossy), sampled_(sampled), claimed_(claimed), scale_(pdf_scale),
        mirror_(mirror_samples) {}
  RGB eval(const Vec3& wo, const Vec3& wi) const { return RGB(density(wo, wi)); }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    s.wi = sample_cosine_power(u, sampled_);
    if ((wo.z < 0.0f) != mirror_) s.wi.z = -s.wi.z;  // mirror_: into the wrong hemisphere
    s.pdf = density(wo, s.wi);
    if (mirror_) s.pdf = 1.0f;
    s.f = RGB(s.pdf);
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    if (!same_hemisphere(wo, wi)) return 0.0f;
    return scale_ * cosine_power_pdf(std::fabs(wi.z), claimed_);
  }

 private:
  float sampled_, claimed_, scale_;
  bool mirror_;
};

Chi2Config small_config() {
  Chi2Config c;
  c.samples = 200000;
  return c;
}

}  // namespace

TEST(SphereChi2, CorrectSamplersPass) {
  const Lambertian lambert(RGB(0.5f));
  const PowerLobe lobe(30.0f, 30.0f);
  for (const Vec3& wo : {Vec3(0, 0, 1), Vec3(0.6f, 0.0f, -0.8f)}) {
    for (const BxDF* m : {static_cast<const BxDF*>(&lambert), static_cast<const BxDF*>(&lobe)}) {
      const Chi2Result r = run_chi2(*m, wo, small_config());
      EXPECT_TRUE(r.hard_failure.empty()) << r.hard_failure;
      EXPECT_GT(r.p_value, 1e-3) << r.statistic << " dof " << r.dof << r.worst_cells;
      EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3);
      EXPECT_GT(r.dof, 100);
    }
  }
}

TEST(SphereChi2, SlightlyWrongPdfFails) {
  // Sampling cos^30 but claiming cos^31: a 3% change of lobe width.
  const Chi2Result r = run_chi2(PowerLobe(30.0f, 31.0f), Vec3(0, 0, 1), Chi2Config());
  EXPECT_TRUE(r.hard_failure.empty()) << r.hard_failure;
  EXPECT_LT(r.p_value, 1e-6) << r.statistic << " dof " << r.dof;
}

TEST(SphereChi2, PdfThatIntegratesAbove1Point1Fails) {
  const Chi2Result r = run_chi2(PowerLobe(5.0f, 5.0f, 1.2f), Vec3(0, 0, 1), small_config());
  EXPECT_NE(r.hard_failure.find("pdf integrates"), std::string::npos) << r.hard_failure;
}

TEST(SphereChi2, SamplesWherePdfIsZeroFail) {
  const Chi2Result r = run_chi2(PowerLobe(5.0f, 5.0f, 1.0f, true), Vec3(0, 0, 1), small_config());
  EXPECT_NE(r.hard_failure.find("pdf integrates to 0"), std::string::npos) << r.hard_failure;
}

TEST(SphereChi2, PdfTooSmallByAFewPercentFails) {
  const Chi2Result r = run_chi2(PowerLobe(5.0f, 5.0f, 0.97f), Vec3(0, 0, 1), Chi2Config());
  EXPECT_LT(r.p_value, 1e-6) << r.statistic << " dof " << r.dof;
}

TEST(SphereChi2, QuadratureAlbedoOfLambertIsR) {
  const Lambertian lambert(RGB(0.2f, 0.5f, 1.0f));
  for (const Vec3& wo : {Vec3(0, 0, 1), Vec3(0.6f, 0.0f, -0.8f)}) {
    const RGB a = quadrature_albedo(lambert, wo).reflected;
    EXPECT_TRUE(quadrature_albedo(lambert, wo).transmitted.is_black());
    EXPECT_NEAR(a.r, 0.2f, 2e-4f);
    EXPECT_NEAR(a.g, 0.5f, 5e-4f);
    EXPECT_NEAR(a.b, 1.0f, 1e-3f);
  }
}

// LoneDiffuse: the path tracer's shortcut for a BSDF of one constant diffuse closure gives what
// the BSDF itself gives (f·cos, pdf, samples) on every kind of direction pair, with and without
// the triangle's plane clipping the lobe, and is refused for every other BSDF.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/lone_diffuse.h"
#include "bxdf/models/cycles_oren_nayar.h"
#include "bxdf/models/lambertian.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

constexpr float kTolerance = 2e-5f;

void expect_close(const RGB& a, const RGB& b, const char* what) {
  const float scale = std::max(1.0f, std::max(a.max_component(), b.max_component()));
  EXPECT_NEAR(a.r, b.r, kTolerance * scale) << what;
  EXPECT_NEAR(a.g, b.g, kTolerance * scale) << what;
  EXPECT_NEAR(a.b, b.b, kTolerance * scale) << what;
}

Vec3 random_direction(PCG32& rng) {
  return sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
}

// A shading frame tilted from the geometric normal, as on a smooth-shaded triangle; the
// BSDF as the path tracer builds it (opaque: the horizon is the geometric normal).
struct Surface {
  Frame frame;
  Vec3 ng;
  BSDF bsdf;
  Surface(const Vec3& shading_normal, const Vec3& geometric_normal, bool horizon)
      : frame(Frame::from_normal(shading_normal)),
        ng(geometric_normal),
        bsdf(frame, frame.n) {
    if (horizon) bsdf.set_sampling_horizon(ng);
  }
};

// Compares LoneDiffuse with the BSDF it stands for over random pairs and samples.
void expect_agreement(const BxDF& model, const RGB& weight, bool defensive, const Vec3& ns,
                      const Vec3& ng, bool horizon) {
  Surface s(ns, ng, horizon);
  s.bsdf.add(&model, weight);
  if (defensive) s.bsdf.use_defensive_sampling();
  LoneDiffuse lone;
  ASSERT_TRUE(LoneDiffuse::of(s.bsdf, &lone));
  // Built from the parts, without the BSDF, it is the same.
  LoneDiffuse from_parts;
  ASSERT_TRUE(LoneDiffuse::of(model, weight, s.frame, s.frame.n, horizon ? &ng : nullptr,
                              &from_parts));
  PCG32 rng(7, 11);
  int sampled = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 wo = random_direction(rng), wi = random_direction(rng);
    float pdf_bsdf = 0.0f, pdf_lone = 0.0f, pdf_parts = 0.0f;
    const RGB f_bsdf = s.bsdf.f_cos_pdf(wo, wi, &pdf_bsdf);
    const RGB f_lone = lone.f_cos_pdf(wo, wi, &pdf_lone);
    expect_close(f_lone, f_bsdf, "f_cos_pdf's f·cos");
    EXPECT_NEAR(pdf_lone, pdf_bsdf, kTolerance * std::max(1.0f, pdf_bsdf)) << "pdf";
    expect_close(lone.f_cos(wo, wi), s.bsdf.f_cos(wo, wi), "f_cos");
    expect_close(from_parts.f_cos_pdf(wo, wi, &pdf_parts), f_lone, "from parts");
    EXPECT_EQ(pdf_parts, pdf_lone);

    const Point2 u(rng.uniform(), rng.uniform());
    const BSDFSample a = s.bsdf.sample_f(wo, u);
    const BSDFSample b = lone.sample_f(wo, u);
    // The BSDF returns a sample with f = 0 where the geometric normal calls the drawn
    // direction a transmission; LoneDiffuse returns none: the path ends either way.
    const bool a_counts = a.valid() && !a.f.is_black();
    ASSERT_EQ(b.valid(), a_counts) << "wo " << wo.x << " " << wo.y << " " << wo.z;
    // The path tracer's form of the same sample: its direction and pdf, and f·cos/pdf.
    Vec3 wi_c;
    float pdf_c = 0.0f;
    RGB weight_c;
    ASSERT_EQ(lone.sample(wo, u, &wi_c, &pdf_c, &weight_c), b.valid());
    if (!b.valid()) continue;
    EXPECT_EQ(wi_c, b.wi);
    EXPECT_EQ(pdf_c, b.pdf);
    expect_close(weight_c, b.f_cos / b.pdf, "sample()'s weight");
    ++sampled;
    // The BSDF stretches u.x back from its component's slot ((u.x w)/w), which can move it
    // by an ulp: the directions agree to rounding.
    EXPECT_NEAR(b.wi.x, a.wi.x, 1e-4f);
    EXPECT_NEAR(b.wi.y, a.wi.y, 1e-4f);
    EXPECT_NEAR(b.wi.z, a.wi.z, 1e-4f);
    EXPECT_NEAR(b.pdf, a.pdf, 1e-3f * a.pdf);
    expect_close(b.f, a.f, "sample f");
    expect_close(b.f_cos / b.pdf, a.f_cos / a.pdf, "sample weight");
    EXPECT_EQ(b.flags, a.flags);
    EXPECT_EQ(b.component, 0);
  }
  EXPECT_GT(sampled, 1000);
}

}  // namespace

TEST(LoneDiffuse, AgreesWithTheBSDF) {
  const Lambertian lambert(RGB(0.7f, 0.4f, 0.2f));
  const CyclesOrenNayar diffuse_node(RGB(0.3f, 0.6f, 0.9f), 0.0f);
  const Vec3 up(0, 0, 1);
  Vec3 tilted(0.3f, -0.2f, 0.93f);
  normalize_direction(tilted);
  for (const BxDF* model : {static_cast<const BxDF*>(&lambert),
                            static_cast<const BxDF*>(&diffuse_node)}) {
    for (bool defensive : {false, true}) {
      SCOPED_TRACE(defensive ? "defensive" : "by weight");
      expect_agreement(*model, RGB(1.0f), defensive, up, up, true);  // flat: nothing clipped
      expect_agreement(*model, RGB(0.5f, 0.25f, 1.0f), defensive, tilted, up, true);
      expect_agreement(*model, RGB(1.0f), defensive, tilted, up, false);  // no horizon set
      expect_agreement(*model, RGB(1.0f), defensive, up, tilted, true);
    }
  }
}

TEST(LoneDiffuse, IsOnlyTheLoneConstantDiffuseClosure) {
  const Lambertian lambert(RGB(0.5f));
  const Lambertian black(RGB(0.0f));
  const CyclesOrenNayar rough(RGB(0.5f), 0.5f);
  LoneDiffuse lone;
  {
    Surface s(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
    EXPECT_FALSE(LoneDiffuse::of(s.bsdf, &lone)) << "no component";
    s.bsdf.add(&lambert);
    s.bsdf.add(&lambert);
    EXPECT_FALSE(LoneDiffuse::of(s.bsdf, &lone)) << "two components";
  }
  {
    Surface s(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
    s.bsdf.add(&rough);
    EXPECT_FALSE(LoneDiffuse::of(s.bsdf, &lone)) << "Oren-Nayar with roughness";
  }
  {
    Surface s(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
    s.bsdf.add(&black);
    EXPECT_FALSE(LoneDiffuse::of(s.bsdf, &lone)) << "a zero sample weight";
  }
  {
    Surface s(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
    const Frame bumped = Frame::from_normal(Vec3(0.6f, 0.0f, 0.8f));
    s.bsdf.add(&lambert, RGB(1.0f), &bumped, true);
    EXPECT_FALSE(LoneDiffuse::of(s.bsdf, &lone)) << "a perturbed normal";
  }
}

// The BSDF: frame changes, reflection vs transmission by the geometric normal, component
// selection and remapping, summed f / averaged pdf, flag masks and delta lobes.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/bsdf.h"
#include "bxdf/models/lambertian.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

// A perfect mirror with reflectance R: a delta lobe for the selection and pdf tests.
class TestMirror final : public BxDFImpl<TestMirror> {
 public:
  explicit TestMirror(RGB r) : BxDFImpl(kReflection | kSpecular), r_(r) {}
  RGB eval(const Vec3&, const Vec3&) const { return RGB(0.0f); }
  BxDFSample sample(const Vec3& wo, Point2) const {
    BxDFSample s;
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.pdf = 1.0f;
    s.f = r_ / std::fabs(s.wi.z);
    s.flags = kReflection | kSpecular;
    return s;
  }
  float density(const Vec3&, const Vec3&) const { return 0.0f; }

 private:
  RGB r_;
};

// Diffuse transmission T/π into the opposite hemisphere.
class TestDiffuseTransmission final : public BxDFImpl<TestDiffuseTransmission> {
 public:
  explicit TestDiffuseTransmission(RGB t) : BxDFImpl(kTransmission | kDiffuse), t_(t * kInvPi) {}
  RGB eval(const Vec3& wo, const Vec3& wi) const {
    return same_hemisphere(wo, wi) ? RGB(0.0f) : t_;
  }
  BxDFSample sample(const Vec3& wo, Point2 u) const {
    BxDFSample s;
    s.wi = sample_cosine_hemisphere(u);
    if (wo.z > 0.0f) s.wi.z = -s.wi.z;
    s.pdf = cosine_hemisphere_pdf(std::fabs(s.wi.z));
    s.f = t_;
    s.flags = kTransmission | kDiffuse;
    return s;
  }
  float density(const Vec3& wo, const Vec3& wi) const {
    return same_hemisphere(wo, wi) ? 0.0f : cosine_hemisphere_pdf(std::fabs(wi.z));
  }

 private:
  RGB t_;
};

// A tilted shading frame, so that world and local directions differ.
Frame tilted_frame() {
  return Frame::from_normal(normalize(Vec3(0.3f, -0.2f, 0.9f)));
}

void expect_rgb_near(const RGB& a, const RGB& b, float tol) {
  EXPECT_NEAR(a.r, b.r, tol);
  EXPECT_NEAR(a.g, b.g, tol);
  EXPECT_NEAR(a.b, b.b, tol);
}

}  // namespace

TEST(BSDF, WorldAndLocalRoundTrip) {
  const Frame fr = tilted_frame();
  const BSDF bsdf(fr, fr.n);
  const Vec3 v = normalize(Vec3(0.1f, 0.7f, -0.4f));
  const Vec3 back = bsdf.to_world(bsdf.to_local(v));
  EXPECT_NEAR(back.x, v.x, 1e-6f);
  EXPECT_NEAR(back.y, v.y, 1e-6f);
  EXPECT_NEAR(back.z, v.z, 1e-6f);
  EXPECT_NEAR(bsdf.to_local(fr.n).z, 1.0f, 1e-6f);
}

TEST(BSDF, SingleLambertianMatchesTheModelInWorldSpace) {
  const Lambertian lam(RGB(0.5f, 0.6f, 0.7f));
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(&lam);
  const Vec3 wo = normalize(fr.n + fr.s * 0.5f), wi = normalize(fr.n - fr.t * 0.8f);
  expect_rgb_near(bsdf.f(wo, wi), RGB(0.5f, 0.6f, 0.7f) * kInvPi, 1e-6f);
  EXPECT_NEAR(bsdf.pdf(wo, wi), dot(wi, fr.n) * kInvPi, 1e-6f);
}

TEST(BSDF, GeometricNormalDecidesReflectionVersusTransmission) {
  // Shading normal tilted away from the geometric normal: wi is above the shading surface but
  // below the geometric one, so a reflection-only BSDF must give 0 there (no light leak)...
  const Vec3 ng(0, 0, 1);
  const Frame shading = Frame::from_normal(normalize(Vec3(0.6f, 0.0f, 0.8f)));
  const Lambertian lam(RGB(0.8f));
  BSDF reflect_only(shading, ng);
  reflect_only.add(&lam);
  const Vec3 wo = normalize(Vec3(0.0f, 0.3f, 1.0f));
  const Vec3 wi = normalize(Vec3(1.0f, 0.0f, -0.2f));
  ASSERT_GT(dot(wi, shading.n), 0.0f);
  ASSERT_LT(dot(wi, ng), 0.0f);
  EXPECT_TRUE(reflect_only.f(wo, wi).is_black());
  // ...and a transmission component is asked instead, even though the local directions are in
  // the same shading hemisphere (so it answers 0 as well: nothing is counted twice).
  const TestDiffuseTransmission trans(RGB(0.5f));
  BSDF both(shading, ng);
  both.add(&lam);
  both.add(&trans);
  EXPECT_TRUE(both.f(wo, wi).is_black());
  // A true transmission pair gets only the transmission component.
  const Vec3 below = normalize(Vec3(-0.2f, 0.1f, -1.0f));
  ASSERT_LT(dot(below, shading.n), 0.0f);
  expect_rgb_near(both.f(wo, below), RGB(0.5f * kInvPi), 1e-6f);
}

TEST(BSDF, SumsFAndAveragesPdfOverComponents) {
  const Lambertian a(RGB(0.2f, 0.3f, 0.4f));
  const Lambertian b(RGB(0.5f, 0.1f, 0.0f));
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(&a);
  bsdf.add(&b);
  EXPECT_EQ(bsdf.num_components(), 2);
  const Vec3 wo = normalize(fr.n + fr.s * 0.3f), wi = normalize(fr.n + fr.t * 0.4f);
  expect_rgb_near(bsdf.f(wo, wi), RGB(0.7f, 0.4f, 0.4f) * kInvPi, 1e-6f);
  EXPECT_NEAR(bsdf.pdf(wo, wi), dot(wi, fr.n) * kInvPi, 1e-6f);  // average of two equal pdfs
}

TEST(BSDF, SampleWeightOfALambertianMixtureIsTheTotalAlbedo) {
  // Two cosine-sampled Lambertians: f cosθ / pdf = R1 + R2 for every sample, exactly.
  const Lambertian a(RGB(0.2f, 0.3f, 0.4f));
  const Lambertian b(RGB(0.5f, 0.1f, 0.0f));
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(&a);
  bsdf.add(&b);
  const Vec3 wo = normalize(fr.n + fr.s * 0.3f);
  PCG32 rng(7);
  for (int i = 0; i < 200; ++i) {
    const BSDFSample s = bsdf.sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    ASSERT_TRUE(s.valid());
    EXPECT_FALSE(s.is_delta());
    const RGB weight = s.f * (abs_dot(s.wi, fr.n) / s.pdf);
    expect_rgb_near(weight, RGB(0.7f, 0.4f, 0.4f), 2e-5f);
    EXPECT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-5f);
  }
}

TEST(BSDF, SelectsComponentWithFirstNumberAndRemapsIt) {
  const Lambertian lam(RGB(1.0f));  // white: its sample weight is its weight (see below)
  const TestMirror mirror(RGB(0.9f));
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(&lam);
  bsdf.add(&mirror);
  BSDF lam_alone(fr, fr.n);
  lam_alone.add(&lam);
  const Vec3 wo = normalize(fr.n + fr.s * 0.3f);
  // u.x in [0, 0.5): the Lambertian, sampled with u.x stretched to 2 u.x.
  const BSDFSample first = bsdf.sample_f(wo, Point2(0.2f, 0.7f));
  const BSDFSample alone = lam_alone.sample_f(wo, Point2(0.4f, 0.7f));
  ASSERT_TRUE(first.valid() && alone.valid());
  EXPECT_NEAR(first.wi.x, alone.wi.x, 1e-5f);
  EXPECT_NEAR(first.wi.y, alone.wi.y, 1e-5f);
  EXPECT_NEAR(first.wi.z, alone.wi.z, 1e-5f);
  // The mixture pdf: half the Lambertian's (the mirror's pdf is 0 for any given wi).
  EXPECT_NEAR(first.pdf, 0.5f * alone.pdf, 1e-5f);
  // u.x in [0.5, 1): the mirror, with its selection probability in the pdf.
  const BSDFSample second = bsdf.sample_f(wo, Point2(0.75f, 0.7f));
  ASSERT_TRUE(second.valid());
  EXPECT_TRUE(second.is_delta());
  EXPECT_NEAR(second.pdf, 0.5f, 1e-6f);
  const Vec3 mirrored = reflect(wo, fr.n);
  EXPECT_NEAR(dot(second.wi, mirrored), 1.0f, 1e-5f);
  expect_rgb_near(second.f * (abs_dot(second.wi, fr.n) / second.pdf), RGB(1.8f), 1e-4f);
  // Delta lobes have no f or pdf for given directions.
  EXPECT_NEAR(bsdf.f(wo, mirrored).r, kInvPi, 1e-6f);
}

TEST(BSDF, PicksComponentsByTheirColourAsCyclesSampleWeights) {
  // Cycles folds a closure's Color into its weight, so a Mix (0.65 / 0.35) of a dark green
  // Diffuse and a white Glossy samples the Glossy with 0.35 / (0.65 * 0.3 + 0.35) = 0.642.
  // The mixture pdf weighs the components alike, and f is unchanged.
  const Lambertian diffuse(RGB(0.2f, 0.5f, 0.2f));
  const TestMirror mirror(RGB(1.0f));
  EXPECT_FLOAT_EQ(diffuse.closure_sample_weight(), 0.3f);
  EXPECT_FLOAT_EQ(mirror.closure_sample_weight(), 1.0f);  // no Color folded: the default
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(&diffuse, RGB(0.65f));
  bsdf.add(&mirror, RGB(0.35f));
  const float diffuse_share = 0.65f * 0.3f / (0.65f * 0.3f + 0.35f);
  const Vec3 wo = normalize(fr.n + fr.s * 0.3f), wi = normalize(fr.n + fr.t * 0.4f);
  EXPECT_NEAR(bsdf.pdf(wo, wi), diffuse_share * dot(wi, fr.n) * kInvPi, 1e-6f);
  expect_rgb_near(bsdf.f(wo, wi), RGB(0.2f, 0.5f, 0.2f) * (0.65f * kInvPi), 1e-6f);
  // u.x below the diffuse share picks the Diffuse, above it the mirror (pdf: its chance).
  EXPECT_FALSE(bsdf.sample_f(wo, Point2(diffuse_share - 0.01f, 0.3f)).is_delta());
  const BSDFSample mirrored = bsdf.sample_f(wo, Point2(diffuse_share + 0.01f, 0.3f));
  ASSERT_TRUE(mirrored.valid() && mirrored.is_delta());
  EXPECT_NEAR(mirrored.pdf, 1.0f - diffuse_share, 1e-6f);
}

TEST(BSDF, FlagMaskLimitsTheComponents) {
  const Lambertian lam(RGB(0.5f));
  const TestMirror mirror(RGB(0.9f));
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(&lam);
  bsdf.add(&mirror);
  EXPECT_EQ(bsdf.num_components(kReflection | kDiffuse), 1);
  EXPECT_EQ(bsdf.num_components(kReflection | kSpecular), 1);
  EXPECT_EQ(bsdf.num_components(kTransmission | kAllTypes), 0);
  EXPECT_TRUE(bsdf.has_non_delta());
  EXPECT_FALSE(bsdf.has_transmission());
  const Vec3 wo = normalize(fr.n + fr.s * 0.3f);
  // Only the mirror matches: every u picks it and its pdf is not divided.
  const BSDFSample s = bsdf.sample_f(wo, Point2(0.1f, 0.5f), kReflection | kSpecular);
  ASSERT_TRUE(s.valid());
  EXPECT_TRUE(s.is_delta());
  EXPECT_NEAR(s.pdf, 1.0f, 1e-6f);
  // Only the Lambertian: pdf not averaged with anything.
  const Vec3 wi = normalize(fr.n + fr.t * 0.4f);
  EXPECT_NEAR(bsdf.pdf(wo, wi, kReflection | kDiffuse), dot(wi, fr.n) * kInvPi, 1e-6f);
  EXPECT_FALSE(bsdf.sample_f(wo, Point2(0.1f, 0.5f), kTransmission | kAllTypes).valid());
  EXPECT_TRUE(bsdf.f(wo, wi, kTransmission | kAllTypes).is_black());
}

TEST(BSDF, DeltaSampleIsDroppedWhenGeometryDisagreesWithItsLobe) {
  // A mirror under a shading normal tilted 60° from the geometric one: for wo leaning away from
  // the tilt the mirrored direction goes below the geometric surface. Such a "reflection" would
  // pass through the surface, so the BSDF drops it; a mirrored direction that stays above is kept.
  const Vec3 ng(0, 0, 1);
  const Frame shading = Frame::from_normal(normalize(Vec3(std::sin(1.05f), 0.0f, std::cos(1.05f))));
  const TestMirror mirror(RGB(1.0f));
  BSDF bsdf(shading, ng);
  bsdf.add(&mirror);
  const Vec3 wo_low = normalize(Vec3(-0.5f, 0.0f, 1.0f));
  ASSERT_GT(dot(wo_low, shading.n), 0.0f);
  ASSERT_LT(dot(reflect(wo_low, shading.n), ng), 0.0f);
  EXPECT_FALSE(bsdf.sample_f(wo_low, Point2(0.5f, 0.5f)).valid());
  const Vec3 wo_high = normalize(Vec3(1.0f, 0.0f, 0.2f));
  ASSERT_GT(dot(reflect(wo_high, shading.n), ng), 0.0f);
  EXPECT_TRUE(bsdf.sample_f(wo_high, Point2(0.5f, 0.5f)).valid());
}

TEST(BSDF, DegenerateInputGivesNothing) {
  const Lambertian lam(RGB(0.5f));
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  EXPECT_FALSE(bsdf.sample_f(fr.n, Point2(0.5f, 0.5f)).valid());  // no components
  EXPECT_EQ(bsdf.pdf(fr.n, fr.n), 0.0f);
  bsdf.add(&lam);
  EXPECT_FALSE(bsdf.sample_f(fr.s, Point2(0.5f, 0.5f)).valid());  // grazing wo
  EXPECT_TRUE(bsdf.f(Vec3(0, 0, 0), fr.n).is_black());
  EXPECT_FALSE(bsdf.sample_f(Vec3(0, 0, 0), Point2(0.5f, 0.5f)).valid());
}

TEST(BSDF, RefusesNullAndTooManyComponents) {
  const Lambertian lam(RGB(0.5f));
  BSDF bsdf;
  EXPECT_THROW(bsdf.add(nullptr), ParameterError);
  for (int i = 0; i < BSDF::kMaxComponents; ++i) bsdf.add(&lam);
  EXPECT_THROW(bsdf.add(&lam), ParameterError);
}

TEST(BSDF, WorksWithRegistryModels) {
  const BxDFPtr lam = make("lambertian");
  const Frame fr = tilted_frame();
  BSDF bsdf(fr, fr.n);
  bsdf.add(lam.get());
  const Vec3 wo = fr.n, wi = normalize(fr.n + fr.s);
  expect_rgb_near(bsdf.f(wo, wi), RGB(0.8f * kInvPi), 1e-6f);
}

// Light sampling asks for f·cos and the pdf of one pair together (BSDF::f_cos_pdf, through each
// model's f_pdf): the same values as the separate calls, for every registry model, on both
// sides of a tilted frame, with and without a sampling horizon.
TEST(BSDF, FCosPdfEqualsFCosAndPdfForEveryModel) {
  const Frame fr = tilted_frame();
  const Vec3 ng = normalize(fr.n + fr.s * 0.2f);
  PCG32 rng(0x5eed);
  ParamSet layered;
  layered.set("clearcoat", 0.5);
  layered.set("transmission", 0.3);
  layered.set("sheen", 0.4);
  const BxDFPtr principled = make("cycles_principled", layered);
  std::vector<BxDFPtr> models{principled};
  // The Glass and Refraction nodes' defaults are sharp (a delta): their rough lobes too, which
  // give f and pdf together from one Fresnel (CyclesRoughDielectric::eval_density).
  for (const char* node : {"cycles_glass", "cycles_refraction"}) {
    for (const char* distribution : {"ggx", "beckmann"}) {
      ParamSet rough;
      rough.set("distribution", std::string(distribution));
      rough.set("roughness", 0.4);
      models.push_back(make(node, rough));
    }
  }
  for (const ModelInfo& info : bxdf::models()) models.push_back(make(info.name));
  for (const BxDFPtr& m : models) {
    for (bool horizon : {false, true}) {
      BSDF bsdf(fr, ng);
      if (horizon) bsdf.set_sampling_horizon(ng);
      bsdf.add(m.get(), RGB(0.7f, 0.8f, 0.9f));
      bsdf.add(principled.get(), RGB(0.3f));
      for (int i = 0; i < 200; ++i) {
        const Vec3 wo = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
        const Vec3 wi = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
        float pdf = -1.0f;
        const RGB f_cos = bsdf.f_cos_pdf(wo, wi, &pdf);
        const RGB expected = bsdf.f_cos(wo, wi);
        EXPECT_EQ(f_cos.r, expected.r) << m->model_name() << " horizon " << horizon;
        EXPECT_EQ(f_cos.g, expected.g) << m->model_name();
        EXPECT_EQ(f_cos.b, expected.b) << m->model_name();
        EXPECT_EQ(pdf, bsdf.pdf(wo, wi)) << m->model_name() << " horizon " << horizon;
        float model_pdf = -1.0f;
        const RGB model_f = m->f_pdf(wo, wi, &model_pdf);
        EXPECT_EQ(model_pdf, m->pdf(wo, wi)) << m->model_name();
        EXPECT_EQ(model_f.r, m->f(wo, wi).r) << m->model_name();
      }
    }
  }
}

TEST(BSDF, DefensiveSamplingRaisesEachComponentToAnEighthOfTheSum) {
  // Cycles' first surface: a Mix (0.95 / 0.05) of a white Diffuse and a white mirror picks the
  // mirror with 0.125 / (0.95 + 0.125), not 0.05; its sample then weighs 0.05 / that chance,
  // the mixture pdf uses the raised weights, and f is unchanged.
  const Lambertian diffuse(RGB(1.0f));
  const TestMirror mirror(RGB(1.0f));
  const Frame fr = tilted_frame();
  BSDF plain(fr, fr.n), defensive(fr, fr.n);
  for (BSDF* b : {&plain, &defensive}) {
    b->add(&diffuse, RGB(0.95f));
    b->add(&mirror, RGB(0.05f));
  }
  defensive.use_defensive_sampling();
  defensive.use_defensive_sampling();  // once raised, the weights stay as they are
  const float mirror_chance = 0.125f / (0.95f + 0.125f);
  const Vec3 wo = normalize(fr.n + fr.s * 0.3f), wi = normalize(fr.n + fr.t * 0.4f);
  EXPECT_NEAR(defensive.pdf(wo, wi), (1.0f - mirror_chance) * dot(wi, fr.n) * kInvPi, 1e-6f);
  EXPECT_NEAR(plain.pdf(wo, wi), 0.95f * dot(wi, fr.n) * kInvPi, 1e-6f);
  expect_rgb_near(defensive.f(wo, wi), plain.f(wo, wi), 0.0f);
  EXPECT_FALSE(defensive.sample_f(wo, Point2(1.0f - mirror_chance - 0.01f, 0.3f)).is_delta());
  const BSDFSample m = defensive.sample_f(wo, Point2(1.0f - mirror_chance + 0.01f, 0.3f));
  ASSERT_TRUE(m.valid() && m.is_delta());
  EXPECT_NEAR(m.pdf, mirror_chance, 1e-6f);
  expect_rgb_near(m.f * (abs_dot(m.wi, fr.n) / m.pdf), RGB(0.05f / mirror_chance), 1e-5f);
  // Both estimate the same albedo: 0.95 + 0.05.
  PCG32 rng(11);
  constexpr int kN = 100000;
  double sum_plain = 0.0, sum_defensive = 0.0;
  int mirrors = 0;
  for (int i = 0; i < kN; ++i) {
    const Point2 u(rng.uniform(), rng.uniform());
    const BSDFSample a = plain.sample_f(wo, u), b = defensive.sample_f(wo, u);
    if (a.valid()) sum_plain += a.f_cos.r / a.pdf;
    if (b.valid()) sum_defensive += b.f_cos.r / b.pdf;
    mirrors += b.valid() && b.is_delta();
  }
  EXPECT_NEAR(sum_plain / kN, 1.0, 2e-3);
  EXPECT_NEAR(sum_defensive / kN, 1.0, 2e-3);
  EXPECT_NEAR(double(mirrors) / kN, mirror_chance, 5.0 * std::sqrt(mirror_chance / kN));
}

TEST(BSDF, DefensiveSamplingOfOneComponentPicksItsOwnClosuresSo) {
  // A Glass node, or a Principled BSDF of full transmission, alone is one component of two
  // Cycles closures: at the first surface its Fresnel reflection (F = 0.04 head-on, against
  // 0.96) is picked with 0.125 / (0.125 + 0.96), as Cycles' defensive sampling picks it, and
  // each pick weighs F over that chance.
  ParamSet glass_params, principled_params;
  glass_params.set("ior", 1.5);
  glass_params.set("distribution", std::string("sharp"));
  principled_params.set("transmission", 1.0);
  principled_params.set("roughness", 0.0);
  principled_params.set("ior", 1.5);
  principled_params.set("base_color", RGBValue{1.0, 1.0, 1.0});
  for (const BxDFPtr& glass : {make("cycles_glass", glass_params),
                               make("cycles_principled", principled_params)}) {
    SCOPED_TRACE(glass->model_name());
    const Frame fr = tilted_frame();
    BSDF plain(fr, fr.n), defensive(fr, fr.n);
    plain.add(glass.get());
    defensive.add(glass.get());
    defensive.use_defensive_sampling();
    const Vec3 wo = fr.n;  // head-on: F = 0.04
    const float f0 = 0.04f, floor = 0.125f;  // the closures' weights F and 1 - F sum to 1
    const float reflect_chance = floor / (floor + (1.0f - f0));
    PCG32 rng(5);
    constexpr int kN = 20000;
    int reflections = 0, plain_reflections = 0;
    for (int i = 0; i < kN; ++i) {
      const Point2 u(rng.uniform(), rng.uniform());
      const BSDFSample s = defensive.sample_f(wo, u);
      ASSERT_TRUE(s.valid());
      const bool reflected = dot(s.wi, fr.n) > 0.0f;
      reflections += reflected;
      const float weight = s.f_cos.r / s.pdf;
      EXPECT_NEAR(weight, reflected ? f0 / reflect_chance : (1.0f - f0) / (1.0f - reflect_chance),
                  2e-4f);
      const BSDFSample p = plain.sample_f(wo, u);
      plain_reflections += p.valid() && dot(p.wi, fr.n) > 0.0f;
    }
    EXPECT_NEAR(double(reflections) / kN, reflect_chance, 5.0 * std::sqrt(reflect_chance / kN));
    EXPECT_NEAR(double(plain_reflections) / kN, f0, 5.0 * std::sqrt(f0 / kN));
  }
}

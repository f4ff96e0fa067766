// Models built per hit from plain values (ModelInfo::place into a ClosureArena) equal the same
// models made through the registry; BSDF mixtures weight, frame and pick their components as
// Cycles does (in proportion to the average of the RGB weight).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bxdf/bsdf.h"
#include "bxdf/models/cycles_principled.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

Vec3 random_direction(PCG32& rng) {
  return sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
}

void expect_same_model(const BxDF& a, const BxDF& b, uint64_t seed) {
  PCG32 rng(seed);
  for (int i = 0; i < 200; ++i) {
    const Vec3 wo = random_direction(rng), wi = random_direction(rng);
    const RGB fa = a.f(wo, wi), fb = b.f(wo, wi);
    EXPECT_EQ(fa.r, fb.r);
    EXPECT_EQ(fa.g, fb.g);
    EXPECT_EQ(fa.b, fb.b);
    EXPECT_EQ(a.pdf(wo, wi), b.pdf(wo, wi));
    const Point2 u(rng.uniform(), rng.uniform());
    const BxDFSample sa = a.sample_f(wo, u), sb = b.sample_f(wo, u);
    EXPECT_EQ(sa.pdf, sb.pdf);
    EXPECT_EQ(sa.wi.x, sb.wi.x);
    EXPECT_EQ(sa.f.g, sb.f.g);
  }
  EXPECT_EQ(a.flags(), b.flags());
}

}  // namespace

TEST(ClosurePlace, PlacedModelsEqualRegistryModels) {
  const std::vector<std::pair<std::string, ParamSet>> cases = [] {
    std::vector<std::pair<std::string, ParamSet>> c;
    ParamSet lam;
    lam.set("reflectance", RGBValue{0.2, 0.5, 0.9});
    c.emplace_back("lambertian", lam);
    ParamSet on;
    on.set("color", RGBValue{0.7, 0.3, 0.1});
    on.set("roughness", 0.6);
    c.emplace_back("cycles_oren_nayar", on);
    for (const char* dist : {"ggx", "beckmann"})
      for (double r : {0.0, 0.01, 0.3, 0.9})
        for (double an : {-0.7, 0.0, 0.5}) {
          ParamSet g;
          g.set("color", RGBValue{0.9, 0.6, 0.3});
          g.set("distribution", dist);
          g.set("roughness", r);
          g.set("anisotropy", an);
          c.emplace_back("cycles_glossy", g);
        }
    // Every distribution of the dielectric nodes, rough and sharp, an index near 1 and below 1.
    for (const char* model : {"cycles_glass", "cycles_refraction"})
      for (const char* dist : {"sharp", "beckmann", "ggx", "multi_ggx"}) {
        for (double r : {0.0, 0.35, 0.8})
          for (double ior : {1.5, 0.7, 1.00005}) {
            ParamSet d;
            d.set("color", RGBValue{0.9, 0.7, 0.4});
            d.set("distribution", dist);
            d.set("roughness", r);
            d.set("ior", ior);
            c.emplace_back(model, d);
          }
      }
    ParamSet tl;
    tl.set("color", RGBValue{0.3, 0.6, 0.2});
    c.emplace_back("cycles_translucent", tl);
    ParamSet tp;
    tp.set("color", RGBValue{0.5, 0.8, 0.1});
    c.emplace_back("cycles_transparent", tp);
    for (double sigma : {0.0, 0.3, 1.0}) {
      ParamSet v;
      v.set("color", RGBValue{0.4, 0.2, 0.7});
      v.set("sigma", sigma);
      c.emplace_back("cycles_velvet", v);
    }
    // Principled: every parameter off its default, both distributions, rough and smooth
    // (multiscatter only above roughness 0.075), opaque and transmissive.
    for (const char* dist : {"ggx", "multi_ggx"})
      for (double r : {0.02, 0.4})
        for (double transmission : {0.0, 0.7}) {
          ParamSet p;
          p.set("base_color", RGBValue{0.7, 0.4, 0.2});
          p.set("subsurface", 0.2);
          p.set("subsurface_color", RGBValue{0.9, 0.1, 0.3});
          p.set("metallic", 0.3);
          p.set("specular", 0.6);
          p.set("specular_tint", 0.4);
          p.set("roughness", r);
          p.set("anisotropic", 0.5);
          p.set("anisotropic_rotation", 0.15);
          p.set("sheen", 0.6);
          p.set("sheen_tint", 0.2);
          p.set("clearcoat", 0.5);
          p.set("clearcoat_roughness", 0.2);
          p.set("ior", 1.6);
          p.set("transmission", transmission);
          p.set("transmission_roughness", 0.3);
          p.set("distribution", dist);
          c.emplace_back("cycles_principled", p);
        }
    return c;
  }();
  uint64_t seed = 1;
  for (const auto& [name, params] : cases) {
    SCOPED_TRACE(name + " " + std::to_string(seed));
    const ModelInfo* info = find_model(name);
    ASSERT_TRUE(info && info->place);
    const BxDFPtr made = make(name, params);
    const std::vector<PlainValue> plain = plain_values(*info, made->params());
    ClosureArena arena;
    const BxDF* placed = info->place(plain.data(), arena);
    ASSERT_NE(placed, nullptr);
    EXPECT_LE(arena.used(), info->place_size);
    expect_same_model(*made, *placed, seed++);
  }
}

TEST(ClosurePlace, PlainPrincipledInputsEqualTheParamSetMapping) {
  ParamSet p;
  p.set("base_color", RGBValue{0.1, 0.2, 0.3});
  p.set("anisotropic_rotation", 0.4);
  p.set("transmission_roughness", 0.6);
  p.set("distribution", "multi_ggx");
  const ModelInfo* info = find_model("cycles_principled");
  const BxDFPtr made = make("cycles_principled", p);
  const std::vector<PlainValue> plain = plain_values(*info, made->params());
  const CyclesPrincipledInputs a = cycles_principled_inputs(made->params());
  const CyclesPrincipledInputs b = cycles_principled_inputs(info->params, plain.data());
  EXPECT_EQ(a.base_color.b, b.base_color.b);
  EXPECT_EQ(a.anisotropic_rotation, b.anisotropic_rotation);
  EXPECT_EQ(a.transmission_roughness, b.transmission_roughness);
  EXPECT_EQ(a.ior, b.ior);
  EXPECT_TRUE(b.multiscatter);
}

TEST(ClosurePlace, ArenaHoldsAFullMaterialOfTheLargestModel) {
  // The material graph reader refuses a material whose closures need more than kCapacity
  // (place_size + 64 alignment slack each); a material of BSDF::kMaxComponents closures of the
  // largest placeable model must pass.
  size_t largest = 0;
  for (const ModelInfo& m : models())
    if (m.place) largest = std::max(largest, m.place_size);
  EXPECT_LE(BSDF::kMaxComponents * (largest + 64), ClosureArena::kCapacity);
  EXPECT_GE(ClosureArena::kMaxObjects, BSDF::kMaxComponents);
  const ModelInfo* info = find_model("cycles_principled");
  const std::vector<PlainValue> plain = plain_values(*info, make("cycles_principled")->params());
  ClosureArena arena;
  for (int i = 0; i < BSDF::kMaxComponents; ++i) EXPECT_NE(info->place(plain.data(), arena), nullptr);
}

TEST(ClosurePlace, ArenaRefusesWhenFullAndResets) {
  const ModelInfo* info = find_model("lambertian");
  const std::vector<PlainValue> plain = plain_values(*info, make("lambertian")->params());
  ClosureArena arena;
  int made = 0;
  while (info->place(plain.data(), arena)) ++made;
  EXPECT_EQ(made, ClosureArena::kMaxObjects);  // small models: the object count limits first
  arena.reset();
  EXPECT_EQ(arena.used(), 0u);
  EXPECT_NE(info->place(plain.data(), arena), nullptr);
}

TEST(ClosurePlace, ClampPlainBringsValuesIntoTheDeclaredRange) {
  const ModelInfo* info = find_model("cycles_glossy");
  const ParamSpec& roughness = info->params[param_index(info->params, "roughness")];
  EXPECT_EQ(clamp_plain(roughness, {1.7f, 0, 0}).x, 1.0f);
  EXPECT_EQ(clamp_plain(roughness, {-0.2f, 0, 0}).x, 0.0f);
  EXPECT_EQ(clamp_plain(roughness, {NAN, 0, 0}).x, 0.0f);
  EXPECT_EQ(clamp_plain(roughness, {0.25f, 0, 0}).x, 0.25f);
  const ParamSpec& color = info->params[param_index(info->params, "color")];
  const PlainValue c = clamp_plain(color, {2.0f, -1.0f, 0.5f});
  EXPECT_EQ(c.x, 1.0f);
  EXPECT_EQ(c.y, 0.0f);
  EXPECT_EQ(c.z, 0.5f);
  EXPECT_THROW(param_index(info->params, "no_such"), ParameterError);
}

TEST(WeightedBSDF, FAndPdfAreTheWeightedMixture) {
  ParamSet g;
  g.set("roughness", 0.4);
  const BxDFPtr diffuse = make("lambertian"), glossy = make("cycles_glossy", g);
  const RGB w1(0.2f, 0.4f, 0.6f), w2(0.9f, 0.3f, 0.0f);
  const float s1 = (0.2f + 0.4f + 0.6f) / 3.0f, s2 = (0.9f + 0.3f + 0.0f) / 3.0f;
  BSDF bsdf(Frame(), Vec3(0, 0, 1));
  bsdf.add(diffuse.get(), w1);
  bsdf.add(glossy.get(), w2);
  PCG32 rng(7);
  for (int i = 0; i < 100; ++i) {
    Vec3 wo = random_direction(rng), wi = random_direction(rng);
    wo.z = std::fabs(wo.z) + 0.05f;
    wi.z = std::fabs(wi.z) + 0.05f;
    wo = normalize(wo);
    wi = normalize(wi);
    const RGB expected = w1 * diffuse->f(wo, wi) + w2 * glossy->f(wo, wi);
    const RGB f = bsdf.f(wo, wi);
    EXPECT_NEAR(f.r, expected.r, 1e-6f * (1 + expected.r));
    EXPECT_NEAR(f.b, expected.b, 1e-6f * (1 + expected.b));
    const RGB fc = bsdf.f_cos(wo, wi);
    EXPECT_NEAR(fc.g, expected.g * wi.z, 1e-6f * (1 + expected.g));
    const float pdf = (s1 * diffuse->pdf(wo, wi) + s2 * glossy->pdf(wo, wi)) / (s1 + s2);
    EXPECT_NEAR(bsdf.pdf(wo, wi), pdf, 1e-5f * (1 + pdf));
    // A sample's f_cos and pdf are those of the mixture at the sampled direction.
    const BSDFSample s = bsdf.sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    if (!s.valid()) continue;
    EXPECT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-5f * (1 + s.pdf));
    EXPECT_NEAR(s.f_cos.r, bsdf.f_cos(wo, s.wi).r, 1e-5f * (1 + s.f_cos.r));
  }
}

TEST(WeightedBSDF, PicksComponentsInProportionToTheirSampleWeight) {
  ParamSet mirror;
  mirror.set("roughness", 0.0);
  const BxDFPtr diffuse = make("lambertian"), specular = make("cycles_glossy", mirror);
  BSDF bsdf(Frame(), Vec3(0, 0, 1));
  bsdf.add(diffuse.get(), RGB(0.3f, 0.3f, 0.0f));   // sample weight 0.2
  bsdf.add(specular.get(), RGB(0.6f, 0.6f, 0.6f));  // sample weight 0.6
  const int n = 40000;
  int delta = 0;
  PCG32 rng(3);
  const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 0.9f));
  for (int i = 0; i < n; ++i) {
    const BSDFSample s = bsdf.sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    if (s.valid() && s.is_delta()) {
      ++delta;
      // Mirror: weight · colour / cos, picked with probability 0.75.
      EXPECT_NEAR(s.pdf, 0.75f, 1e-6f);
      EXPECT_NEAR(s.f_cos.g, 0.6f * 0.8f, 1e-5f);
    }
  }
  const double p = double(delta) / n, sigma = std::sqrt(0.75 * 0.25 / n);
  EXPECT_NEAR(p, 0.75, 5 * sigma);
}

TEST(WeightedBSDF, EachComponentUsesItsOwnFrame) {
  const BxDFPtr diffuse = make("lambertian");
  const Vec3 tilted = normalize(Vec3(0.4f, 0.0f, 0.9f));
  const Frame own = Frame::from_normal(tilted);
  BSDF bsdf(Frame(), Vec3(0, 0, 1));
  bsdf.add(diffuse.get(), RGB(1.0f), &own);
  const Vec3 wo = normalize(Vec3(0.0f, 0.2f, 1.0f));
  const Vec3 wi = normalize(Vec3(-0.5f, 0.0f, 0.6f));
  // The point's normal says reflection; the component's frame gives cos θi about `tilted`.
  const RGB fc = bsdf.f_cos(wo, wi);
  EXPECT_NEAR(fc.r, 0.8f / kPi * std::fabs(dot(wi, tilted)), 1e-6f);
  EXPECT_NEAR(bsdf.pdf(wo, wi), std::fabs(dot(wi, tilted)) / kPi, 1e-6f);
  EXPECT_THROW(bsdf.add(diffuse.get(), RGB(-1.0f)), ParameterError);
}

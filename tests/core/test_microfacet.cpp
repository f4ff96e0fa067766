// The `microfacet` model (Torrance–Sparrow): the V-groove G against the seed's expression,
// f against an evaluation written out here in double precision for every distribution,
// shadowing and Fresnel kind, the optional diffuse term (f, the lobe mixture's pdf and
// sampling, and that a black one leaves the plain lobe untouched), and its parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bxdf/microfacet/beckmann.h"
#include "bxdf/microfacet/blinn.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/models/microfacet.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "microfacet_quadrature.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;

struct V {
  double x, y, z;
};
V to_v(const Vec3& w) { return {w.x, w.y, w.z}; }
double dot(const V& a, const V& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V unit(const V& a) {
  const double l = std::sqrt(dot(a, a));
  return {a.x / l, a.y / l, a.z / l};
}

Vec3 random_upper(PCG32& rng) {
  const double z = 0.02 + 0.98 * rng.uniform_double();
  const double r = std::sqrt(1.0 - z * z), phi = 2.0 * kPiD * rng.uniform_double();
  return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

// The seed's G: min(1, min(2 NdotWh NdotWo / WodotWh, 2 NdotWh NdotWi / WodotWh)).
double seed_v_groove(const V& wo, const V& wi, const V& wh) {
  const double n_h = std::fabs(wh.z), n_o = std::fabs(wo.z), n_i = std::fabs(wi.z);
  const double wo_h = std::fabs(dot(wo, wh));
  return std::min(1.0, std::min(2.0 * n_h * n_o / wo_h, 2.0 * n_h * n_i / wo_h));
}

// The reference model, written from reference/models.md and the seed.
struct Reference {
  std::string distribution, shadowing, fresnel;
  double e = 0, ex = 0, ey = 0, ax = 0, ay = 0;
  double eta_i = 1, eta_t = 1.5, eta = 0.2, k = 3.0;

  double D(const V& h) const {
    const double cos_t = h.z, sin_t = std::sqrt(h.x * h.x + h.y * h.y);
    const double cos_p = h.x / sin_t, sin_p = h.y / sin_t;
    const double tan2 = sin_t * sin_t / (cos_t * cos_t);
    if (distribution == "blinn") return (e + 2) / (2 * kPiD) * std::pow(cos_t, e);
    if (distribution == "ashikhmin_shirley")
      return std::sqrt((ex + 2) * (ey + 2)) / (2 * kPiD) *
             std::pow(cos_t, ex * cos_p * cos_p + ey * sin_p * sin_p);
    const double q = tan2 * (cos_p * cos_p / (ax * ax) + sin_p * sin_p / (ay * ay));
    const double c4 = std::pow(cos_t, 4);
    if (distribution == "beckmann") return std::exp(-q) / (kPiD * ax * ay * c4);
    return 1.0 / (kPiD * ax * ay * c4 * (1 + q) * (1 + q));  // ggx
  }
  double lambda(const V& w) const {
    const double sin_t = std::sqrt(w.x * w.x + w.y * w.y);
    const double cos_p = w.x / sin_t, sin_p = w.y / sin_t;
    double bx = ax, by = ay;  // Blinn/AS: Beckmann at α = sqrt(2/(e + 2)) per axis
    if (distribution == "blinn") bx = by = std::sqrt(2 / (e + 2));
    if (distribution == "ashikhmin_shirley") {
      bx = std::sqrt(2 / (ex + 2));
      by = std::sqrt(2 / (ey + 2));
    }
    const double alpha = std::sqrt(cos_p * cos_p * bx * bx + sin_p * sin_p * by * by);
    const double tan_t = sin_t / std::fabs(w.z);
    if (distribution == "ggx") return (-1 + std::sqrt(1 + alpha * alpha * tan_t * tan_t)) / 2;
    const double a = 1 / (alpha * tan_t);
    return a >= 1.6 ? 0.0 : (1 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
  }
  double F(double c) const {
    if (fresnel == "dielectric") {
      const double sin_t = eta_i / eta_t * std::sqrt(1 - c * c);
      if (sin_t >= 1) return 1;
      const double ct = std::sqrt(1 - sin_t * sin_t);
      const double rpar = (eta_t * c - eta_i * ct) / (eta_t * c + eta_i * ct);
      const double rperp = (eta_i * c - eta_t * ct) / (eta_i * c + eta_t * ct);
      return (rpar * rpar + rperp * rperp) / 2;
    }
    if (fresnel == "conductor") {  // the seed's r∥², r⊥²
      const double ek = eta * eta + k * k;
      const double rpar2 = (ek * c * c - 2 * eta * c + 1) / (ek * c * c + 2 * eta * c + 1);
      const double rperp2 = (ek - 2 * eta * c + c * c) / (ek + 2 * eta * c + c * c);
      return (rpar2 + rperp2) / 2;
    }
    return 1;
  }
  double f(const V& wo, const V& wi, double R) const {
    const V wh = unit({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    const double G =
        shadowing == "v_groove" ? seed_v_groove(wo, wi, wh) : 1 / (1 + lambda(wo) + lambda(wi));
    return R * D(wh) * G * F(dot(wi, wh)) / (4 * wo.z * wi.z);
  }
  ParamSet params(double R) const {
    ParamSet p;
    p.set("reflectance", R);
    p.set("distribution", distribution);
    p.set("shadowing", shadowing);
    p.set("fresnel", fresnel);
    if (distribution == "blinn") p.set("exponent", e);
    if (distribution == "ashikhmin_shirley") {
      p.set("exponent_x", ex);
      p.set("exponent_y", ey);
    }
    if (distribution == "beckmann" || distribution == "ggx") {
      p.set("alpha_x", ax);
      p.set("alpha_y", ay);
    }
    if (fresnel == "dielectric") {
      p.set("eta_i", eta_i);
      p.set("eta_t", eta_t);
    }
    if (fresnel == "conductor") {
      p.set("eta", eta);
      p.set("k", k);
    }
    return p;
  }
};

std::string error_of(const ParamSet& p) {
  try {
    make("microfacet", p);
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Microfacet, VGrooveMatchesTheSeedExpression) {
  PCG32 rng(3);
  const TorranceSparrow<microfacet::Blinn> model(RGB(1.0f), microfacet::Blinn(10.0f),
                                                 MicrofacetShadowing::VGroove, Fresnel::none());
  int clipped = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 wo = random_upper(rng), wi = random_upper(rng);
    const Vec3 wh = normalize(wo + wi);
    const double expected = seed_v_groove(to_v(wo), to_v(wi), to_v(wh));
    clipped += expected < 1.0;
    EXPECT_NEAR(microfacet::v_groove_G(wo, wi, wh), expected, 1e-5);
    EXPECT_NEAR(model.G(wo, wi, wh), expected, 1e-5);
  }
  EXPECT_GT(clipped, 500);  // the min() branches were exercised, not only G = 1
}

TEST(Microfacet, TorranceSparrowMatchesAnIndependentEvaluation) {
  std::vector<Reference> cases;
  for (const std::string shadowing : {"v_groove", "smith"}) {
    for (const std::string fresnel : {"none", "dielectric", "conductor"}) {
      Reference r;
      r.shadowing = shadowing;
      r.fresnel = fresnel;
      r.distribution = "blinn";
      r.e = 35;
      cases.push_back(r);
      r.distribution = "ashikhmin_shirley";
      r.ex = 8;
      r.ey = 150;
      cases.push_back(r);
      r.distribution = "beckmann";
      r.ax = 0.25;
      r.ay = 0.4;
      cases.push_back(r);
      r.distribution = "ggx";
      r.ax = 0.5;
      r.ay = 0.12;
      cases.push_back(r);
    }
  }
  PCG32 rng(5);
  for (const Reference& ref : cases) {
    SCOPED_TRACE(ref.distribution + " " + ref.shadowing + " " + ref.fresnel);
    const BxDFPtr m = make("microfacet", ref.params(0.7));
    int nonzero = 0;
    for (int i = 0; i < 1000; ++i) {
      const Vec3 wo = random_upper(rng), wi = random_upper(rng);
      const double expected = ref.f(to_v(wo), to_v(wi), 0.7);
      const RGB got = m->f(wo, wi);
      nonzero += expected > 1e-3;
      EXPECT_NEAR(got.r, expected, 1e-4 * expected + 1e-7);
      EXPECT_EQ(got.r, got.g);
      // Two-sided: the same pair mirrored below the surface.
      const RGB below = m->f(Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z));
      EXPECT_EQ(below.r, got.r);
      // No reflection into the other hemisphere.
      EXPECT_EQ(m->f(wo, Vec3(wi.x, wi.y, -wi.z)).r, 0.0f);
      EXPECT_EQ(m->pdf(wo, Vec3(wi.x, wi.y, -wi.z)), 0.0f);
    }
    EXPECT_GT(nonzero, 100);
  }
}

TEST(Microfacet, NormalIncidenceValue) {
  // wo = wi = n: D = 1/(π α²), Smith G = 1, F = 1, so f = R/(4π α²).
  ParamSet p;
  p.set("reflectance", 0.8);
  p.set("alpha_x", 0.5);
  p.set("alpha_y", 0.5);
  const RGB f = make("microfacet", p)->f(Vec3(0, 0, 1), Vec3(0, 0, 1));
  EXPECT_NEAR(f.r, 0.8 / (4 * kPiD * 0.25), 1e-6);
}

TEST(Microfacet, ParametersAreRefusedByNameAndShownOnlyForTheirKind) {
  ParamSet p;
  p.set("alpha_x", 0.0);
  std::string msg = error_of(p);
  EXPECT_NE(msg.find("'alpha_x'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(0, 10]"), std::string::npos) << msg;
  p = ParamSet();
  p.set("distribution", "phong");
  msg = error_of(p);
  EXPECT_NE(msg.find("'distribution'"), std::string::npos) << msg;
  p = ParamSet();
  p.set("exponent", -1.0);
  EXPECT_NE(error_of(p).find("'exponent'"), std::string::npos);

  const ModelInfo* info = find_model("microfacet");
  ASSERT_NE(info, nullptr);
  auto when = [&](const std::string& name) {
    for (const ParamSpec& s : info->params)
      if (s.name == name) {
        std::string w = s.when_param;
        for (const auto& v : s.when_values) w += " " + v;
        return w;
      }
    return std::string("missing");
  };
  EXPECT_EQ(when("reflectance"), "");
  EXPECT_EQ(when("diffuse"), "");
  EXPECT_EQ(when("exponent"), "distribution blinn");
  EXPECT_EQ(when("exponent_x"), "distribution ashikhmin_shirley");
  EXPECT_EQ(when("alpha_y"), "distribution beckmann ggx");
  EXPECT_EQ(when("eta_t"), "fresnel dielectric");
  EXPECT_EQ(when("k"), "fresnel conductor");
}

TEST(Microfacet, TinyAlphaIsRaisedToTheFloorAndStaysFinite) {
  // α = 1e-9 is accepted (> 0) and behaves as α = 1e-4 (microfacet::kMinAlpha).
  ParamSet tiny, floor;
  tiny.set("alpha_x", 1e-9);
  tiny.set("alpha_y", 1e-9);
  floor.set("alpha_x", 1e-4);
  floor.set("alpha_y", 1e-4);
  const BxDFPtr a = make("microfacet", tiny), b = make("microfacet", floor);
  const Vec3 wo(0.6f, 0.0f, 0.8f), wi(-0.6f, 0.0f, 0.8f);
  EXPECT_EQ(a->f(wo, wi).r, b->f(wo, wi).r);
  EXPECT_GT(a->f(wo, wi).r, 1e6f);
  EXPECT_TRUE(std::isfinite(a->f(wo, wi).r));
  const BxDFSample s = a->sample_f(wo, Point2(0.3f, 0.6f));
  ASSERT_TRUE(s.valid());
  EXPECT_NEAR(s.wi.x, -0.6f, 1e-3f);  // a near-perfect mirror
}

TEST(Microfacet, DiffuseTermAddsRdOverPi) {
  const double rd[3] = {0.3, 0.55, 0.1};
  std::vector<Reference> cases;
  Reference r;
  r.shadowing = "v_groove";
  r.fresnel = "dielectric";
  r.distribution = "blinn";
  r.e = 35;
  cases.push_back(r);
  r.shadowing = "smith";
  r.distribution = "ggx";
  r.ax = 0.5;
  r.ay = 0.12;
  cases.push_back(r);
  PCG32 rng(9);
  for (const Reference& ref : cases) {
    SCOPED_TRACE(ref.distribution);
    ParamSet p = ref.params(0.7);
    p.set("diffuse", RGBValue{rd[0], rd[1], rd[2]});
    const BxDFPtr m = make("microfacet", p);
    EXPECT_EQ(m->flags(), uint32_t(kReflection | kGlossy | kDiffuse));
    for (int i = 0; i < 500; ++i) {
      const Vec3 wo = random_upper(rng), wi = random_upper(rng);
      const double lobe = ref.f(to_v(wo), to_v(wi), 0.7);
      const RGB got = m->f(wo, wi);
      for (int c = 0; c < 3; ++c) {
        const double expected = rd[c] / kPiD + lobe;
        EXPECT_NEAR(got[c], expected, 1e-4 * expected + 1e-7);
      }
      // Two-sided like the lobe, and nothing into the other hemisphere.
      EXPECT_EQ(m->f(Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z)), got);
      EXPECT_EQ(m->f(wo, Vec3(wi.x, wi.y, -wi.z)), RGB(0.0f));
      EXPECT_EQ(m->pdf(wo, Vec3(wi.x, wi.y, -wi.z)), 0.0f);
    }
  }
}

// With a black diffuse term, sampling is the plain lobe's: u goes to the distribution
// unchanged (no probability spent on the empty lobe) and the pdf is the lobe's own.
TEST(Microfacet, BlackDiffuseLeavesTheLobeUntouched) {
  const microfacet::GGX ggx(0.3f, 0.15f);
  const TorranceSparrow<microfacet::GGX> plain(RGB(0.9f), ggx, MicrofacetShadowing::Smith,
                                               Fresnel::dielectric(1.0f, 1.5f));
  EXPECT_EQ(plain.flags(), uint32_t(kReflection | kGlossy));
  EXPECT_EQ(plain.diffuse_probability(), 0.0f);
  ParamSet p;
  p.set("diffuse", 0.0);
  EXPECT_EQ(make("microfacet", p)->flags(), uint32_t(kReflection | kGlossy));
  PCG32 rng(21);
  int valid = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 wo = random_upper(rng);
    const Point2 u(rng.uniform(), rng.uniform());
    const BxDFSample s = plain.sample(wo, u);
    const Vec3 wh = ggx.sample_wh(wo, u);
    const Vec3 wi = reflect(wo, wh);
    if (!(dot(wo, wh) > 0.0f) || !(wi.z > 0.0f)) {
      EXPECT_FALSE(s.valid());
      continue;
    }
    ++valid;
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s.wi.x, wi.x);
    EXPECT_EQ(s.wi.y, wi.y);
    EXPECT_EQ(s.wi.z, wi.z);
    EXPECT_EQ(s.flags, uint32_t(kReflection | kGlossy));
    const Vec3 h = normalize(wo + wi);
    EXPECT_EQ(s.pdf, ggx.pdf_wh(wo, h) / (4.0f * dot(wo, h)));
    EXPECT_EQ(plain.density(wo, wi), s.pdf);
  }
  EXPECT_GT(valid, 1500);
}

// ∫ pdf dωi, as an integral over half vectors: dωi = 4 |ωo·ωh| dωh.
static double pdf_integral(const BxDF& m, const Vec3& wo, double alpha) {
  const auto q = bxdf_test::quadrature_for_alphas(alpha, alpha);
  return q.integrate([&](const Vec3& wh) {
    const float wo_h = dot(wo, wh);
    if (!(wo_h > 0.0f)) return 0.0;
    return double(m.pdf(wo, reflect(wo, wh))) * 4.0 * wo_h;
  });
}

TEST(Microfacet, DiffuseMixturePdfIntegratesToOne) {
  const double alpha = 0.25;
  ParamSet p;
  p.set("distribution", "beckmann");
  p.set("alpha_x", alpha);
  p.set("alpha_y", alpha);
  p.set("fresnel", "dielectric");
  const BxDFPtr lobe = make("microfacet", p);
  p.set("diffuse", RGBValue{0.2, 0.4, 0.3});
  const BxDFPtr both = make("microfacet", p);
  const auto* ts = dynamic_cast<const TorranceSparrow<microfacet::Beckmann>*>(both.get());
  ASSERT_NE(ts, nullptr);
  const double pd = ts->diffuse_probability();
  EXPECT_GE(pd, 0.1);
  EXPECT_LE(pd, 0.9);
  EXPECT_GT(pd, 0.5);  // Rd luminance ≈ 0.36 against R F(0) = 0.8 · 0.04
  for (const Vec3& wo : {Vec3(0.0f, 0.0f, 1.0f), normalize(Vec3(0.6f, 0.2f, 0.75f))}) {
    SCOPED_TRACE(wo.z);
    // The lobe alone loses only what it reflects below the horizon.
    const double lobe_mass = pdf_integral(*lobe, wo, alpha);
    EXPECT_LE(lobe_mass, 1.0 + 2e-3);
    EXPECT_GT(lobe_mass, 0.95);
    // The mixture: the cosine lobe's whole mass plus the glossy lobe's share, ≈ 1 here.
    const double mass = pdf_integral(*both, wo, alpha);
    EXPECT_NEAR(mass, pd + (1.0 - pd) * lobe_mass, 2e-3);
    EXPECT_NEAR(mass, 1.0, 0.01);
  }
}

TEST(Microfacet, DiffuseMixtureSamplesMatchPdfAndF) {
  ParamSet p;
  p.set("distribution", "ggx");
  p.set("alpha_x", 0.2);
  p.set("alpha_y", 0.35);
  p.set("reflectance", 0.9);
  p.set("fresnel", "dielectric");
  p.set("diffuse", RGBValue{0.5, 0.3, 0.1});
  const BxDFPtr m = make("microfacet", p);
  const double pd = dynamic_cast<const TorranceSparrow<microfacet::GGX>&>(*m).diffuse_probability();
  const Vec3 wo = normalize(Vec3(0.5f, -0.3f, 0.8f));
  PCG32 rng(33);
  const int n = 40000;
  int diffuse = 0;
  double estimate = 0.0;  // ∫ f_g cos θi dωi by importance sampling
  for (int i = 0; i < n; ++i) {
    const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    if (!s.valid()) continue;
    diffuse += (s.flags & kDiffuse) != 0;
    EXPECT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-4f * s.pdf);
    const RGB f = m->f(wo, s.wi);
    EXPECT_NEAR(s.f.g, f.g, 1e-5f * f.g);
    estimate += s.f.g * s.wi.z / s.pdf;
  }
  estimate /= n;
  EXPECT_NEAR(double(diffuse) / n, pd, 0.01);
  // The same integral by quadrature over half vectors (dωi = 4 |ωo·ωh| dωh).
  const auto q = bxdf_test::quadrature_for_alphas(0.2, 0.35);
  const double expected = q.integrate([&](const Vec3& wh) {
    const float wo_h = dot(wo, wh);
    if (!(wo_h > 0.0f)) return 0.0;
    const Vec3 wi = reflect(wo, wh);
    return wi.z > 0.0f ? double(m->f(wo, wi).g) * wi.z * 4.0 * wo_h : 0.0;
  });
  EXPECT_NEAR(estimate, expected, 0.01 * expected);
}

TEST(Microfacet, DiffuseOutOfRangeIsRefusedByName) {
  ParamSet p;
  p.set("diffuse", RGBValue{0.2, 1.5, 0.0});
  const std::string msg = error_of(p);
  EXPECT_NE(msg.find("'diffuse'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[0, 1]"), std::string::npos) << msg;
}

TEST(Microfacet, DiffuseModelStaysFiniteForAwkwardDirections) {
  ParamSet p;
  p.set("distribution", "blinn");
  p.set("exponent", 1e5);
  p.set("diffuse", RGBValue{0.9, 0.0, 0.4});
  const BxDFPtr m = make("microfacet", p);
  const std::vector<Vec3> dirs = {Vec3(0, 0, 0),         Vec3(0, 0, 1),          Vec3(0, 0, -3),
                                  Vec3(1, 0, 0),         Vec3(1, 0, 1e-7f),      Vec3(-1, 0, 1e-7f),
                                  Vec3(0.3f, 0.4f, -5), Vec3(1e-20f, 0, 1e-20f), Vec3(2, -1, 0.5f)};
  for (const Vec3& wo : dirs) {
    for (const Vec3& wi : dirs) {
      const RGB f = m->f(wo, wi);
      EXPECT_TRUE(finite_nonnegative(f));
      const float pdf = m->pdf(wo, wi);
      EXPECT_TRUE(std::isfinite(pdf) && pdf >= 0.0f);
    }
    for (const Point2 u : {Point2(0, 0), Point2(0.05f, 0.5f), Point2(0.5f, 0.999f),
                           Point2(0.999999f, 0.2f)}) {
      const BxDFSample s = m->sample_f(wo, u);
      EXPECT_TRUE(finite_nonnegative(s.f));
      EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.0f);
      if (s.valid()) {
        EXPECT_GT(s.wi.z * wo.z, 0.0f);
      }
    }
  }
}

// Lafortune: f against the lobe expression evaluated in the test, the mixture sampler's
// consistency with pdf and f, its normalisation, its weights against a quadrature of f cos θi,
// and the refusal of lobes that would overflow.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/lafortune.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

struct LobeRow {
  RGBValue cxy, cz, n;
};

ParamSet lafortune_params(const RGBValue& diffuse, const std::vector<LobeRow>& rows) {
  std::vector<ParamSet> lobes;
  for (const LobeRow& r : rows) {
    ParamSet l;
    l.set("cx", r.cxy);
    l.set("cy", r.cxy);
    l.set("cz", r.cz);
    l.set("exponent", r.n);
    lobes.push_back(l);
  }
  ParamSet p;
  p.set("diffuse", diffuse);
  p.set("lobes", lobes);
  return p;
}

// Lafortune et al.'s clay fit (reference/models.md): one lobe below the horizon (Cz < 0),
// two forward lobes.
ParamSet clay() {
  return lafortune_params({.383626, .260749, .274207}, {{{-1.089701, -1.102701, -1.107603},
                                                         {-1.354682, -2.714801, -1.569866},
                                                         {17.968505, 11.024489, 21.270282}},
                                                        {{-.733381, -.793320, -.848206},
                                                         {.676108, .679314, .726031},
                                                         {8.219745, 9.055139, 11.261951}},
                                                        {{-1.010548, -1.012378, -1.011263},
                                                         {.910783, .885239, .892451},
                                                         {152.912795, 141.937171, 201.046802}}});
}

// An anisotropic lobe, a retro-reflective one (Cx, Cy > 0) and a constant one (n = 0).
ParamSet mixed() {
  ParamSet p = lafortune_params({0.1, 0.2, 0.3}, {});
  std::vector<ParamSet> lobes;
  ParamSet aniso;
  aniso.set("cx", RGBValue{-1.2, -1.1, -1.0});
  aniso.set("cy", RGBValue{-0.5, -0.6, -0.7});
  aniso.set("cz", RGBValue{0.9, 1.0, 1.1});
  aniso.set("exponent", RGBValue{5.0, 8.0, 12.0});
  ParamSet retro;
  retro.set("cx", RGBValue{0.8, 0.8, 0.8});
  retro.set("cy", RGBValue{0.8, 0.8, 0.8});
  retro.set("cz", RGBValue{0.6, 0.6, 0.6});
  retro.set("exponent", RGBValue{3.0, 3.0, 3.0});
  ParamSet flat;
  flat.set("cx", RGBValue{0.2, 0.2, 0.2});
  flat.set("cy", RGBValue{0.0, 0.0, 0.0});
  flat.set("cz", RGBValue{0.0, 0.0, 0.0});
  flat.set("exponent", RGBValue{0.0, 0.0, 0.0});
  p.set("lobes", std::vector<ParamSet>{aniso, retro, flat});
  return p;
}

// f from the definition, in double.
double lafortune_reference(const ParamSet& p, int c, const Vec3& wo, const Vec3& wi) {
  double f = p.rgb("diffuse")[c] / M_PI;
  for (const ParamSet& l : p.list("lobes")) {
    const double d =
        l.rgb("cx")[c] * wo.x * wi.x + l.rgb("cy")[c] * wo.y * wi.y + l.rgb("cz")[c] * wo.z * wi.z;
    if (d > 0.0) f += std::pow(d, l.rgb("exponent")[c]);
  }
  return f;
}

Vec3 random_upper(PCG32& rng) {
  return sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
}

// ∫ g(wi) dωi over wo's hemisphere by the midpoint rule in (cos θ, φ).
template <class G>
double hemisphere_integral(float side, int n, G g) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double ct = (i + 0.5) / n, phi = 2.0 * M_PI * (j + 0.5) / n;
      const double st = std::sqrt(1.0 - ct * ct);
      sum += g(Vec3(static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                    side * static_cast<float>(ct)));
    }
  }
  return sum * 2.0 * M_PI / (static_cast<double>(n) * n);
}

}  // namespace

TEST(Lafortune, MatchesTheLobeExpression) {
  PCG32 rng(31);
  for (const ParamSet& p : {clay(), mixed(), ParamSet()}) {
    BxDFPtr m = make("lafortune", p);
    const ParamSet& full = m->params();  // with defaults filled in
    for (int i = 0; i < 300; ++i) {
      Vec3 wo = random_upper(rng), wi = random_upper(rng);
      if (i % 2) wo = -wo, wi = -wi;  // and from below
      const RGB f = m->f(wo, wi);
      for (int c = 0; c < 3; ++c) {
        // pow with exponents up to 201 multiplies the float rounding of the dot product.
        const double expected = lafortune_reference(full, c, wo, wi);
        EXPECT_NEAR(f[c], expected, 1e-4 * expected) << "channel " << c;
      }
      EXPECT_TRUE(m->f(wo, -wi).is_black());
    }
  }
}

TEST(Lafortune, ZeroExponentLobeIsOffWhereItsDotIsNotPositive) {
  ParamSet p = lafortune_params({0, 0, 0}, {{{1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}}});
  BxDFPtr m = make("lafortune", p);
  EXPECT_EQ(m->f(Vec3(0.6f, 0, 0.8f), Vec3(0.6f, 0, 0.8f)).r, 1.0f);   // d > 0: d^0 = 1
  EXPECT_EQ(m->f(Vec3(0.6f, 0, 0.8f), Vec3(-0.6f, 0, 0.8f)).r, 0.0f);  // d < 0
  EXPECT_EQ(m->f(Vec3(0, 0, 1), Vec3(0, 0, 1)).r, 0.0f);               // d = 0, not pow(0, 0)
}

TEST(Lafortune, DefaultIsADiffusePlusPhongLobe) {
  BxDFPtr m = make("lafortune");
  EXPECT_EQ(flags_to_string(m->flags()), "reflection|diffuse|glossy");
  const Vec3 wo = normalize(Vec3(0.3f, 0.2f, 0.8f));
  const Vec3 mirror(-wo.x, -wo.y, wo.z);
  EXPECT_NEAR(m->f(wo, mirror).r, 0.5 / M_PI + std::pow(0.95, 10.0), 1e-5);
  // Documented: about 0.81 of normally incident light is reflected.
  const double rho = hemisphere_integral(
      1.0f, 300, [&](const Vec3& wi) { return m->f(Vec3(0, 0, 1), wi).r * wi.z; });
  EXPECT_NEAR(rho, 0.5 + std::pow(0.95, 10.0) * 2.0 * M_PI / 12.0, 2e-3);
  EXPECT_LT(rho, 1.0);
}

TEST(Lafortune, MixtureProbabilitiesSumToOneAndKeepACosineShare) {
  for (const ParamSet& p :
       {clay(), mixed(), ParamSet(),
        lafortune_params({0, 0, 0}, {{{-1, -1, -1}, {1, 1, 1}, {50, 50, 50}}})}) {
    BxDFPtr m = make("lafortune", p);
    const auto& l = static_cast<const Lafortune&>(*m);
    double total = l.diffuse_probability();
    for (size_t j = 0; j < m->params().list("lobes").size(); ++j) total += l.lobe_probability(j);
    EXPECT_NEAR(total, 1.0, 1e-6);
    EXPECT_GE(l.diffuse_probability(), Lafortune::kMinDiffuseProbability);
  }
  BxDFPtr no_lobes = make("lafortune", lafortune_params({0.5, 0.5, 0.5}, {}));
  EXPECT_EQ(static_cast<const Lafortune&>(*no_lobes).diffuse_probability(), 1.0f);
  EXPECT_EQ(flags_to_string(no_lobes->flags()), "reflection|diffuse|glossy");
  EXPECT_EQ(flags_to_string(make("lafortune", lafortune_params({0, 0, 0}, {}))->flags()),
            "reflection|glossy");
}

TEST(Lafortune, SamplesAgreeWithPdfAndF) {
  PCG32 rng(37);
  for (const ParamSet& p : {clay(), mixed(), ParamSet()}) {
    BxDFPtr m = make("lafortune", p);
    int valid = 0;
    for (int i = 0; i < 400; ++i) {
      Vec3 wo = random_upper(rng);
      if (i % 2) wo = -wo;
      const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
      if (!s.valid()) continue;
      ++valid;
      EXPECT_GT(s.wi.z * wo.z, 0.0f);
      EXPECT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-5f * s.pdf);
      // s.wi was renormalised after s.f was computed; exponents up to 201 magnify that.
      const RGB f = m->f(wo, s.wi);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.f[c], f[c], 1e-4f * f[c]);
    }
    EXPECT_EQ(valid, 400);  // lobe samples below the horizon are folded back, not lost
  }
}

TEST(Lafortune, PdfIntegratesToOneOverTheHemisphere) {
  // Lobe samples that fall below the horizon are folded back, so nothing is lost: also for an
  // oblique wo, whose Phong lobe is cut by the horizon, and for clay, whose first lobe points
  // below the surface.
  for (const ParamSet& p : {ParamSet(), clay()}) {
    BxDFPtr m = make("lafortune", p);
    for (const Vec3& wo :
         {Vec3(0, 0, 1), normalize(Vec3(0.9f, 0.0f, -0.3f)), normalize(Vec3(0.2f, -0.5f, 0.05f))}) {
      const float side = wo.z > 0.0f ? 1.0f : -1.0f;
      const double total =
          hemisphere_integral(side, 300, [&](const Vec3& wi) { return m->pdf(wo, wi); });
      EXPECT_NEAR(total, 1.0, 3e-3) << "wo.z " << wo.z;
    }
  }
}

TEST(Lafortune, SampledReflectanceMatchesQuadratureOfF) {
  // If sample_f's weights f/pdf were wrong the Monte Carlo ρhd would drift from the quadrature.
  for (const ParamSet& p : {clay(), mixed()}) {
    BxDFPtr m = make("lafortune", p);
    for (double theta : {0.3, 1.2, 1.5}) {
      const Vec3 wo(static_cast<float>(std::sin(theta)), 0.0f, static_cast<float>(std::cos(theta)));
      const RGB mc = m->rho_hd(wo, 1 << 14);
      double quad[3] = {0, 0, 0};
      hemisphere_integral(1.0f, 400, [&](const Vec3& wi) {
        const RGB f = m->f(wo, wi);
        for (int c = 0; c < 3; ++c) quad[c] += f[c] * wi.z;
        return 0.0;
      });
      for (int c = 0; c < 3; ++c) {
        quad[c] *= 2.0 * M_PI / (400.0 * 400.0);
        EXPECT_NEAR(mc[c], quad[c], 0.01 * quad[c]) << "theta " << theta << " channel " << c;
      }
    }
  }
}

TEST(Lafortune, RefusesLobesThatOverflowOrHaveBadFields) {
  auto error_of = [](const ParamSet& p) -> std::string {
    try {
      make("lafortune", p);
    } catch (const ParameterError& e) {
      return e.what();
    }
    return "";
  };
  // 100^100 = 1e200 cannot be represented.
  std::string msg =
      error_of(lafortune_params({0, 0, 0}, {{{-1, -1, -1}, {1, 1, 1}, {10, 10, 10}},
                                            {{-1, -1, -1}, {100, 100, 100}, {10, 100, 10}}}));
  EXPECT_NE(msg.find("lobes[1]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("channel g"), std::string::npos) << msg;
  EXPECT_NE(msg.find("exponent"), std::string::npos) << msg;
  msg = error_of(lafortune_params({0, 0, 0}, {{{-1, -1, -1}, {1, 1, 1}, {10, -1, 10}}}));
  EXPECT_NE(msg.find("lobes[0]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'exponent'"), std::string::npos) << msg;
  msg = error_of(lafortune_params({0, 0, 0}, {{{-1, -1, -1}, {1, 1, 101}, {10, 10, 10}}}));
  EXPECT_NE(msg.find("'cz'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[-100, 100]"), std::string::npos) << msg;
}

TEST(Lafortune, IsTwoSidedAndReciprocal) {
  BxDFPtr m = make("lafortune", mixed());
  PCG32 rng(41);
  for (int i = 0; i < 100; ++i) {
    const Vec3 wo = random_upper(rng), wi = random_upper(rng);
    const RGB f = m->f(wo, wi);
    EXPECT_TRUE(m->f(-wo, -wi) == f);
    EXPECT_TRUE(m->f(wi, wo) == f);
    EXPECT_NEAR(m->pdf(-wo, -wi), m->pdf(wo, wi), 1e-6f * m->pdf(wo, wi));
  }
}

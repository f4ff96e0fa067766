// cycles_glass and cycles_refraction against Cycles 3.4's Glass and Refraction nodes, written
// out here in double precision the way svm/closure.h builds the closures and
// closure/bsdf_microfacet.h evaluates them (eval returns f·cos θi; the closure weights are
// F(N·V) and max(1e-4, 1 − F) for Glass, 1 for Refraction; back faces see 1/ior).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bxdf/microfacet/ggx.h"
#include "bxdf/microfacet/refraction_cover.h"
#include "bxdf/models/cycles_glass.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;
// The share of refraction samples a model drew as cover samples for wo (cycles_glass.h): the
// cover table at the pair turned so that wo is above.
float cover_share(const std::string& distribution, double roughness, double ior, const Vec3& wo) {
  const cycles::CoverDistribution kind = distribution == "ggx"
                                             ? cycles::CoverDistribution::kGGX
                                             : cycles::CoverDistribution::kBeckmann;
  const float ior_f = static_cast<float>(ior);
  const float eta = wo.z >= 0.0f ? ior_f : 1.0f / ior_f;
  return cycles::refraction_cover_share(kind, static_cast<float>(roughness * roughness), eta,
                                        std::fabs(wo.z));
}

struct D3 {
  double x, y, z;
};
D3 d3(const Vec3& v) { return {v.x, v.y, v.z}; }
double dot3(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// fresnel_dielectric_cos (bsdf_util.h).
double fresnel_dielectric_cos(double cosi, double eta) {
  const double c = std::fabs(cosi);
  double g = eta * eta - 1 + c * c;
  if (g <= 0) return 1.0;
  g = std::sqrt(g);
  const double A = (g - c) / (g + c);
  const double B = (c * (g + c) - 1) / (c * (g - c) + 1);
  return 0.5 * A * A * (1 + B * B);
}

struct CyclesDielectric {
  bool ggx;
  bool glass;
  double alpha, ior;

  double D(double cos_m) const {
    const double a2 = alpha * alpha, c2 = cos_m * cos_m, t2 = (1 - c2) / c2;
    return ggx ? a2 / (kPiD * c2 * c2 * (a2 + t2) * (a2 + t2))
               : std::exp(-t2 / a2) / (kPiD * a2 * c2 * c2);
  }
  double G1(double cos_n) const {
    const double c2 = cos_n * cos_n;
    if (ggx) return 2 / (1 + std::sqrt(1 + alpha * alpha * (1 - c2) / c2));
    const double inv_a = alpha * std::sqrt((1 - c2) / c2);
    if (inv_a < 0.625) return 1.0;
    const double a = 1 / inv_a;
    return ((2.181 * a + 3.535) * a) / ((2.577 * a + 2.276) * a + 1);
  }
  // Cycles' eval of the whole node (all closures, weights included, colour 1), divided by
  // |cos θi|; N is turned to the viewer and the IOR inverted on a back face.
  double f(D3 I, D3 L) const {
    double eta = ior;
    if (I.z < 0) {  // back face: N = −N
      I.z = -I.z;
      L.z = -L.z;
      eta = 1 / eta;
    }
    const double cos_no = I.z, cos_ni = L.z;
    const double fresnel = fresnel_dielectric_cos(cos_no, eta);
    const double w_reflect = glass ? fresnel : 0.0;
    const double w_refract = glass ? std::max(1e-4, 1 - fresnel) : 1.0;
    if (cos_ni > 0) {
      if (!(cos_no > 0)) return 0;
      D3 m{I.x + L.x, I.y + L.y, I.z + L.z};
      const double len = std::sqrt(dot3(m, m));
      const double eval = D(m.z / len) * G1(cos_no) * G1(cos_ni) * 0.25 / cos_no;
      return w_reflect * eval / cos_ni;
    }
    if (cos_no <= 0 || cos_ni >= 0) return 0;
    const D3 ht{-(eta * L.x + I.x), -(eta * L.y + I.y), -(eta * L.z + I.z)};
    const double ht2 = dot3(ht, ht), len = std::sqrt(ht2);
    const D3 H{ht.x / len, ht.y / len, ht.z / len};
    const double cos_ho = dot3(H, I), cos_hi = dot3(H, L);
    const double common = D(H.z) * eta * eta / (cos_no * ht2);
    const double eval = G1(cos_no) * G1(cos_ni) * std::fabs(cos_hi * cos_ho) * common;
    return w_refract * eval / -cos_ni;
  }
};

BxDFPtr make_dielectric(const std::string& model, const std::string& distribution,
                        double roughness, double ior, const RGBValue& color = {1, 1, 1}) {
  ParamSet p;
  p.set("distribution", distribution);
  p.set("roughness", roughness);
  p.set("ior", ior);
  p.set("color", color);
  return make(model, p);
}

Vec3 random_sphere(PCG32& rng) {
  for (;;) {
    const Vec3 w = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    if (std::fabs(w.z) > 0.02f) return w;
  }
}

}  // namespace

TEST(CyclesGlass, MatchesCyclesFormulaOnBothFacesIncludingUnphysicalPairs) {
  PCG32 rng(5);
  for (const std::string model : {"cycles_glass", "cycles_refraction"}) {
    for (const std::string distribution : {"ggx", "beckmann"}) {
      for (const double roughness : {0.3, 0.6, 1.0}) {
        for (const double ior : {1.5, 1.33, 0.8}) {
          SCOPED_TRACE(testing::Message() << model << " " << distribution << " r=" << roughness
                                          << " ior=" << ior);
          const CyclesDielectric ref{distribution == "ggx", model == "cycles_glass",
                                     roughness * roughness, ior};
          const BxDFPtr m = make_dielectric(model, distribution, roughness, ior, {0.9, 0.9, 0.9});
          int transmitted = 0, unphysical = 0;
          for (int i = 0; i < 600; ++i) {
            const Vec3 wo = random_sphere(rng);
            Vec3 wi = random_sphere(rng);
            if (i % 3 == 0) {
              const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
              if (!s.valid()) continue;
              wi = s.wi;
            }
            const double expected = 0.9 * ref.f(d3(wo), d3(wi));
            const double got = m->f(wo, wi).r;
            EXPECT_NEAR(got, expected, 1e-4 * expected + 1e-7)
                << "wo " << wo.x << " " << wo.y << " " << wo.z << " wi " << wi.x << " " << wi.y
                << " " << wi.z;
            if (wo.z * wi.z < 0 && expected > 1e-4) {
              ++transmitted;
              // A pair no facet facing wo refracts into: Cycles evaluates it, and so do we.
              const float cover = cover_share(distribution, roughness, ior, wo);
              unphysical += m->pdf(wo, wi) > 0 &&
                            m->pdf(wo, wi) <= 1.0001f * cover * uniform_hemisphere_pdf();
            }
          }
          EXPECT_GT(transmitted, 40);
          // (Narrower lobes put too little there for 600 random pairs to find.)
          if (roughness >= 0.6) {
            EXPECT_GT(unphysical, 0);
          }
        }
      }
    }
  }
}

TEST(CyclesGlass, FacetPdfIsCyclesPdfOnPhysicalPairs) {
  // Cycles' refraction pdf is G1(ωo) |ωh·ωo| |ωh·ωi| D η² / (cos θo |ht|²); ours is that on the
  // pairs its sampler reaches, mixed with the uniform cover.
  const double ior = 1.5, alpha = 0.25;
  const CyclesDielectric ref{true, false, alpha, ior};
  const BxDFPtr m = make_dielectric("cycles_refraction", "ggx", 0.5, ior);
  PCG32 rng(9);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 wo = random_sphere(rng);
    if (wo.z < 0) continue;
    const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    if (!s.valid()) continue;
    const D3 I = d3(wo), L = d3(s.wi);
    const D3 ht{-(ior * L.x + I.x), -(ior * L.y + I.y), -(ior * L.z + I.z)};
    const double ht2 = dot3(ht, ht), len = std::sqrt(ht2);
    const double up = ht.z < 0 ? -1.0 : 1.0;
    const D3 H{up * ht.x / len, up * ht.y / len, up * ht.z / len};
    // Outside the facet sampler's reach: the facet must face wo and turn wi away.
    if (!(dot3(H, I) > 0) || !(dot3(H, L) < 0)) continue;
    const double cycles_pdf = ref.G1(I.z) * std::fabs(dot3(H, I) * dot3(H, L)) * ref.D(H.z) *
                              ior * ior / (I.z * ht2);
    const double cover = cover_share("ggx", 0.5, ior, wo);
    const double facet_pdf =
        (s.pdf - cover * uniform_hemisphere_pdf()) / (1.0 - cover);
    EXPECT_NEAR(facet_pdf, cycles_pdf, 2e-4 * cycles_pdf + 1e-6);
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

TEST(CyclesGlass, SharpGlassPicksByFresnelAndCarriesTheWeightSum) {
  const double ior = 1.5;
  const BxDFPtr m = make_dielectric("cycles_glass", "sharp", 0.0, ior, {1.0, 0.5, 0.25});
  EXPECT_TRUE(m->is_delta());
  for (const double theta : {0.2, 1.0, 1.45}) {
    const Vec3 wo(float(std::sin(theta)), 0.0f, float(std::cos(theta)));
    const double fresnel = fresnel_dielectric_cos(std::cos(theta), ior);
    const double weight = fresnel + std::max(1e-4, 1 - fresnel);
    const BxDFSample r = m->sample_f(wo, Point2(float(0.999 * fresnel / weight), 0.5f));
    const BxDFSample t = m->sample_f(wo, Point2(float(1.001 * fresnel / weight), 0.5f));
    ASSERT_TRUE(r.valid() && t.valid());
    EXPECT_EQ(r.flags, uint32_t(kReflection | kSpecular));
    EXPECT_EQ(t.flags, uint32_t(kTransmission | kSpecular));
    EXPECT_NEAR(r.f.g * std::fabs(r.wi.z), 0.5 * weight, 1e-6);
    EXPECT_NEAR(t.f.g * std::fabs(t.wi.z), 0.5 * weight, 1e-6);
    // Snell: sin θt = sin θo / ior, on the far azimuth.
    EXPECT_NEAR(t.wi.x, -std::sin(theta) / ior, 1e-6);
  }
}

TEST(CyclesGlass, RefractionWeightStaysUnderTotalInternalReflection) {
  // From inside (wo below, index 1/1.5 seen from there) beyond the critical angle F = 1: the
  // rough refraction lobe keeps weight 1e-4; the sharp one reflects and samples nothing else.
  const Vec3 wo(float(std::sin(1.0)), 0.0f, -float(std::cos(1.0)));
  const Vec3 wi = normalize(Vec3(-0.9f, 0.1f, 0.6f));  // transmitted to the outside
  const BxDFPtr glass = make_dielectric("cycles_glass", "ggx", 0.8, 1.5);
  const BxDFPtr refraction = make_dielectric("cycles_refraction", "ggx", 0.8, 1.5);
  const float lobe = refraction->f(wo, wi).r;
  ASSERT_GT(lobe, 0.0f);
  EXPECT_NEAR(glass->f(wo, wi).r, 1e-4f * lobe, 1e-6f * lobe);
  const BxDFPtr sharp = make_dielectric("cycles_glass", "sharp", 0.0, 1.5);
  int reflected = 0;
  for (int i = 0; i < 1000; ++i) {
    const BxDFSample s = sharp->sample_f(wo, Point2((i + 0.5f) / 1000.0f, 0.5f));
    if (s.valid()) {
      EXPECT_TRUE(s.flags & kReflection);
      EXPECT_NEAR(s.f.r * std::fabs(s.wi.z), 1.0001f, 1e-6f);
      ++reflected;
    }
  }
  EXPECT_EQ(reflected, 1000);  // u.x < 1/1.0001 for every stratum here
}

TEST(CyclesGlass, SingularCasesAreDelta) {
  EXPECT_TRUE(make_dielectric("cycles_glass", "ggx", 1e-4, 1.5)->is_delta());  // node: sharp
  EXPECT_TRUE(make_dielectric("cycles_glass", "ggx", 0.017, 1.5)->is_delta());  // α² <= 1e-7
  EXPECT_FALSE(make_dielectric("cycles_glass", "ggx", 0.018, 1.5)->is_delta());
  EXPECT_TRUE(make_dielectric("cycles_glass", "multi_ggx", 1e-4, 1.5)->is_delta());
  EXPECT_FALSE(make_dielectric("cycles_glass", "multi_ggx", 0.017, 1.5)->is_delta());
  // An index of 1 makes Cycles' rough refraction a pass-through.
  const BxDFPtr m = make_dielectric("cycles_refraction", "beckmann", 0.5, 1.00005);
  ASSERT_TRUE(m->is_delta());
  const Vec3 wo = normalize(Vec3(0.3f, 0.2f, 0.9f));
  const BxDFSample s = m->sample_f(wo, Point2(0.5f, 0.5f));
  ASSERT_TRUE(s.valid());
  EXPECT_NEAR(s.wi.x, -wo.x, 1e-4f);
  EXPECT_NEAR(s.wi.z, -wo.z, 1e-4f);
}

TEST(CyclesGlass, MultiscatterRefractionIsTheGlassWalksTransmittedPart) {
  // Blender 3.4's Refraction node has no multiscatter GGX; cycles_refraction's multi_ggx is
  // the multiscatter glass restricted to transmission: the same f below, none above.
  const RGBValue color{0.9, 0.8, 0.7};
  const BxDFPtr refraction = make_dielectric("cycles_refraction", "multi_ggx", 0.5, 1.5, color);
  const BxDFPtr glass = make_dielectric("cycles_glass", "multi_ggx", 0.5, 1.5, color);
  EXPECT_EQ(refraction->flags(), kTransmission | kGlossy);
  PCG32 rng(7);
  int transmitted = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 wo = random_sphere(rng), wi = random_sphere(rng);
    const RGB f = refraction->f(wo, wi), g = glass->f(wo, wi);
    if (wo.z * wi.z < 0.0f) {
      ++transmitted;
      EXPECT_EQ(f.r, g.r) << "wo " << wo.z << " wi " << wi.z;
      EXPECT_EQ(f.b, g.b);
    } else {
      EXPECT_TRUE(f.is_black()) << "reflected pair wo " << wo.z << " wi " << wi.z;
    }
    const BxDFSample s = refraction->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
    if (s.valid()) {
      EXPECT_LT(s.wi.z * wo.z, 0.0f) << "sampled a reflection";
    }
  }
  EXPECT_GT(transmitted, 50);
}

// Cycles draws a rough refraction from its facets alone, so the light of the pairs no facet
// facing wo refracts into reaches its images only by light sampling. sample_f does the same
// (for Glass, Refraction and the Principled BSDF's glass), its weight f·|cos θi| over the
// density of that draw: its mean is ∫ f |cos θi| over the pairs the facets reach, while the
// exact sampler's mean is ∫ f |cos θi| over every pair. Measured here with the exact sampler
// split by whether a pair is one the facets reach (pdf of the facet draw > 0).
TEST(CyclesGlass, CyclesSampleDrawsTheRefractionFromItsFacetsAlone) {
  ParamSet principled;
  principled.set("transmission", 1.0);
  principled.set("roughness", 0.2);
  principled.set("transmission_roughness", 1.0);
  principled.set("base_color", RGBValue{1, 1, 1});
  const struct {
    const char* label;
    BxDFPtr model;
    double eta;  // index below over index above
  } cases[] = {
      {"glass ggx 0.8", make_dielectric("cycles_glass", "ggx", 0.8, 1.45), 1.45},
      {"refraction beckmann 0.7", make_dielectric("cycles_refraction", "beckmann", 0.7, 1.3), 1.3},
      {"principled transmission roughness 1", make("cycles_principled", principled), 1.45},
  };
  for (const auto& c : cases) {
    EXPECT_FALSE(c.model->sample_f_is_exact()) << c.label;
    for (const double cos_o : {0.9, 0.25, -0.6}) {
      const Vec3 wo(float(std::sqrt(1 - cos_o * cos_o)), 0.0f, float(cos_o));
      // wo's side: the pair turned so that wo is above, the index inverted below.
      const double eta = cos_o > 0 ? c.eta : 1.0 / c.eta;
      const auto reached = [&](const Vec3& wi) {
        const double s = cos_o > 0 ? 1.0 : -1.0;
        const D3 I{wo.x, wo.y, s * wo.z}, L{wi.x, wi.y, s * wi.z};
        if (L.z > 0) return true;  // reflection: every pair
        const D3 ht{-(eta * L.x + I.x), -(eta * L.y + I.y), -(eta * L.z + I.z)};
        const double up = ht.z < 0 ? -1.0 : 1.0;
        return up * dot3(ht, I) > 0 && up * dot3(ht, L) < 0;
      };
      constexpr int kN = 400000;
      PCG32 rng(31);
      double cycles_sum = 0, cycles_sq = 0, exact_sum = 0, exact_sq = 0, reached_sum = 0,
             reached_sq = 0;
      int unreached_draws = 0;
      for (int i = 0; i < kN; ++i) {
        const Point2 u(rng.uniform(), rng.uniform());
        const BxDFSample s = c.model->sample_f(wo, u);
        if (s.valid()) {
          const double w = s.f.g * std::fabs(s.wi.z) / s.pdf;
          cycles_sum += w;
          cycles_sq += w * w;
          unreached_draws += !reached(s.wi);
          // pdf is still the mixture's, the density MIS weighs with.
          EXPECT_NEAR(s.pdf, c.model->pdf(wo, s.wi), 1e-3 * s.pdf) << c.label;
        }
        const BxDFSample e = c.model->sample_f_exact(wo, u);
        if (e.valid()) {
          const double w = e.f.g * std::fabs(e.wi.z) / e.pdf;
          exact_sum += w;
          exact_sq += w * w;
          if (reached(e.wi)) {
            reached_sum += w;
            reached_sq += w * w;
          }
        }
      }
      const auto mean_and_error = [](double sum, double sq) {
        const double mean = sum / kN;
        return std::pair<double, double>{mean, std::sqrt((sq / kN - mean * mean) / kN)};
      };
      const auto [cycles_mean, cycles_error] = mean_and_error(cycles_sum, cycles_sq);
      const auto [reached_mean, reached_error] = mean_and_error(reached_sum, reached_sq);
      const auto [exact_mean, exact_error] = mean_and_error(exact_sum, exact_sq);
      SCOPED_TRACE(std::string(c.label) + " cos θo " + std::to_string(cos_o));
      EXPECT_EQ(unreached_draws, 0);
      EXPECT_NEAR(cycles_mean, reached_mean, 5 * std::hypot(cycles_error, reached_error));
      // Towards grazing the unreached pairs hold light (so the case tells the samplers apart).
      if (cos_o == 0.25) {
        EXPECT_GT(exact_mean - reached_mean, 10 * exact_error);
      }
    }
  }
}

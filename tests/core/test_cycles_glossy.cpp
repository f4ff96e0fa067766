// cycles_glossy against Cycles 3.4's Glossy/Anisotropic BSDF, written out here in double
// precision the way Cycles' kernel computes it (bsdf_microfacet.h: the isotropic branch with
// tan²θm and the anisotropic branch with slopes; eval returns f·cos θi).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bxdf/registry.h"
#include "bxdf/rng.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;

struct CyclesReference {
  bool ggx = true;
  double alpha_x = 0, alpha_y = 0;

  // Node → closure: α = roughness², anisotropy clamped to ±0.99, then each α saturated.
  CyclesReference(const std::string& distribution, double roughness, double anisotropy) {
    ggx = distribution == "ggx";
    const double r = roughness * roughness;
    const double a = std::min(0.99, std::max(-0.99, anisotropy));
    if (a < 0) {
      alpha_x = r / (1 + a);
      alpha_y = r * (1 + a);
    } else {
      alpha_x = r * (1 - a);
      alpha_y = r / (1 - a);
    }
    alpha_x = std::min(1.0, alpha_x);
    alpha_y = std::min(1.0, alpha_y);
  }

  double G1(double cos_n, double cos_phi, double sin_phi) const {
    // α projected on the azimuth of the direction, then GGX's 2/(1 + sqrt(1 + α²tan²)) or
    // Beckmann's rational fit in a = 1/(α tan θ).
    double alpha2 =
        (cos_phi * cos_phi * alpha_x * alpha_x + sin_phi * sin_phi * alpha_y * alpha_y) /
        (cos_phi * cos_phi + sin_phi * sin_phi);
    if (alpha_x == alpha_y) alpha2 = alpha_x * alpha_y;
    const double tan2 = (1 - cos_n * cos_n) / (cos_n * cos_n);
    if (ggx) return 2 / (1 + std::sqrt(1 + alpha2 * tan2));
    const double a = 1 / std::sqrt(alpha2 * tan2);
    return a < 1.6 ? (3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a) : 1.0;
  }

  // Cycles' eval (f · cos θi), then divided by cos θi.
  double f(const Vec3& I, const Vec3& omega_in) const {
    const double cos_no = I.z, cos_ni = omega_in.z;
    if (!(cos_no > 0 && cos_ni > 0)) return 0;
    double mx = I.x + omega_in.x, my = I.y + omega_in.y, mz = I.z + omega_in.z;
    const double len = std::sqrt(mx * mx + my * my + mz * mz);
    mx /= len;
    my /= len;
    mz /= len;
    const double alpha2 = alpha_x * alpha_y;
    const double cos_m2 = mz * mz, cos_m4 = cos_m2 * cos_m2;
    double D;
    if (alpha_x == alpha_y) {
      const double tan_m2 = (1 - cos_m2) / cos_m2;
      D = ggx ? alpha2 / (kPiD * cos_m4 * (alpha2 + tan_m2) * (alpha2 + tan_m2))
              : std::exp(-tan_m2 / alpha2) / (kPiD * alpha2 * cos_m4);
    } else {
      const double sx = -mx / (mz * alpha_x), sy = -my / (mz * alpha_y);
      if (ggx) {
        const double slope_len = 1 + sx * sx + sy * sy;
        D = 1 / (slope_len * slope_len * kPiD * alpha2 * cos_m4);
      } else {
        D = std::exp(-sx * sx - sy * sy) / (kPiD * alpha2 * cos_m4);
      }
    }
    const double G = G1(cos_no, I.x, I.y) * G1(cos_ni, omega_in.x, omega_in.y);
    const double eval = D * G * 0.25 / cos_no;
    return eval / cos_ni;
  }
};

BxDFPtr make_glossy(const std::string& distribution, double roughness, double anisotropy,
                    double color = 0.9) {
  ParamSet p;
  p.set("color", color);
  p.set("distribution", distribution);
  p.set("roughness", roughness);
  p.set("anisotropy", anisotropy);
  return make("cycles_glossy", p);
}

Vec3 random_upper(PCG32& rng) {
  const double z = 0.02 + 0.98 * rng.uniform_double();
  const double r = std::sqrt(1.0 - z * z), phi = 2.0 * kPiD * rng.uniform_double();
  return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

}  // namespace

TEST(CyclesGlossy, MatchesCyclesFormula) {
  PCG32 rng(17);
  for (const std::string distribution : {"ggx", "beckmann"}) {
    for (const double roughness : {0.2, 0.5, 0.9, 1.0}) {
      for (const double anisotropy : {0.0, 0.5, -0.7, 1.0}) {
        SCOPED_TRACE(testing::Message()
                     << distribution << " r=" << roughness << " a=" << anisotropy);
        const CyclesReference ref(distribution, roughness, anisotropy);
        const BxDFPtr m = make_glossy(distribution, roughness, anisotropy);
        int nonzero = 0;
        for (int i = 0; i < 500; ++i) {
          // Every other wi comes from the model's sampler, only to look inside narrow lobes.
          const Vec3 wo = random_upper(rng);
          Vec3 wi = random_upper(rng);
          if (i % 2) {
            const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
            if (!s.valid()) continue;
            wi = s.wi;
          }
          const double expected = 0.9 * ref.f(wo, wi);
          // The model works in float: its unit inputs and half vector carry ~1e-7 of error,
          // which 1/|wo + wi| (small near grazing) and the slope x/α (one α tiny when
          // a = 1: αx = r²/100) magnify. Beckmann's visible-normal sampler puts wi deep inside
          // those lobes, where the magnification is largest (up to ~5e-7/(α|wo + wi|)).
          const double rel_tol =
              2e-4 + 6e-7 / (std::min(ref.alpha_x, ref.alpha_y) * double(length(wo + wi)));
          nonzero += expected > 1e-3;
          EXPECT_NEAR(m->f(wo, wi).g, expected, rel_tol * expected + 1e-7);
          // Two-sided, like Cycles with its normal turned to the viewer.
          EXPECT_EQ(m->f(Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z)).g, m->f(wo, wi).g);
        }
        EXPECT_GT(nonzero, 100);
      }
    }
  }
}

TEST(CyclesGlossy, AnisotropyMapping) {
  // a = 0.5, roughness 0.6: r = 0.36, αx = 0.18, αy = 0.72, so the lobe is wider along y:
  // the same tilt of the half vector costs less along y than along x.
  const BxDFPtr m = make_glossy("ggx", 0.6, 0.5);
  const Vec3 wo(0, 0, 1);
  const float s = std::sin(0.4f), c = std::cos(0.4f);
  // wi reflected about a half vector tilted by 0.2 rad towards x, resp. y.
  const Vec3 wi_x(s, 0, c), wi_y(0, s, c);
  EXPECT_GT(m->f(wo, wi_y).r, 2.0f * m->f(wo, wi_x).r);
  // Negative anisotropy swaps the axes: a = −0.5 gives αx = 0.72, αy = 0.18.
  const BxDFPtr n = make_glossy("ggx", 0.6, -0.5);
  EXPECT_NEAR(n->f(wo, wi_x).r, m->f(wo, wi_y).r, 1e-5f * m->f(wo, wi_y).r);
  EXPECT_NEAR(n->f(wo, wi_y).r, m->f(wo, wi_x).r, 1e-5f * m->f(wo, wi_x).r);
}

TEST(CyclesGlossy, SingularRoughnessIsAMirror) {
  // Roughness 0 (and anything with αx·αy <= 1e-7, like Cycles' kernel) is a delta mirror.
  for (const double roughness : {0.0, 1e-4, 0.015}) {
    const BxDFPtr m = make_glossy("ggx", roughness, 0.0, 0.6);
    EXPECT_TRUE(m->flags() & kSpecular) << roughness;
    const Vec3 wo(0.3f, -0.4f, std::sqrt(0.75f));
    EXPECT_EQ(m->f(wo, Vec3(-wo.x, -wo.y, wo.z)).r, 0.0f);
    EXPECT_EQ(m->pdf(wo, Vec3(-wo.x, -wo.y, wo.z)), 0.0f);
    const BxDFSample s = m->sample_f(wo, Point2(0.2f, 0.7f));
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s.pdf, 1.0f);
    EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(s.wi.y, -wo.y, 1e-6f);
    EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
    EXPECT_NEAR(s.f.r * std::fabs(s.wi.z) / s.pdf, 0.6f, 1e-6f);  // weight = colour
  }
  // Just above the threshold it is glossy again (0.018⁴ > 1e-7).
  EXPECT_TRUE(make_glossy("ggx", 0.018, 0.0)->flags() & kGlossy);
}

TEST(CyclesGlossy, ParametersAreRefusedByName) {
  ParamSet p;
  p.set("roughness", 1.5);
  try {
    make("cycles_glossy", p);
    FAIL() << "roughness 1.5 accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'roughness'"), std::string::npos) << e.what();
  }
  p = ParamSet();
  p.set("distribution", "phong");
  EXPECT_THROW(make("cycles_glossy", p), ParameterError);
}

namespace {

// Cycles' bsdf_ashikhmin_shirley_eval written out in double: the node's α (roughness², the
// anisotropy mapping of the GGX case, saturated) clamped to [1e-4, 1], n = 2/α² − 2, eval =
// cos θi · norm · lobe · pump, divided here by cos θi. Also its pdf.
struct CyclesAshikhminShirley {
  double n_x, n_y;
  CyclesAshikhminShirley(double roughness, double anisotropy) {
    const CyclesReference alphas("ggx", roughness, anisotropy);
    const double ax = std::min(1.0, std::max(1e-4, alphas.alpha_x));
    const double ay = std::min(1.0, std::max(1e-4, alphas.alpha_y));
    n_x = 2 / (ax * ax) - 2;
    n_y = 2 / (ay * ay) - 2;
  }
  // {f, pdf}
  std::pair<double, double> eval(const Vec3& I, const Vec3& O) const {
    double n_dot_i = I.z, n_dot_o = O.z;
    if (!(n_dot_i > 0 && n_dot_o > 0)) return {0, 0};
    const double cos_ni = O.z;
    n_dot_i = std::max(n_dot_i, 1e-6);
    n_dot_o = std::max(n_dot_o, 1e-6);
    double hx = double(I.x) + O.x, hy = double(I.y) + O.y, hz = double(I.z) + O.z;
    const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
    hx /= len;
    hy /= len;
    hz /= len;
    const double h_dot_i = std::max(std::fabs(hx * I.x + hy * I.y + hz * I.z), 1e-6);
    const double h_dot_n = std::max(hz, 1e-6);
    const double pump = 1 / std::max(1e-6, h_dot_i * std::max(n_dot_o, n_dot_i));
    double lobe, norm;
    if (n_x == n_y) {
      lobe = std::pow(h_dot_n, n_x);
      norm = (n_x + 1) / (8 * kPiD);
    } else {
      lobe = h_dot_n < 1 ? std::pow(h_dot_n, (n_x * hx * hx + n_y * hy * hy) /
                                                 (1 - h_dot_n * h_dot_n))
                         : 1.0;
      norm = std::sqrt((n_x + 1) * (n_y + 1)) / (8 * kPiD);
    }
    const double out = n_dot_o * norm * lobe * pump;
    return {out / cos_ni, norm * lobe / h_dot_i};
  }
};

}  // namespace

TEST(CyclesGlossy, AshikhminShirleyMatchesCyclesFormula) {
  PCG32 rng(23);
  for (const double roughness : {0.1, 0.3, 0.6, 1.0}) {
    for (const double anisotropy : {0.0, 0.4, -0.8}) {
      SCOPED_TRACE(testing::Message() << "r=" << roughness << " a=" << anisotropy);
      const CyclesAshikhminShirley ref(roughness, anisotropy);
      const BxDFPtr m = make_glossy("ashikhmin_shirley", roughness, anisotropy);
      EXPECT_TRUE(m->flags() & kGlossy);
      int nonzero = 0;
      for (int i = 0; i < 400; ++i) {
        const Vec3 wo = random_upper(rng);
        Vec3 wi = random_upper(rng);
        if (i % 2) {
          const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
          if (!s.valid()) continue;
          wi = s.wi;
        }
        const auto [f, pdf] = ref.eval(wo, wi);
        // cos θh^n with n up to 2e4 (roughness 0.1) turns float's 1e-7 in cos θh into
        // n·1e-7 relative.
        const double rel_tol = 2e-5 + 2e-7 * std::max(ref.n_x, ref.n_y);
        nonzero += f > 1e-3;
        EXPECT_NEAR(m->f(wo, wi).g, 0.9 * f, rel_tol * 0.9 * f + 1e-7);
        EXPECT_NEAR(m->pdf(wo, wi), pdf, rel_tol * pdf + 1e-7);
      }
      EXPECT_GT(nonzero, 50);
    }
  }
}

TEST(CyclesGlossy, AshikhminShirleyIsSingularAtTheAlphaFloor) {
  // α = roughness² below 1e-4 is raised to 1e-4, which Cycles treats as a mirror.
  for (const double roughness : {0.0, 0.005, 0.01}) {
    const BxDFPtr m = make_glossy("ashikhmin_shirley", roughness, 0.0, 0.6);
    EXPECT_TRUE(m->is_delta()) << roughness;
    const BxDFSample s = m->sample_f(Vec3(0.6f, 0.0f, 0.8f), Point2(0.3f, 0.3f));
    ASSERT_TRUE(s.valid());
    EXPECT_NEAR(s.f.r * s.wi.z, 0.6f, 1e-6f);
  }
  EXPECT_FALSE(make_glossy("ashikhmin_shirley", 0.011, 0.0)->is_delta());
}

TEST(CyclesGlossy, SharpIsAMirrorWhateverTheRoughness) {
  const BxDFPtr m = make_glossy("sharp", 0.8, 0.5, 0.7);
  EXPECT_TRUE(m->is_delta());
  const Vec3 wo = normalize(Vec3(0.2f, 0.5f, 0.6f));
  const BxDFSample s = m->sample_f(wo, Point2(0.9f, 0.1f));
  ASSERT_TRUE(s.valid());
  EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s.wi.y, -wo.y, 1e-6f);
  EXPECT_NEAR(s.f.g * s.wi.z, 0.7f, 1e-6f);
}

// cycles_velvet against Cycles 3.4's bsdf_ashikhmin_velvet_eval written out here in double
// (eval returns f·cos θi; σ = max(saturate(sigma), 0.01)), and its uniform sampling.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;

double cycles_velvet_f(double sigma, const Vec3& I, const Vec3& L) {
  const double s = std::max(sigma, 0.01), inv_sigma2 = 1 / (s * s);
  const double cos_no = I.z, cos_ni = L.z;
  if (!(cos_no > 0 && cos_ni > 0)) return 0;
  double hx = double(I.x) + L.x, hy = double(I.y) + L.y, hz = double(I.z) + L.z;
  const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
  hx /= len;
  hy /= len;
  hz /= len;
  const double cos_nh = hz, cos_ho = std::fabs(hx * I.x + hy * I.y + hz * I.z);
  if (!(std::fabs(cos_nh) < 1 - 1e-5 && cos_ho > 1e-5)) return 0;
  const double ratio = std::max(cos_nh / cos_ho, 1e-5);
  const double fac1 = 2 * std::fabs(ratio * cos_no), fac2 = 2 * std::fabs(ratio * cos_ni);
  const double sin_nh2 = 1 - cos_nh * cos_nh, sin_nh4 = sin_nh2 * sin_nh2;
  const double cot2 = cos_nh * cos_nh / sin_nh2;
  const double D = std::exp(-cot2 * inv_sigma2) * inv_sigma2 / kPiD / sin_nh4;
  const double G = std::min(1.0, std::min(fac1, fac2));
  return 0.25 * D * G / cos_no / cos_ni;
}

}  // namespace

TEST(CyclesVelvet, MatchesCyclesFormula) {
  PCG32 rng(31);
  for (const double sigma : {0.0, 0.05, 0.3, 1.0}) {
    ParamSet p;
    p.set("sigma", sigma);
    p.set("color", RGBValue{0.5, 0.5, 0.5});
    const BxDFPtr m = make("cycles_velvet", p);
    int nonzero = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 wo = sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
      const Vec3 wi = sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
      if (wo.z < 0.02f || wi.z < 0.02f) continue;
      const double expected = 0.5 * cycles_velvet_f(sigma, wo, wi);
      nonzero += expected > 1e-6;
      // exp(−cot²θh/σ²) magnifies float's error in cot²θh by cot²θh/σ² (up to ~100 here).
      EXPECT_NEAR(m->f(wo, wi).r, expected, 3e-5 * expected + 1e-7) << sigma;
      // Two-sided; uniform pdf on wo's side.
      EXPECT_EQ(m->f(Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z)).r, m->f(wo, wi).r);
      EXPECT_FLOAT_EQ(m->pdf(wo, wi), float(1 / (2 * kPiD)));
      EXPECT_EQ(m->pdf(wo, Vec3(wi.x, wi.y, -wi.z)), 0.0f);
    }
    // A narrow σ puts the sheen at grazing pairs only.
    EXPECT_GE(nonzero, sigma >= 0.3 ? 200 : (sigma >= 0.05 ? 20 : 1)) << sigma;
  }
}

TEST(CyclesVelvet, SigmaIsRefusedOutsideTheNodeRange) {
  ParamSet p;
  p.set("sigma", 1.5);
  try {
    make("cycles_velvet", p);
    FAIL() << "sigma 1.5 accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'sigma'"), std::string::npos) << e.what();
  }
}

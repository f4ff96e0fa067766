// The share of cosine-weighted samples in Cycles' rough refraction lobes
// (bxdf/microfacet/refraction_cover.h): the table is what the lobes give, the share stays in
// range whatever it is asked, and it lowers the second moment of the sampled estimate below a
// fixed share of 1/4 (what cycles_glass.h used) without moving its mean.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bxdf/microfacet/cycles_lobes.h"
#include "bxdf/microfacet/ggx.h"
#include "bxdf/microfacet/refraction_cover.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;
using cycles::CoverDistribution;

TEST(RefractionCover, ShareStaysInRangeWhateverItIsAsked) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const CoverDistribution d : {CoverDistribution::kGGX, CoverDistribution::kBeckmann}) {
    for (const float alpha : {-1.0f, 0.0f, 1e-8f, 0.09f, 1.0f, 4.0f, inf, nan}) {
      for (const float eta : {-1.0f, 0.0f, 1e-6f, 0.5f, 1.0f, 1.45f, 100.0f, inf, nan}) {
        for (const float cos_o : {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f, inf, nan}) {
          const float s = cycles::refraction_cover_share(d, alpha, eta, cos_o);
          ASSERT_TRUE(s >= cycles::kCoverShareMin && s <= cycles::kCoverShareMax)
              << "alpha " << alpha << " eta " << eta << " cos " << cos_o << " share " << s;
        }
      }
    }
  }
}

TEST(RefractionCover, TableHoldsWhatTheLobesGive) {
  // Entries where the uncovered part of f is large enough to estimate well from 64² fresh
  // samples (other seeds than the table's 128²), and entries where it is next to nothing.
  struct Entry {
    CoverDistribution d;
    int i, j, k;  // √α, ln η and cos θo indices
  };
  const Entry entries[] = {
      {CoverDistribution::kGGX, 6, 11, 3},       {CoverDistribution::kGGX, 9, 11, 0},
      {CoverDistribution::kGGX, 9, 5, 8},        {CoverDistribution::kGGX, 15, 11, 15},
      {CoverDistribution::kGGX, 15, 2, 4},       {CoverDistribution::kBeckmann, 9, 11, 1},
      {CoverDistribution::kBeckmann, 15, 13, 6}, {CoverDistribution::kGGX, 2, 11, 14},
      {CoverDistribution::kBeckmann, 4, 11, 10},
  };
  for (const Entry& e : entries) {
    const float alpha = cycles::cover_table_alpha(e.i), eta = cycles::cover_table_eta(e.j),
                cos_o = cycles::cover_table_cos(e.k);
    const float stored = cycles::cover_table_value(e.d, e.i, e.j, e.k);
    const float fresh = cycles::estimate_cover_share(e.d, alpha, eta, cos_o, 64, 77);
    EXPECT_NEAR(stored, fresh, 0.02f + 0.15f * fresh)
        << "distribution " << static_cast<int>(e.d) << " alpha " << alpha << " eta " << eta
        << " cos " << cos_o;
    // At a table point the interpolation returns the entry itself.
    EXPECT_NEAR(cycles::refraction_cover_share(e.d, alpha, eta, cos_o), stored, 1e-4f);
  }
  // The share follows the uncovered part of f: least for a smooth lobe near normal incidence,
  // large for a rough one at grazing incidence.
  EXPECT_LE(cycles::refraction_cover_share(CoverDistribution::kGGX, 0.01f, 1.45f, 0.95f), 0.02f);
  EXPECT_GE(cycles::refraction_cover_share(CoverDistribution::kGGX, 0.64f, 1.45f, 0.05f), 0.4f);
}

namespace {

struct Moments {
  double mean = 0.0, second = 0.0;
};

// The sampled estimate of ∫ f |cos θi| for a cycles_refraction model (its exact sampler, the
// one with the cover) and for the same lobe with a fixed share, on the same stratified numbers.
Moments model_moments(const BxDF& m, const Vec3& wo, int strata) {
  Moments out;
  PCG32 rng(3);
  for (int y = 0; y < strata; ++y)
    for (int x = 0; x < strata; ++x) {
      const BxDFSample s = m.sample_f_exact(wo, Point2((x + rng.uniform()) / strata,
                                                       (y + rng.uniform()) / strata));
      if (!s.valid()) continue;
      const double w = double(s.f.r) * std::fabs(s.wi.z) / s.pdf;
      out.mean += w;
      out.second += w * w;
    }
  out.mean /= double(strata) * strata;
  out.second /= double(strata) * strata;
  return out;
}

Moments fixed_share_moments(float alpha, float eta, const Vec3& wo, float share, int strata) {
  const cycles::RefractionLobe<microfacet::GGX> lobe{microfacet::GGX(alpha, alpha)};
  Moments out;
  PCG32 rng(3);
  for (int y = 0; y < strata; ++y)
    for (int x = 0; x < strata; ++x) {
      Point2 u((x + rng.uniform()) / strata, (y + rng.uniform()) / strata);
      Vec3 wi;
      bool ok;
      if (u.x < share) {
        wi = cycles::sample_refraction_cover(Point2(u.x / share, u.y));
        ok = wi.z < 0.0f;
      } else {
        ok = lobe.sample(wo, Point2((u.x - share) / (1.0f - share), u.y), eta, &wi);
      }
      if (!ok) continue;
      const double pdf =
          share * cycles::refraction_cover_pdf(wi) + (1.0 - share) * lobe.pdf(wo, wi, eta);
      if (!(pdf > 0.0)) continue;
      const double w = double(lobe.f(wo, wi, eta)) * std::fabs(wi.z) / pdf;
      out.mean += w;
      out.second += w * w;
    }
  out.mean /= double(strata) * strata;
  out.second /= double(strata) * strata;
  return out;
}

}  // namespace

TEST(RefractionCover, LowersTheSecondMomentOfAFixedQuarterAndKeepsTheMean) {
  for (const float roughness : {0.3f, 0.6f}) {
    for (const float cos_o : {0.1f, 0.5f, 0.95f}) {
      ParamSet p;
      p.set("distribution", std::string("ggx"));
      p.set("roughness", double(roughness));
      p.set("ior", 1.45);
      p.set("color", RGBValue{1, 1, 1});
      const BxDFPtr m = make("cycles_refraction", p);
      const Vec3 wo(std::sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
      const Moments table = model_moments(*m, wo, 256);
      const Moments quarter = fixed_share_moments(roughness * roughness, 1.45f, wo, 0.25f, 256);
      SCOPED_TRACE(testing::Message() << "roughness " << roughness << " cos " << cos_o);
      EXPECT_NEAR(table.mean, quarter.mean, 0.02 * quarter.mean);
      EXPECT_LT(table.second, 1.01 * quarter.second);
    }
  }
  // Where the facets cover nearly all of f the gain is the quarter's whole cost (1/0.75).
  ParamSet p;
  p.set("distribution", std::string("ggx"));
  p.set("roughness", 0.3);
  p.set("ior", 1.45);
  p.set("color", RGBValue{1, 1, 1});
  const Vec3 wo(std::sqrt(1.0f - 0.81f), 0.0f, 0.9f);
  const Moments table = model_moments(*make("cycles_refraction", p), wo, 256);
  const Moments quarter = fixed_share_moments(0.09f, 1.45f, wo, 0.25f, 256);
  EXPECT_LT(table.second, 0.85 * quarter.second);
}

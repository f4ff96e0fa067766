// specular_reflection: the mirror direction, pdf 1, and the seed's weight F(cos θo) R / |cos θi|
// for each Fresnel kind, F evaluated independently in the test; f and pdf are 0.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/models/specular_reflection.h"
#include "bxdf/registry.h"

using namespace bxdf;

namespace {

double dielectric_reference(double cos_i, double eta_i, double eta_t) {
  const double sin_t = eta_i / eta_t * std::sqrt(1.0 - cos_i * cos_i);
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double r_par = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  const double r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  return 0.5 * (r_par * r_par + r_perp * r_perp);
}

double conductor_seed_reference(double c, double eta, double k) {
  const double ek = eta * eta + k * k;
  const double r_par2 = (ek * c * c - 2 * eta * c + 1) / (ek * c * c + 2 * eta * c + 1);
  const double r_perp2 = (ek - 2 * eta * c + c * c) / (ek + 2 * eta * c + c * c);
  return 0.5 * (r_par2 + r_perp2);
}

const RGBValue kReflectance = {0.9, 0.6, 0.3};

// Checks direction, pdf and weight for wo from above and (two-sided) from below.
void expect_mirror(const BxDF& m, const Vec3& wo_unit, const RGB& fresnel) {
  for (const Vec3& w : {wo_unit, Vec3(wo_unit.x, wo_unit.y, -wo_unit.z)}) {
    const BxDFSample s = m.sample_f(w, Point2(0.3f, 0.7f));
    ASSERT_TRUE(s.valid());
    EXPECT_NEAR(s.wi.x, -w.x, 1e-6);
    EXPECT_NEAR(s.wi.y, -w.y, 1e-6);
    EXPECT_NEAR(s.wi.z, w.z, 1e-6);
    EXPECT_EQ(s.pdf, 1.0f);
    EXPECT_EQ(s.flags, static_cast<uint32_t>(kReflection | kSpecular));
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.f[c] * std::fabs(s.wi.z), fresnel[c] * kReflectance[c], 1e-6) << c;
    // A delta lobe: no density or value for any given pair, even the mirror pair itself.
    EXPECT_TRUE(m.f(w, s.wi).is_black());
    EXPECT_EQ(m.pdf(w, s.wi), 0.0f);
  }
}

}  // namespace

TEST(SpecularReflection, DefaultsToADielectric) {
  BxDFPtr m = make("specular_reflection");
  EXPECT_EQ(m->params().string("fresnel"), "dielectric");
  EXPECT_TRUE(m->is_delta());
  EXPECT_EQ(flags_to_string(m->flags()), "reflection|specular");
}

TEST(SpecularReflection, NoFresnelWeighsByReflectanceOnly) {
  ParamSet p;
  p.set("reflectance", kReflectance);
  p.set("fresnel", "none");
  expect_mirror(*make("specular_reflection", p), normalize(Vec3(0.3f, -0.4f, 0.5f)), RGB(1.0f));
}

TEST(SpecularReflection, DielectricWeighsByFresnelAtCosThetaO) {
  ParamSet p;
  p.set("reflectance", kReflectance);
  p.set("fresnel", "dielectric");
  p.set("eta_i", 1.0);
  p.set("eta_t", 1.7);
  BxDFPtr m = make("specular_reflection", p);
  for (double theta : {0.0, 0.5, 1.0, 1.5}) {
    const Vec3 wo(static_cast<float>(std::sin(theta)), 0.0f, static_cast<float>(std::cos(theta)));
    expect_mirror(*m, wo, RGB(static_cast<float>(dielectric_reference(std::cos(theta), 1.0, 1.7))));
  }
}

TEST(SpecularReflection, ConductorWeighsByTheSeedConductorFormula) {
  ParamSet p;
  p.set("reflectance", kReflectance);
  p.set("fresnel", "conductor");
  p.set("eta", RGBValue{0.370, 0.177, 0.617});  // gold, silver, copper from the seed
  p.set("k", RGBValue{2.820, 3.638, 2.630});
  BxDFPtr m = make("specular_reflection", p);
  for (double theta : {0.2, 1.0, 1.4}) {
    const double c = std::cos(theta);
    const RGB fresnel(static_cast<float>(conductor_seed_reference(c, 0.370, 2.820)),
                      static_cast<float>(conductor_seed_reference(c, 0.177, 3.638)),
                      static_cast<float>(conductor_seed_reference(c, 0.617, 2.630)));
    expect_mirror(*m, Vec3(static_cast<float>(std::sin(theta)), 0.0f, static_cast<float>(c)),
                  fresnel);
  }
}

TEST(SpecularReflection, RhoIsFresnelTimesReflectance) {
  ParamSet p;
  p.set("reflectance", 0.8);
  BxDFPtr m = make("specular_reflection", p);  // dielectric 1 → 1.5
  const RGB rho = m->rho_hd(Vec3(0, 0, 1), 16);
  EXPECT_NEAR(rho.r, 0.8 * 0.04, 1e-6);
}

TEST(SpecularReflection, GrazingGivesNoSample) {
  BxDFPtr m = make("specular_reflection");
  EXPECT_FALSE(m->sample_f(Vec3(1, 0, 0), Point2(0.5f, 0.5f)).valid());
  EXPECT_FALSE(m->sample_f(Vec3(0, 0, 0), Point2(0.5f, 0.5f)).valid());
  // The kernel itself refuses a cosine so small that F R/|cos θi| would overflow.
  const SpecularReflection kernel(RGB(1.0f), Fresnel::none());
  EXPECT_FALSE(kernel.sample(Vec3(1.0f, 0.0f, 1e-40f), Point2(0.5f, 0.5f)).valid());
  const BxDFSample near = kernel.sample(Vec3(1.0f, 0.0f, 1e-20f), Point2(0.5f, 0.5f));
  ASSERT_TRUE(near.valid());
  EXPECT_NEAR(near.f.r, 1e20f, 1e14f);
}

TEST(SpecularReflection, IndicesShowOnlyForTheirFresnelKind) {
  const ModelInfo* info = find_model("specular_reflection");
  ASSERT_NE(info, nullptr);
  int checked = 0;
  for (const ParamSpec& s : info->params) {
    if (s.name == "eta_i" || s.name == "eta_t") {
      EXPECT_EQ(s.when_param, "fresnel");
      EXPECT_EQ(s.when_values, std::vector<std::string>{"dielectric"});
      ++checked;
    } else if (s.name == "eta" || s.name == "k") {
      EXPECT_EQ(s.when_param, "fresnel");
      EXPECT_EQ(s.when_values, std::vector<std::string>{"conductor"});
      ++checked;
    } else {
      EXPECT_TRUE(s.when_param.empty()) << s.name;
    }
  }
  EXPECT_EQ(checked, 4);
}

TEST(SpecularReflection, RefusesNonPositiveIndicesAndNegativeK) {
  const std::pair<const char*, Value> bad[] = {{"eta_t", Value(0.0)},
                                               {"eta_i", Value(-1.0)},
                                               {"eta", Value(RGBValue{0.5, 0.0, 0.5})},
                                               {"k", Value(RGBValue{1.0, -0.1, 1.0})},
                                               {"fresnel", Value("schlick")}};
  for (const auto& [name, value] : bad) {
    ParamSet p;
    p.set(name, value);
    try {
      make("specular_reflection", p);
      ADD_FAILURE() << "accepted " << name << " = " << value.to_string();
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + name + "'"), std::string::npos)
          << e.what();
    }
  }
}

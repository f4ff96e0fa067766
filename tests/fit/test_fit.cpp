// Fitting: parameters used to generate data are recovered (within 1%), the errors are the
// Ngan et al. cosine-weighted L2 error, a fit to a real Cornell paint is better than a stated
// bound, and bad requests are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "bxdf/fit/fit.h"
#include "bxdf/measured/measured_data.h"
#include "bxdf/measured/merl.h"
#include "bxdf/registry.h"

using namespace bxdf;
using bxdf::fit::FitOptions;
using bxdf::fit::FitResult;
using bxdf::fit::fit_error;

namespace {

const std::string kDataDir = BXDF_TEST_DATA_DIR "/measured";
constexpr double kPiD = 3.14159265358979323846;

// The measurement geometry of a real Cornell file, with values replaced by `f`.
template <class F>
std::vector<MeasuredSample> synthetic_samples(F f) {
  std::vector<MeasuredSample> out = load_measured_data(kDataDir + "/garnet_red.brdf")->samples();
  for (MeasuredSample& s : out) s.value = f(s.wo, s.wi);
  return out;
}

// Independent double-precision formulas (reference/models.md) for the generating models.
double lafortune_lobe(const Vec3& wo, const Vec3& wi, double cxy, double cz, double n) {
  const double base = cxy * (double(wo.x) * wi.x + double(wo.y) * wi.y) + cz * double(wo.z) * wi.z;
  return base > 0.0 ? std::pow(base, n) : 0.0;
}

double fresnel(double c, double eta) {
  const double ct = std::sqrt(1.0 - (1.0 - c * c) / (eta * eta));
  const double rp = (eta * c - ct) / (eta * c + ct), rs = (c - eta * ct) / (c + eta * ct);
  return 0.5 * (rp * rp + rs * rs);
}

// ρs D G F / (4 cos θi cos θo) with V-groove G, for a D given cos θh.
template <class D>
double torrance_sparrow(const Vec3& wo, const Vec3& wi, double eta, D d) {
  const Vec3 h = normalize(wo + wi);
  const double g = std::min({1.0, 2.0 * h.z * wo.z / dot(wo, h), 2.0 * h.z * wi.z / dot(wo, h)});
  return d(double(h.z)) * g * fresnel(dot(wi, h), eta) / (4.0 * wo.z * wi.z);
}

// The fitted parameters, after checking that the fit is the expected registry model.
const ParamSet& fitted(const FitResult& r, const std::string& model) {
  EXPECT_EQ(r.model, model);
  return r.params;
}

void expect_rel(double got, double want, double tol, const char* what) {
  EXPECT_NEAR(got, want, tol * std::fabs(want)) << what;
}

}  // namespace

TEST(Fit, LambertianIsTheWeightedLeastSquaresOptimum) {
  const auto samples = synthetic_samples([](const Vec3&, const Vec3&) {
    return RGB(0.5f / kPi, 0.25f / kPi, 0.125f / kPi);
  });
  FitOptions o;
  o.model = "lambertian";
  const FitResult r = fit::fit(samples, o);
  const RGBValue rho = fitted(r, "lambertian").rgb("reflectance");
  EXPECT_NEAR(rho[0], 0.5, 1e-6);
  EXPECT_NEAR(rho[1], 0.25, 1e-6);
  EXPECT_NEAR(rho[2], 0.125, 1e-6);
  EXPECT_LT(r.report.error, 1e-7);
  EXPECT_NEAR(fit_error(samples, *r.build()), r.report.error, 1e-6);
}

TEST(Fit, RecoversOneLobeLafortune) {
  const double diffuse[3] = {0.3, 0.2, 0.1}, cxy[3] = {-1.0, -0.95, -1.05}, cz[3] = {0.9, 0.95, 1.0},
               n[3] = {20.0, 35.0, 12.0};
  const auto samples = synthetic_samples([&](const Vec3& wo, const Vec3& wi) {
    RGB v;
    for (int c = 0; c < 3; ++c)
      v[c] = static_cast<float>(diffuse[c] / kPiD + lafortune_lobe(wo, wi, cxy[c], cz[c], n[c]));
    return v;
  });
  FitOptions o;
  o.model = "lafortune";
  o.lobes = 1;
  const FitResult r = fit::fit(samples, o);
  const ParamSet& p = fitted(r, "lafortune");
  const ParamSet& lobe = p.list("lobes").at(0);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE(c);
    expect_rel(p.rgb("diffuse")[size_t(c)], diffuse[c], 0.01, "diffuse");
    expect_rel(lobe.rgb("cx")[size_t(c)], cxy[c], 0.01, "cx");
    expect_rel(lobe.rgb("cy")[size_t(c)], cxy[c], 0.01, "cy");
    expect_rel(lobe.rgb("cz")[size_t(c)], cz[c], 0.01, "cz");
    expect_rel(lobe.rgb("exponent")[size_t(c)], n[c], 0.01, "exponent");
  }
  EXPECT_LT(r.report.error, 1e-4 * r.report.baseline_error);
}

TEST(Fit, RecoversTwoLobeLafortune) {
  // A forward mirror lobe and a broad retro-reflective one (Cxy > 0), grey.
  const auto samples = synthetic_samples([](const Vec3& wo, const Vec3& wi) {
    return RGB(static_cast<float>(0.2 / kPiD + lafortune_lobe(wo, wi, -1.0, 1.0, 30.0) +
                                  lafortune_lobe(wo, wi, 0.6, 0.6, 4.0)));
  });
  FitOptions o;
  o.model = "lafortune";
  o.lobes = 2;
  const FitResult r = fit::fit(samples, o);
  const ParamSet& p = fitted(r, "lafortune");
  std::vector<ParamSet> lobes = p.list("lobes");
  std::sort(lobes.begin(), lobes.end(), [](const ParamSet& a, const ParamSet& b) {
    return a.rgb("exponent")[0] > b.rgb("exponent")[0];
  });
  for (int c = 0; c < 3; ++c) {
    expect_rel(p.rgb("diffuse")[size_t(c)], 0.2, 0.01, "diffuse");
    expect_rel(lobes[0].rgb("cx")[size_t(c)], -1.0, 0.01, "lobe 1 cx");
    expect_rel(lobes[0].rgb("cz")[size_t(c)], 1.0, 0.01, "lobe 1 cz");
    expect_rel(lobes[0].rgb("exponent")[size_t(c)], 30.0, 0.01, "lobe 1 n");
    expect_rel(lobes[1].rgb("cx")[size_t(c)], 0.6, 0.01, "lobe 2 cx");
    expect_rel(lobes[1].rgb("cz")[size_t(c)], 0.6, 0.01, "lobe 2 cz");
    expect_rel(lobes[1].rgb("exponent")[size_t(c)], 4.0, 0.01, "lobe 2 n");
  }
}

TEST(Fit, RecoversBlinnAndBeckmannTorranceSparrow) {
  const double rd[3] = {0.4, 0.1, 0.05}, rs[3] = {0.9, 0.8, 0.7};
  {
    const double e = 150.0, eta = 1.6;
    const auto samples = synthetic_samples([&](const Vec3& wo, const Vec3& wi) {
      const double s = torrance_sparrow(wo, wi, eta, [&](double c) {
        return (e + 2.0) / (2.0 * kPiD) * std::pow(c, e);
      });
      RGB v;
      for (int c = 0; c < 3; ++c) v[c] = static_cast<float>(rd[c] / kPiD + rs[c] * s);
      return v;
    });
    FitOptions o;
    o.model = "blinn";
    const FitResult r = fit::fit(samples, o);
    const ParamSet& m = fitted(r, "microfacet");
    for (int c = 0; c < 3; ++c) {
      expect_rel(m.rgb("diffuse")[size_t(c)], rd[c], 0.01, "blinn diffuse");
      expect_rel(m.rgb("reflectance")[size_t(c)], rs[c], 0.01, "blinn specular");
    }
    expect_rel(m.number("exponent"), e, 0.01, "exponent");
    expect_rel(m.number("eta_t"), eta, 0.01, "eta");
    EXPECT_EQ(m.string("distribution"), "blinn");
  }
  {
    const double alpha = 0.15, eta = 1.4;
    const auto samples = synthetic_samples([&](const Vec3& wo, const Vec3& wi) {
      const double s = torrance_sparrow(wo, wi, eta, [&](double c) {
        const double t2 = (1.0 - c * c) / (c * c);
        return std::exp(-t2 / (alpha * alpha)) / (kPiD * alpha * alpha * c * c * c * c);
      });
      RGB v;
      for (int c = 0; c < 3; ++c) v[c] = static_cast<float>(rd[c] / kPiD + rs[c] * s);
      return v;
    });
    FitOptions o;
    o.model = "cook_torrance";
    const FitResult r = fit::fit(samples, o);
    const ParamSet& m = fitted(r, "microfacet");
    for (int c = 0; c < 3; ++c) {
      expect_rel(m.rgb("diffuse")[size_t(c)], rd[c], 0.01, "ct diffuse");
      expect_rel(m.rgb("reflectance")[size_t(c)], rs[c], 0.01, "ct specular");
    }
    expect_rel(m.number("alpha_x"), alpha, 0.01, "alpha");
    expect_rel(m.number("eta_t"), eta, 0.01, "eta");
  }
}

// Fit quality on a real paint (krylon_blue): stated bounds on the RMS cosine-weighted error,
// against 0.258 for f = 0 and 0.255 for the best Lambertian.
TEST(Fit, CornellPaintFitsBetterThanStatedBounds) {
  const auto data = load_measured_data(kDataDir + "/krylon_blue.brdf");
  FitOptions o;
  o.model = "lambertian";
  const double lambert = fit::fit(*data, o).report.error;
  o.model = "lafortune";
  o.lobes = 2;
  const FitResult laf = fit::fit(*data, o);
  o.model = "cook_torrance";
  const FitResult ct = fit::fit(*data, o);
  EXPECT_LT(laf.report.error, 0.060);
  EXPECT_LT(ct.report.error, 0.050);
  EXPECT_LT(laf.report.error, lambert / 4.0);
  EXPECT_EQ(laf.report.samples, 1439u);
  EXPECT_GE(laf.report.starts, 2);
  EXPECT_GT(laf.report.iterations, 0);
  EXPECT_GT(laf.report.seconds, 0.0);
}

TEST(Fit, RefusesBadRequests) {
  const auto samples = load_measured_data(kDataDir + "/acryl_blue.brdf")->samples();
  auto message = [&](FitOptions o, std::vector<MeasuredSample> s) {
    try {
      fit::fit(s, o);
    } catch (const ParameterError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  FitOptions o;
  o.model = "phong";
  EXPECT_NE(message(o, samples).find("'phong'"), std::string::npos);
  o.model = "lafortune";
  o.lobes = 4;
  EXPECT_NE(message(o, samples).find("lobes = 4"), std::string::npos);
  o.lobes = 1;
  EXPECT_NE(message(o, {samples.begin(), samples.begin() + 3}).find("usable samples"), std::string::npos);
  // Through the registry: a measured model is accepted, anything else is refused by name.
  ParamSet p;
  p.set("path", kDataDir + "/acryl_blue.brdf");
  o.model = "lambertian";
  EXPECT_EQ(fit::fit(*make("measured", p), o).report.samples, 1439u);
  try {
    fit::fit(*make("lambertian"), o);
    ADD_FAILURE() << "fitting to a lambertian model was accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'lambertian'"), std::string::npos) << e.what();
  }
}

// The fitted parameters, rebuilt through the registry (lambertian, lafortune, microfacet with
// its diffuse term), give the error the fit reports: the fit's formulas are the registry
// models' formulas, and the result is one model that bxdf::make rebuilds by name.
TEST(Fit, RegistryModelsReproduceTheFittedError) {
  const auto samples = load_measured_data(kDataDir + "/garnet_red.brdf")->samples();
  for (const std::string& model : bxdf::fit::fit_model_names()) {
    SCOPED_TRACE(model);
    FitOptions o;
    o.model = model;
    o.lobes = 2;
    o.max_starts = 2;
    const FitResult r = fit::fit(samples, o);
    const BxDFPtr model_from_registry = make(r.model, r.params);
    EXPECT_EQ(model_from_registry->model_name(), r.model);
    if (model != "lambertian" && model != "lafortune") {
      EXPECT_EQ(r.model, "microfacet");
      EXPECT_FALSE(RGB(float(r.params.rgb("diffuse")[0]), float(r.params.rgb("diffuse")[1]),
                       float(r.params.rgb("diffuse")[2])).is_black());
    }
    const double rebuilt = fit_error(samples, *model_from_registry);
    EXPECT_EQ(rebuilt, fit_error(samples, *r.build()));
    EXPECT_NEAR(rebuilt, r.report.error, 1e-3 * r.report.error);
  }
}

// End to end through a MERL file: Cook–Torrance values written at the cell centres of a
// full-size synthetic .binary file, read back, sampled with a stride and fitted.
TEST(Fit, RecoversCookTorranceFromASyntheticMerlFile) {
  const double rd[3] = {0.3, 0.2, 0.1}, rs[3] = {0.8, 0.9, 1.0}, alpha = 0.2, eta = 1.5;
  std::vector<double> ch[3];
  for (auto& c : ch) c.resize(kMerlCells);
  for (int h = 0; h < kMerlThetaH; ++h)
    for (int t = 0; t < kMerlThetaD; ++t)
      for (int p = 0; p < kMerlPhiD; ++p) {
        const HalfDiff a = merl_cell_center(h, t, p);
        double wi[3], wo[3];
        directions_from_half_diff(a.theta_h, a.theta_d, a.phi_d, wi, wo);
        const size_t i = merl_cell(h, t, p);
        if (wi[2] <= 0.0 || wo[2] <= 0.0) {
          for (auto& c : ch) c[i] = -1.0;
          continue;
        }
        auto vec = [](const double* w) {
          return Vec3(static_cast<float>(w[0]), static_cast<float>(w[1]), static_cast<float>(w[2]));
        };
        const Vec3 vi = vec(wi), vo = vec(wo);
        const double s = torrance_sparrow(vo, vi, eta, [&](double c) {
          const double t2 = (1.0 - c * c) / (c * c);
          return std::exp(-t2 / (alpha * alpha)) / (kPiD * alpha * alpha * c * c * c * c);
        });
        for (int c = 0; c < 3; ++c) ch[c][i] = rd[c] / kPiD + rs[c] * s;
      }
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("bxdf_fit_" + std::to_string(::getpid()) + ".binary")).string();
  write_merl(path, ch[0], ch[1], ch[2]);
  const auto data = MeasuredData::read(path);
  std::filesystem::remove(path);
  FitOptions o;
  o.model = "cook_torrance";
  o.merl_stride = 8;
  const FitResult r = fit::fit(*data, o);
  EXPECT_GT(r.report.samples, 10000u);
  const ParamSet& m = fitted(r, "microfacet");
  for (int c = 0; c < 3; ++c) {
    expect_rel(m.rgb("diffuse")[size_t(c)], rd[c], 0.01, "diffuse");
    expect_rel(m.rgb("reflectance")[size_t(c)], rs[c], 0.01, "specular");
  }
  expect_rel(m.number("alpha_x"), alpha, 0.01, "alpha");
  expect_rel(m.number("eta_t"), eta, 0.01, "eta");
}

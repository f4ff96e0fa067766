// Measured BRDFs: the spectral → RGB conversion, the Cornell and MERL readers (round trips
// through a synthetic MERL file written in the test, and refusal of bad files), and the
// `measured` model (positivity, reciprocity, isotropy, sampling consistency, χ², cache).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "bxdf/measured/cie1931.h"
#include "bxdf/measured/cornell.h"
#include "bxdf/measured/measured_data.h"
#include "bxdf/measured/merl.h"
#include "bxdf/models/measured.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"
#include "../scratch_folder.h"

using namespace bxdf;
namespace fs = std::filesystem;

namespace {

const std::string kDataDir = BXDF_TEST_DATA_DIR "/measured";

fs::path temp_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("bxdf_measured_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// Removes the temporary files (the synthetic MERL file is 35 MB) when the test program ends.
class RemoveTempDir : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("bxdf_measured_" + std::to_string(getpid())), ec);
  }
};
[[maybe_unused]] ::testing::Environment* const kRemoveTempDir =
    ::testing::AddGlobalTestEnvironment(new RemoveTempDir);

std::string write_text(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

using bxdf::test_support::error_of;

Vec3 random_upper(PCG32& rng) { return sample_uniform_hemisphere({rng.uniform(), rng.uniform()}); }

// The analytic BRDF written into the synthetic MERL file: smooth in (θh, θd, φd), reciprocal
// (period π in φd) and different per channel.
RGB synthetic_brdf(double theta_h, double theta_d, double phi_d) {
  const double peak = std::exp(-theta_h * theta_h / 0.02);
  const double aniso = 0.05 * std::sin(theta_d) * std::sin(theta_d) * std::cos(2.0 * phi_d);
  return RGB(static_cast<float>(0.20 + 2.0 * peak + aniso), static_cast<float>(0.10 + 1.0 * peak),
             static_cast<float>(0.30 + 0.5 * peak + aniso));
}

// Writes the synthetic file once per test run (35 MB, the real MERL size).
const std::string& synthetic_merl_path() {
  static const std::string path = [] {
    std::vector<double> ch[3];
    for (auto& c : ch) c.resize(kMerlCells);
    for (int h = 0; h < kMerlThetaH; ++h)
      for (int t = 0; t < kMerlThetaD; ++t)
        for (int p = 0; p < kMerlPhiD; ++p) {
          const size_t i = merl_cell(h, t, p);
          const HalfDiff a = merl_cell_center(h, t, p);
          double wi[3], wo[3];
          directions_from_half_diff(a.theta_h, a.theta_d, a.phi_d, wi, wo);
          const bool below = wi[2] <= 0.0 || wo[2] <= 0.0;  // MERL has no data there
          const RGB v = synthetic_brdf(a.theta_h, a.theta_d, a.phi_d);
          for (int c = 0; c < 3; ++c) ch[c][i] = below ? -1.0 : static_cast<double>(v[c]);
        }
    const std::string p = (temp_dir() / "synthetic.binary").string();
    write_merl(p, ch[0], ch[1], ch[2]);
    return p;
  }();
  return path;
}

}  // namespace

// ---- Spectral conversion -------------------------------------------------------------------

TEST(Spectrum, FlatSpectrumIsGreyOfTheSameValue) {
  float s[kCieSamples];
  for (float& v : s) v = 0.37f;
  const RGB c = spectrum_to_rgb(s);
  EXPECT_NEAR(c.r, 0.37f, 1e-5f);
  EXPECT_NEAR(c.g, 0.37f, 1e-5f);
  EXPECT_NEAR(c.b, 0.37f, 1e-5f);
}

TEST(Spectrum, NarrowBandsLandInTheExpectedChannel) {
  auto line = [](int nm) {
    float s[kCieSamples] = {};
    s[(nm - 400) / 10] = 1.0f;
    return spectrum_to_rgb(s);
  };
  const RGB blue = line(450), green = line(540), red = line(620);
  EXPECT_GT(blue.b, blue.g);
  EXPECT_GT(blue.b, blue.r);
  EXPECT_GT(green.g, green.r);
  EXPECT_GT(green.g, green.b);
  EXPECT_GT(red.r, red.g);
  EXPECT_GT(red.r, red.b);
  // The table is CIE 1931 2°: ȳ peaks at 555–560 nm with 0.995.
  EXPECT_FLOAT_EQ(cie1931_2deg(16).y, 0.995f);
}

// ---- Cornell reader ------------------------------------------------------------------------

TEST(Cornell, ReadsTheThreePaints) {
  for (const char* name : {"acryl_blue", "garnet_red", "krylon_blue"}) {
    SCOPED_TRACE(name);
    const auto rows = read_cornell(kDataDir + "/" + name + ".brdf");
    EXPECT_EQ(rows.size(), 1439u);
    RGB mean(0.0f);
    for (const auto& r : rows) {
      ASSERT_TRUE(finite_nonnegative(r.value));
      ASSERT_GE(r.theta_i, 0.0f);
      ASSERT_LE(r.theta_i, kPiOver2);
      // Diffuse-dominated rows far from the mirror direction give the paint's colour.
      if (std::fabs(r.phi_s) < 1.0f) mean += r.value;
    }
    if (std::string(name) == "garnet_red") {
      EXPECT_GT(mean.r, 2.0f * mean.b);
    } else {
      EXPECT_GT(mean.b, 2.0f * mean.r);
    }
  }
  // First row of acryl_blue: θi 0.872665, φi 0, θs 0.573513, φs 0.
  const auto rows = read_cornell(kDataDir + "/acryl_blue.brdf");
  EXPECT_FLOAT_EQ(rows[0].theta_i, 0.872665f);
  EXPECT_FLOAT_EQ(rows[0].theta_s, 0.573513f);
}

TEST(Cornell, RefusesBadFilesNamingFileAndProblem) {
  const std::string header =
      "# num wls\n31\n\n# wls\n400 410 420 430 440 450 460 470 480 490 500 510 520 530 540 550 "
      "560 570 580\n590 600 610 620 630 640 650 660 670 680 690 700\n\n# theta i, phi i, theta s, "
      "phi_s, spectral sample values\n";
  std::string row = "0.5 0 0.5 3.14159";
  for (int i = 0; i < 31; ++i) row += " 0.1";
  struct Case {
    const char* name;
    std::string text;
    const char* expect;
  };
  std::string wrong_wls = header;
  wrong_wls.replace(wrong_wls.find("410"), 3, "415");
  std::string nan_row = row;
  nan_row.replace(nan_row.rfind("0.1"), 3, "nan");
  std::string neg_row = row;
  neg_row.replace(neg_row.rfind("0.1"), 3, "-0.2");
  const Case cases[] = {
      {"truncated.brdf", header + row + "\n" + row.substr(0, row.size() / 2) + "\n", "truncated row"},
      {"nonumber.brdf", header + row + " abc\n", "'abc' is not a number"},
      {"nan.brdf", header + nan_row + "\n", "non-finite"},
      {"negative.brdf", header + neg_row + "\n", "negative spectral value"},
      {"nwls.brdf", "# num wls\n16\n# wls\n400 420\n", "only 31"},
      {"wls.brdf", wrong_wls + row + "\n", "wavelength 1 is 415"},
      {"noheader.brdf", row + "\n", "before the '# num wls' header"},
      {"norows.brdf", header, "no measurement rows"},
      {"theta.brdf", header + "2.5" + row.substr(3) + "\n", "theta i = 2.5"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = write_text(c.name, c.text);
    const std::string msg = error_of([&] { read_cornell(path); });
    EXPECT_NE(msg.find(c.name), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
  }
  EXPECT_NE(error_of([] { read_cornell("/nonexistent/x.brdf"); }).find("cannot be opened"),
            std::string::npos);
}

// ---- MERL reader ---------------------------------------------------------------------------

TEST(Merl, HalfDiffAnglesAreTheDefinitionsAndInvert) {
  PCG32 rng(7);
  for (int n = 0; n < 1000; ++n) {
    const Vec3 wi = random_upper(rng), wo = random_upper(rng);
    const HalfDiff a = half_diff_from_directions(wi, wo);
    const Vec3 h = normalize(wi + wo);
    EXPECT_NEAR(std::cos(a.theta_h), h.z, 1e-5f);
    EXPECT_NEAR(std::cos(a.theta_d), dot(wi, h), 1e-5f);
    // Back from (θh, θd, φd) with φh = 0: the pair is the original one rotated about z.
    double bi[3], bo[3];
    directions_from_half_diff(a.theta_h, a.theta_d, a.phi_d, bi, bo);
    EXPECT_NEAR(bi[2], wi.z, 1e-4);
    EXPECT_NEAR(bo[2], wo.z, 1e-4);
    EXPECT_NEAR(bi[0] * bo[0] + bi[1] * bo[1] + bi[2] * bo[2], dot(wi, wo), 1e-4);
    // Reciprocity: swapping the directions moves φd by π, i.e. to the same MERL cell.
    const HalfDiff b = half_diff_from_directions(wo, wi);
    EXPECT_NEAR(std::fabs(std::remainder(a.phi_d - b.phi_d, 2.0f * kPi)), kPi, 1e-3f);
  }
}

TEST(Merl, CellCentresMapBackToTheirCells) {
  for (int h = 0; h < kMerlThetaH; h += 7)
    for (int t = 0; t < kMerlThetaD; t += 5)
      for (int p = 0; p < kMerlPhiD; p += 11) {
        const HalfDiff a = merl_cell_center(h, t, p);
        ASSERT_EQ(merl_theta_h_index(a.theta_h), h);
        ASSERT_EQ(merl_theta_d_index(a.theta_d), t);
        ASSERT_EQ(merl_phi_d_index(a.phi_d), p);
        ASSERT_EQ(merl_phi_d_index(a.phi_d - kPi), p);  // the reciprocal configuration
      }
}

TEST(Merl, SyntheticFileRoundTrips) {
  const MerlData d = read_merl(synthetic_merl_path());
  EXPECT_EQ(fs::file_size(synthetic_merl_path()), kMerlFileBytes);
  EXPECT_GT(d.missing_cells, 0u);
  size_t checked = 0;
  for (size_t i = 0; i < kMerlCells; ++i) {
    const RGB v = d.cell(i);
    ASSERT_TRUE(finite_nonnegative(v)) << i;
    if (!d.measured[i]) continue;
    const int p = static_cast<int>(i % kMerlPhiD);
    const int t = static_cast<int>((i / kMerlPhiD) % kMerlThetaD);
    const int h = static_cast<int>(i / (size_t(kMerlPhiD) * kMerlThetaD));
    const HalfDiff a = merl_cell_center(h, t, p);
    const RGB e = synthetic_brdf(a.theta_h, a.theta_d, a.phi_d);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(v[c], e[c], 1e-6f * (1.0f + e[c])) << i;
    ++checked;
  }
  EXPECT_GT(checked, kMerlCells / 3);
}

TEST(Merl, LookupsMatchTheAnalyticBRDF) {
  const auto data = load_measured_data(synthetic_merl_path());
  PCG32 rng(11);
  double err_nearest = 0, err_linear = 0;
  int n = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 wi = random_upper(rng), wo = random_upper(rng);
    if (wi.z < 0.2f || wo.z < 0.2f) continue;  // away from cells that straddle the horizon
    const HalfDiff a = half_diff_from_directions(wi, wo);
    const RGB e = synthetic_brdf(a.theta_h, a.theta_d, a.phi_d);
    const RGB nearest = data->lookup(wo, wi, false), linear = data->lookup(wo, wi, true);
    for (int c = 0; c < 3; ++c) {
      err_nearest = std::max(err_nearest, double(std::fabs(nearest[c] - e[c]) / e[c]));
      err_linear = std::max(err_linear, double(std::fabs(linear[c] - e[c]) / e[c]));
    }
    ++n;
  }
  EXPECT_GT(n, 1000);
  // Nearest cell is off by at most the change over one cell; trilinear is far closer.
  EXPECT_LT(err_nearest, 0.15);
  EXPECT_LT(err_linear, 0.02);
  EXPECT_LT(err_linear, err_nearest);
}

TEST(Merl, RefusesBadFilesNamingFileAndProblem) {
  const std::string good = synthetic_merl_path();
  auto copy_to = [&](const std::string& name) {
    const fs::path p = temp_dir() / name;
    fs::copy_file(good, p, fs::copy_options::overwrite_existing);
    return p.string();
  };
  // Truncated by one double.
  const std::string truncated = copy_to("truncated.binary");
  fs::resize_file(truncated, kMerlFileBytes - 8);
  std::string msg = error_of([&] { read_merl(truncated); });
  EXPECT_NE(msg.find("truncated.binary"), std::string::npos) << msg;
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  // Trailing garbage.
  const std::string longer = copy_to("long.binary");
  fs::resize_file(longer, kMerlFileBytes + 8);
  msg = error_of([&] { read_merl(longer); });
  EXPECT_NE(msg.find("trailing data"), std::string::npos) << msg;
  // Wrong dimensions.
  const std::string dims = copy_to("dims.binary");
  {
    std::fstream f(dims, std::ios::in | std::ios::out | std::ios::binary);
    const int32_t d[3] = {90, 90, 360};
    f.write(reinterpret_cast<const char*>(d), sizeof(d));
  }
  msg = error_of([&] { read_merl(dims); });
  EXPECT_NE(msg.find("90 x 90 x 360"), std::string::npos) << msg;
  // A NaN in the green channel.
  const std::string nan = copy_to("nan.binary");
  {
    std::fstream f(nan, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(12 + (kMerlCells + 5) * sizeof(double)));
    const double v = std::nan("");
    f.write(reinterpret_cast<const char*>(&v), sizeof(v));
  }
  msg = error_of([&] { read_merl(nan); });
  EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;
  EXPECT_NE(msg.find("green"), std::string::npos) << msg;
  for (const auto& p : {truncated, longer, dims, nan}) fs::remove(p);  // 35 MB each
  // Too short for a header.
  const std::string tiny = write_text("tiny.binary", "abc");
  EXPECT_NE(error_of([&] { read_merl(tiny); }).find("too short"), std::string::npos);
}

TEST(Merl, BytesInMemoryReadAsTheFileWithTheSameChecks) {
  // read_merl reads the file and hands its bytes to parse_merl: the same table either way.
  std::ifstream in(synthetic_merl_path(), std::ios::binary);
  std::string bytes(kMerlFileBytes, '\0');
  ASSERT_TRUE(in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())));
  const MerlData from_file = read_merl(synthetic_merl_path());
  const MerlData from_bytes = parse_merl(bytes.data(), bytes.size(), "memory.binary");
  EXPECT_EQ(from_bytes.rgb, from_file.rgb);
  EXPECT_EQ(from_bytes.measured, from_file.measured);
  EXPECT_EQ(from_bytes.missing_cells, from_file.missing_cells);
  // Refusals name the source given in place of a file name.
  std::string msg = error_of([&] { parse_merl(bytes.data(), bytes.size() - 8, "memory.binary"); });
  EXPECT_NE(msg.find("MERL file 'memory.binary'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  msg = error_of([&] { parse_merl(bytes.data(), 11, "memory.binary"); });
  EXPECT_NE(msg.find("too short for the 12-byte header"), std::string::npos) << msg;
  EXPECT_NE(error_of([&] { parse_merl(nullptr, 0, "empty"); }).find("0 bytes"), std::string::npos);
  const double inf = INFINITY;
  std::memcpy(bytes.data() + 12 + 2 * kMerlCells * sizeof(double), &inf, sizeof(inf));
  msg = error_of([&] { parse_merl(bytes.data(), bytes.size(), "memory.binary"); });
  EXPECT_NE(msg.find("Inf) in the blue channel at cell 0"), std::string::npos) << msg;
}

// ---- The measured model -------------------------------------------------------------------

namespace {

BxDFPtr make_measured(const std::string& path, bool interpolate = true) {
  ParamSet p;
  p.set("path", path);
  p.set("interpolate", interpolate);
  return make("measured", p);
}

std::vector<BxDFPtr> measured_models() {
  return {make_measured(kDataDir + "/acryl_blue.brdf"), make_measured(kDataDir + "/krylon_blue.brdf"),
          make_measured(synthetic_merl_path(), true), make_measured(synthetic_merl_path(), false)};
}

}  // namespace

TEST(MeasuredModel, RefusesMissingAndBadFilesAtMake) {
  std::string msg = error_of([] { make_measured("/nonexistent/paint.brdf"); });
  EXPECT_NE(msg.find("/nonexistent/paint.brdf"), std::string::npos) << msg;
  msg = error_of([] { make_measured(""); });
  EXPECT_NE(msg.find("'path'"), std::string::npos) << msg;
  const std::string junk = write_text("junk.dat", "hello\n");
  msg = error_of([&] { make_measured(junk); });
  EXPECT_NE(msg.find("neither"), std::string::npos) << msg;
}

TEST(MeasuredModel, LoadingTwiceReadsTheFileOnce) {
  const std::string path = (temp_dir() / "cached.brdf").string();
  fs::copy_file(kDataDir + "/garnet_red.brdf", path, fs::copy_options::overwrite_existing);
  const size_t before = measured_file_reads();
  BxDFPtr a = make_measured(path), b = make_measured(path);
  EXPECT_EQ(measured_file_reads(), before + 1);
  EXPECT_EQ(&static_cast<const MeasuredBRDF&>(*a).data(), &static_cast<const MeasuredBRDF&>(*b).data());
  // A rewritten file is read again.
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(5));
  make_measured(path);
  EXPECT_EQ(measured_file_reads(), before + 2);
}

TEST(MeasuredModel, NeverNaNNegativeOrInfForAnyDirections) {
  const Vec3 odd[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 0, 0}, {1e-30f, 0, 0},
                      {0.3f, 0.2f, 1e-8f}, {std::nanf(""), 0, 1}, {INFINITY, 0, 1}, {5, -3, 2}};
  PCG32 rng(3);
  for (const BxDFPtr& m : measured_models()) {
    for (const Vec3& a : odd)
      for (const Vec3& b : odd) {
        ASSERT_TRUE(finite_nonnegative(m->f(a, b)));
        ASSERT_TRUE(finite_nonnegative(m->pdf(a, b)));
        const BxDFSample s = m->sample_f(a, {0.3f, 0.7f});
        ASSERT_TRUE(finite_nonnegative(s.f) && finite_nonnegative(s.pdf));
      }
    for (int k = 0; k < 2000; ++k) {
      const Vec3 a = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      const Vec3 b = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      ASSERT_TRUE(finite_nonnegative(m->f(a, b)));
      ASSERT_TRUE(finite_nonnegative(m->pdf(a, b)));
    }
  }
}

TEST(MeasuredModel, ReciprocalIsotropicAndTwoSided) {
  PCG32 rng(5);
  for (const BxDFPtr& m : measured_models()) {
    for (int k = 0; k < 2000; ++k) {
      const Vec3 wo = random_upper(rng), wi = random_upper(rng);
      const RGB a = m->f(wo, wi), b = m->f(wi, wo);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-4f * (1.0f + a[c]));
      const float phi = 2.0f * kPi * rng.uniform();
      auto rot = [&](const Vec3& w) {
        return Vec3(std::cos(phi) * w.x - std::sin(phi) * w.y,
                    std::sin(phi) * w.x + std::cos(phi) * w.y, w.z);
      };
      const RGB r = m->f(rot(wo), rot(wi));
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], r[c], 2e-3f * (1.0f + a[c]));
      const RGB below = m->f(Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z));
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a[c], below[c]);
      ASSERT_TRUE(m->f(wo, Vec3(wi.x, wi.y, -wi.z)).is_black());
    }
  }
}

TEST(MeasuredModel, CornellLookupReproducesTheMeasurements) {
  const auto data = load_measured_data(kDataDir + "/acryl_blue.brdf");
  // Away from the specular peak the resampled table reproduces each measurement closely;
  // overall the median relative error stays small.
  std::vector<double> rel;
  for (const MeasuredSample& s : data->samples()) {
    const RGB v = data->lookup(s.wo, s.wi, true);
    rel.push_back(std::fabs(v.b - s.value.b) / std::max(1e-3f, s.value.b));
  }
  std::sort(rel.begin(), rel.end());
  EXPECT_LT(rel[rel.size() / 2], 0.05);
}

TEST(MeasuredModel, SampleMatchesPdfAndIntegratesToOne) {
  PCG32 rng(9);
  for (const BxDFPtr& m : measured_models()) {
    for (float theta_o : {0.0f, 0.4f, 1.0f, 1.45f}) {
      const Vec3 wo(std::sin(theta_o) * 0.6f, std::sin(theta_o) * 0.8f, std::cos(theta_o));
      // ∫ pdf dω over the hemisphere, midpoint rule in (θ, φ) relative to wo's azimuth, on a
      // grid that refines the sampler's cells (the pdf is piecewise constant on them plus
      // smooth parts), so the quadrature error is only that of the smooth parts.
      double integral = 0.0;
      const int nt = IsotropicSampler::kThetaICells * 4, np = 2 * IsotropicSampler::kPhiCells * 4;
      const double phi_o = std::atan2(wo.y, wo.x);
      for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
          const double t = (i + 0.5) / nt * kPiOver2, phi = phi_o + 2.0 * kPi * (j + 0.5) / np;
          const Vec3 wi(static_cast<float>(std::sin(t) * std::cos(phi)),
                        static_cast<float>(std::sin(t) * std::sin(phi)), static_cast<float>(std::cos(t)));
          integral += m->pdf(wo, wi) * std::sin(t);
        }
      integral *= (kPiOver2 / nt) * (2.0 * kPi / np);
      EXPECT_NEAR(integral, 1.0, 0.01) << m->params().string("path") << " theta_o " << theta_o;
      for (int k = 0; k < 500; ++k) {
        const BxDFSample s = m->sample_f(wo, {rng.uniform(), rng.uniform()});
        ASSERT_TRUE(s.valid());
        ASSERT_GT(s.wi.z, 0.0f);
        ASSERT_NEAR(s.pdf, m->pdf(wo, s.wi), 1e-3f * s.pdf);
        const RGB f = m->f(wo, s.wi);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.f[c], f[c], 1e-4f * (1.0f + f[c]));
      }
    }
  }
}

// Pearson χ² of sampled directions against the pdf integrated over (cos θ, φ) cells.
TEST(MeasuredModel, SamplingPassesChiSquare) {
  const BxDFPtr m = make_measured(kDataDir + "/garnet_red.brdf");
  const Vec3 wo = normalize(Vec3(0.7f, 0.1f, 0.5f));
  constexpr int kTheta = 20, kPhi = 40, kN = 200000, kSub = 6;
  std::vector<double> expected(kTheta * kPhi, 0.0), observed(kTheta * kPhi, 0.0);
  for (int i = 0; i < kTheta; ++i)
    for (int j = 0; j < kPhi; ++j) {
      double sum = 0.0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const float ct = (i + (a + 0.5f) / kSub) / kTheta;
          const float phi = 2.0f * kPi * (j + (b + 0.5f) / kSub) / kPhi;
          const float st = std::sqrt(1.0f - ct * ct);
          sum += m->pdf(wo, Vec3(st * std::cos(phi), st * std::sin(phi), ct));
        }
      expected[i * kPhi + j] = sum / (kSub * kSub) * (1.0 / kTheta) * (2.0 * kPi / kPhi) * kN;
    }
  PCG32 rng(21);
  for (int k = 0; k < kN; ++k) {
    const BxDFSample s = m->sample_f(wo, {rng.uniform(), rng.uniform()});
    ASSERT_TRUE(s.valid());
    const int i = std::min(kTheta - 1, static_cast<int>(s.wi.z * kTheta));
    float phi = std::atan2(s.wi.y, s.wi.x);
    if (phi < 0.0f) phi += 2.0f * kPi;
    const int j = std::min(kPhi - 1, static_cast<int>(phi / (2.0f * kPi) * kPhi));
    observed[i * kPhi + j] += 1.0;
  }
  // Pool cells expecting < 5 into one; cells expecting nothing must see nothing.
  double chi2 = 0.0, pool_e = 0.0, pool_o = 0.0;
  int dof = -1;
  for (size_t c = 0; c < expected.size(); ++c) {
    if (expected[c] == 0.0) {
      ASSERT_EQ(observed[c], 0.0);
      continue;
    }
    if (expected[c] < 5.0) {
      pool_e += expected[c];
      pool_o += observed[c];
      continue;
    }
    chi2 += (observed[c] - expected[c]) * (observed[c] - expected[c]) / expected[c];
    ++dof;
  }
  if (pool_e > 0.0) {
    chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
    ++dof;
  }
  // Wilson–Hilferty: χ² with k dof exceeds k (1 − 2/(9k) + z √(2/(9k)))³ with probability
  // 0.1% for z = 3.09. The cell pdf integrals above are midpoint estimates, so allow that.
  const double k = dof, z = 3.09;
  const double bound = k * std::pow(1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k)), 3.0);
  EXPECT_LT(chi2, bound) << "dof " << dof;
}

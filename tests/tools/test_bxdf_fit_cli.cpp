// The bxdf-fit command line tool, run as a process: it fits a Cornell paint, writes a material
// file that plugin/io loads back into the same model, writes the plots, and refuses bad
// arguments with a message.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "bxdf/fit/fit.h"
#include "bxdf/io/material_json.h"
#include "bxdf/measured/measured_data.h"

using namespace bxdf;
namespace fs = std::filesystem;

namespace {

struct CliRun {
  int status = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  const std::string command = std::string(BXDF_FIT_EXE) + " " + args + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = ::pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A fresh directory under the system's temporary directory, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("bxdf_fit_cli_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

const std::string kPaint = BXDF_TEST_DATA_DIR "/measured/krylon_blue.brdf";

}  // namespace

TEST(BxdfFitCli, WritesAMaterialThatLoadsBackAsTheFittedModel) {
  TempDir dir;
  const std::string out = (dir.path / "krylon_blue.json").string();
  const std::string plots = (dir.path / "plots").string();
  const CliRun r = run(kPaint + " --model ggx --starts 2 --out " + out + " --plot " + plots);
  ASSERT_EQ(r.status, 0) << r.output;

  // The printed error, to the 6 digits printed.
  const size_t at = r.output.find("error ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double printed_error = std::stod(r.output.substr(at + 6));

  const io::MaterialDesc desc = io::load_material_desc(out);
  EXPECT_EQ(desc.model, "microfacet");
  EXPECT_EQ(desc.params.string("distribution"), "ggx");
  EXPECT_EQ(desc.params.string("fresnel"), "dielectric");
  const RGBValue diffuse = desc.params.rgb("diffuse");
  EXPECT_GT(diffuse[0] + diffuse[1] + diffuse[2], 0.01);  // a blue paint has a diffuse term
  EXPECT_NE(desc.name.find("krylon_blue"), std::string::npos) << desc.name;

  // The loaded model reproduces the fit's error on the data it was fitted to.
  const BxDFPtr loaded = io::load_material(out);
  EXPECT_EQ(loaded->model_name(), "microfacet");
  const auto samples = load_measured_data(kPaint)->samples();
  EXPECT_NEAR(fit::fit_error(samples, *loaded), printed_error, 1e-5 * printed_error + 1e-9);
  EXPECT_LT(printed_error, 0.05);  // f = 0 gives 0.258 on this paint

  int svgs = 0;
  for (const auto& e : fs::directory_iterator(plots)) svgs += e.path().extension() == ".svg";
  EXPECT_GT(svgs, 0);
}

TEST(BxdfFitCli, RefusesBadArgumentsWithAMessage) {
  CliRun r = run(kPaint + " --model phong");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("'phong'"), std::string::npos) << r.output;
  r = run(kPaint + " --starts two");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("--starts"), std::string::npos) << r.output;
  r = run(kPaint + " --out /nonexistent-dir/x.json --model lambertian");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/nonexistent-dir/x.json"), std::string::npos) << r.output;
  r = run("");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("usage"), std::string::npos) << r.output;
}

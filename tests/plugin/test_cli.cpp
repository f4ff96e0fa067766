// The bxdf-render command line: a good scene renders to EXR and PNG, every kind of bad scene file
// fails with a message naming the file, the field and what was expected, and a cancelled render
// leaves an existing output file as it was.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "bxdf/render/image_io.h"
#include "bxdf/render/scene_json.h"
#include "../scratch_folder.h"

namespace fs = std::filesystem;
using bxdf::render::Image;
using bxdf::render::read_image;

namespace {

using RunResult = bxdf::test_support::ShellResult;

// bxdf-render with `args`; stdout and stderr together.
RunResult run(const std::string& args) {
  return bxdf::test_support::run_shell(std::string(BXDF_RENDER_EXE) + " " + args + " 2>&1");
}

class CLI : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("bxdf_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// A good scene: a sphere from a shape, a floor from an OBJ file whose usemtl picks a scene
// material, a combined material, a point light and a grey world.
const char* kGoodScene = R"({
  "render": {"width": 24, "height": 16, "spp": 4, "max_bounces": 2, "filter": "gaussian",
             "filter_width": 1.5},
  "camera": {"lens": 40, "sensor_width": 36, "position": [0, -6, 1], "look_at": [0, 0, 0],
             "up": [0, 0, 1], "clip_start": 0.1, "clip_end": 100},
  "world": {"color": [0.05, 0.05, 0.05]},
  "materials": {
    "red": {"model": "lambertian", "params": {"reflectance": [0.8, 0.2, 0.2]}},
    "floor": {"components": [{"model": "lambertian", "params": {"reflectance": 0.3}},
                             {"model": "lambertian", "params": {"reflectance": 0.2}}]},
    "lamp": {"emission": [2, 2, 2]}
  },
  "meshes": [
    {"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "red"},
    {"obj": "floor.obj"},
    {"positions": [[-1, 2, 2], [1, 2, 2], [1, 2, 3]], "indices": [[0, 1, 2]], "material": "lamp"}
  ],
  "lights": [{"type": "point", "position": [2, -3, 3], "power": 800, "color": [1, 1, 1]}]
})";

const char* kFloorMtl = "newmtl floor\nKd 0.5 0.5 0.5\n";
const char* kFloorObj =
    "mtllib floor.mtl\n"
    "v -5 -5 -1\nv 5 -5 -1\nv 5 5 -1\nv -5 5 -1\n"
    "usemtl floor\n"
    "f 1 2 3\nf 1 3 4\n";

}  // namespace

TEST_F(CLI, GoodSceneRendersToExrAndPng) {
  write("floor.obj", kFloorObj);
  write("floor.mtl", kFloorMtl);
  const std::string scene = write("scene.json", kGoodScene);
  const RunResult exr = run(scene + " -o " + path("out.exr") + " --threads 2 --quiet");
  ASSERT_EQ(exr.exit_code, 0) << exr.output;
  EXPECT_NE(exr.output.find("0 rejected samples"), std::string::npos) << exr.output;
  const Image img = read_image(path("out.exr"));
  ASSERT_EQ(img.width, 24);
  ASSERT_EQ(img.height, 16);
  // The sphere's centre pixel is lit and red.
  const float* centre = &img.rgba[4 * (8 * 24 + 12)];
  EXPECT_GT(centre[0], 0.05f);
  EXPECT_GT(centre[0], 2.0f * centre[1]);
  EXPECT_EQ(centre[3], 1.0f);

  const RunResult png = run(scene + " -o " + path("out.png") + " --spp 4 --quiet");
  ASSERT_EQ(png.exit_code, 0) << png.output;
  const Image back = read_image(path("out.png"));
  ASSERT_EQ(back.width, 24);
  // Same render (same seed): the PNG decodes to the EXR's values within 8-bit sRGB steps.
  for (size_t i = 0; i < img.rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back.rgba[i + c], std::min(1.0f, img.rgba[i + c]),
                  0.01f + 0.02f * img.rgba[i + c]);
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
}

TEST_F(CLI, OptionsOverrideTheFile) {
  write("floor.obj", kFloorObj);
  write("floor.mtl", kFloorMtl);
  const std::string scene = write("scene.json", kGoodScene);
  const RunResult r = run(scene + " -o " + path("o.exr") +
                          " --spp 2 --max-bounces 0 --filter box --seed 7 --width 8 --height 4 -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("8x4, 2 spp"), std::string::npos) << r.output;
  const RunResult bad_option = run(scene + " -o " + path("o.exr") + " --filter blur");
  EXPECT_EQ(bad_option.exit_code, 1);
  EXPECT_NE(bad_option.output.find("filter 'blur'"), std::string::npos) << bad_option.output;
}

TEST_F(CLI, ARegionRendersItsPixelsAsTheWholeImageHasThem) {
  write("floor.obj", kFloorObj);
  write("floor.mtl", kFloorMtl);
  const std::string whole_scene = write("scene.json", kGoodScene);
  std::string text = kGoodScene;
  const std::string spp = "\"spp\": 4";
  text.replace(text.find(spp), spp.size(), spp + ", \"region\": [4, 2, 20, 10]");
  const std::string region_scene = write("region.json", text);
  const RunResult whole = run(whole_scene + " -o " + path("whole.exr") + " --threads 2 -q");
  const RunResult region = run(region_scene + " -o " + path("region.exr") + " --threads 2 -q");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  ASSERT_EQ(region.exit_code, 0) << region.output;
  const Image w = read_image(path("whole.exr")), r = read_image(path("region.exr"));
  ASSERT_EQ(r.width, 16);
  ASSERT_EQ(r.height, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(r.rgba[size_t(4 * (y * 16 + x) + c)], w.rgba[size_t(4 * ((y + 2) * 24 + x + 4) + c)])
            << "pixel " << x << ", " << y;
  // A region the image (here made smaller by an option) does not hold is refused by name.
  const RunResult outside = run(region_scene + " -o " + path("outside.exr") + " --width 12 -q");
  EXPECT_EQ(outside.exit_code, 1) << outside.output;
  EXPECT_NE(outside.output.find("'region' is (4, 2, 20, 10)"), std::string::npos) << outside.output;
  EXPECT_NE(outside.output.find("x_max <= width 12"), std::string::npos) << outside.output;
  EXPECT_FALSE(fs::exists(path("outside.exr")));
}

TEST_F(CLI, AdaptiveSamplingFromTheFileStopsPixelsAndSaysSo) {
  // The good scene at 256 spp with the loosest threshold, 1: its automatic minimum is 16
  // samples, and at the first check (after 32) every pixel has stopped.
  write("floor.obj", kFloorObj);
  write("floor.mtl", kFloorMtl);
  std::string text = kGoodScene;
  const std::string spp = "\"spp\": 4";
  text.replace(text.find(spp), spp.size(),
               "\"spp\": 256, \"adaptive_sampling\": true, \"adaptive_threshold\": 1");
  const std::string scene = write("adaptive.json", text);
  const RunResult r = run(scene + " -o " + path("adaptive.exr") + " --threads 2 -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("adaptive sampling: every pixel stopped by 32 spp, a mean of 32.0"),
            std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(path("adaptive.exr")));
}

struct BadCase {
  const char* name;
  std::string text;                    // the scene file
  std::vector<std::string> expected;   // pieces of the message
};

TEST_F(CLI, EachKindOfBadSceneFailsWithItsMessage) {
  write("floor.obj", kFloorObj);
  write("floor.mtl", kFloorMtl);
  const std::string good = kGoodScene;
  const auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  const std::vector<BadCase> cases = {
      {"not_json", "{\"camera\": ", {"not valid JSON"}},
      {"no_camera", replace("\"camera\"", "\"kamera\""), {"'kamera'", "unknown field"}},
      {"unknown_model", replace("\"model\": \"lambertian\", \"params\": {\"reflectance\": [0.8",
                                "\"model\": \"lambertain\", \"params\": {\"reflectance\": [0.8"),
       {"materials.red", "unknown model 'lambertain'"}},
      {"param_out_of_range", replace("[0.8, 0.2, 0.2]", "[1.8, 0.2, 0.2]"),
       {"materials.red", "'reflectance'", "1.8", "[0, 1]"}},
      {"bad_light_position", replace("\"position\": [2, -3, 3]", "\"position\": [2, -3]"),
       {"lights[0].position", "expected [x, y, z]"}},
      {"negative_power", replace("\"power\": 800", "\"power\": -800"),
       {"lights[0].power", "[0, inf)"}},
      {"unknown_light", replace("\"type\": \"point\"", "\"type\": \"laser\""),
       {"lights[0].type", "\"point\""}},
      {"unknown_material_ref", replace("\"material\": \"red\"", "\"material\": \"blue\""),
       {"meshes[0].material", "red"}},
      {"index_out_of_range", replace("[[0, 1, 2]]", "[[0, 1, 5]]"),
       {"meshes[2].indices[0][2]", "[0, 2]"}},
      {"missing_obj", replace("floor.obj", "nowhere.obj"), {"meshes[1].obj", "does not exist"}},
      {"bad_filter", replace("\"gaussian\"", "\"blur\""), {"render.filter", "'blackman_harris'"}},
      {"bad_spp", replace("\"spp\": 4", "\"spp\": 0"), {"render.spp", "[1,"}},
      {"bad_fit", replace("\"lens\": 40", "\"lens\": 40, \"sensor_fit\": \"WIDE\""),
       {"camera.sensor_fit", "AUTO"}},
      {"bad_camera_type", replace("\"lens\": 40", "\"lens\": 40, \"type\": \"PANO\""),
       {"camera.type", "\"ORTHO\""}},
      {"bad_ortho_scale", replace("\"lens\": 40", "\"lens\": 40, \"type\": \"ORTHO\", \"ortho_scale\": 0"),
       {"camera.ortho_scale", "(0, inf)"}},
      {"bad_radius", replace("\"radius\": 1", "\"radius\": -1"), {"meshes[0].radius", "(0, inf)"}},
      {"clip", replace("\"clip_end\": 100", "\"clip_end\": 0.05"), {"camera.clip_end"}},
      {"region_shape", replace("\"spp\": 4", "\"spp\": 4, \"region\": [0, 0, 8]"),
       {"render.region", "[x_min, y_min, x_max, y_max]"}},
      {"region_bound", replace("\"spp\": 4", "\"spp\": 4, \"region\": [0, -1, 8, 8]"),
       {"render.region[1]", "[0, 65536]"}},
      {"adaptive_threshold", replace("\"spp\": 4", "\"spp\": 4, \"adaptive_threshold\": 2"),
       {"render.adaptive_threshold", "[0, 1]"}},
      {"adaptive_min_samples",
       replace("\"spp\": 4", "\"spp\": 4, \"adaptive_min_samples\": -1"),
       {"render.adaptive_min_samples", "[0, 4096]"}},
      {"adaptive_sampling", replace("\"spp\": 4", "\"spp\": 4, \"adaptive_sampling\": 1"),
       {"render.adaptive_sampling", "true or false"}},
  };
  // Every case through the reader the CLI uses (a process start costs ~0.5 s here, as OIIO
  // loads its codecs), and a few through the CLI itself for the exit code and the message.
  for (size_t i = 0; i < cases.size(); ++i) {
    const BadCase& c = cases[i];
    SCOPED_TRACE(c.name);
    const std::string file = write(std::string(c.name) + ".json", c.text);
    std::string message;
    try {
      bxdf::render::load_scene_json(file);
    } catch (const bxdf::render::SceneFileError& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_EQ(message.rfind(file, 0), 0u) << "message does not start with the file: " << message;
    for (const std::string& piece : c.expected)
      EXPECT_NE(message.find(piece), std::string::npos) << "'" << piece << "' not in: " << message;
    if (i % 5 != 0) continue;
    const RunResult r = run(file + " -o " + path("bad.exr") + " -q");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("bad.exr")));
  }
  const RunResult missing = run(path("absent.json") + " -o " + path("bad.exr"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("absent.json"), std::string::npos) << missing.output;
}

TEST_F(CLI, CancelledRenderLeavesThePreviousOutputIntact) {
  write("floor.obj", kFloorObj);
  write("floor.mtl", kFloorMtl);
  const std::string scene = write("scene.json", kGoodScene);
  const std::string out = write("keep.exr", "previous contents");
  // A render far too long to finish, stopped with SIGTERM once its first pass is reported (a
  // signal before the handler is installed would kill it: the test would then prove nothing
  // about cancelling). `timeout` guards the test against a render that ignores the signal.
  const std::string err = path("stderr.txt");
  const std::string cmd = std::string("sh -c '") + "timeout -s KILL 120 " + BXDF_RENDER_EXE +
                          " " + scene + " -o " + out + " --spp 16000000 --width 64 --height 64 2>" +
                          err + " & pid=$!; i=0; while [ $i -lt 600 ] && ! grep -q pass " + err +
                          "; do sleep 0.05; i=$((i+1)); done; kill -TERM $pid; wait $pid; "
                          "echo exit=$?; cat " + err + "' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  char buf[1024];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, n);
  pclose(pipe);
  fs::remove(err);
  EXPECT_NE(text.find("exit=130"), std::string::npos) << text;
  EXPECT_NE(text.find("cancelled"), std::string::npos) << text;
  std::ifstream in(out);
  std::stringstream contents;
  contents << in.rdbuf();
  EXPECT_EQ(contents.str(), "previous contents");
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
}

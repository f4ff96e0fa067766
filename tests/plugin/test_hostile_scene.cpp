// Hostile scene files and failing renders (issue 15): OBJ indices out of range, devices named as
// files, deep nesting, cameras and meshes beyond Embree's coordinate range, the pass x tile count
// past 2^31, and a PNG write that fails under a file-size limit.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "bxdf/params.h"
#include "bxdf/render/image_io.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene_json.h"
#include "../scratch_folder.h"

using namespace bxdf;
using namespace bxdf::render;
namespace fs = std::filesystem;

namespace {

class HostileScene : public bxdf::test_support::ScratchFolderTest {
 protected:
  // The message of parse_scene_json on `text`, or "" if it loads.
  std::string scene_error(const std::string& text) {
    return bxdf::test_support::error_of([&] { parse_scene_json(text, "s.json", dir_.string()); });
  }
};

std::string scene_with(const std::string& camera, const std::string& mesh,
                       const std::string& render = R"({"width": 8, "height": 8})") {
  return R"({"render": )" + render + R"(, "camera": )" + camera +
         R"(, "materials": {"grey": {"model": "lambertian", "params": {"reflectance": 0.5}}},
            "meshes": [)" + mesh + R"(], "lights": [{"type": "point", "position": [0, 0, 3], "power": 100}]})";
}

const std::string kCamera = R"({"position": [0, -5, 0], "look_at": [0, 0, 0]})";
const std::string kQuad = R"({"shape": "quad", "corner": [-1, 0, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "material": "grey"})";

}  // namespace

TEST_F(HostileScene, ObjFaceIndicesOutOfRangeAreRefused) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n";
  const struct {
    const char* name;
    std::string faces;
    const char* expect;
  } cases[] = {
      {"past_end.obj", "f 1 2 9\n", "vertex index 9 is out of range [1, 3]"},
      {"slightly_past.obj", "f 1 2 4\n", "vertex index 4 is out of range [1, 3]"},
      {"negative.obj", "f 1 2 -9\n", "vertex index"},
      {"zero.obj", "f 0 1 2\n", "obj"},
      {"normal.obj", "f 1//1 2//1 3//7\n", "normal index 7 is out of range [1, 1]"},
      {"uv.obj", "f 1/1 2/5 3/1\n", "texture index 5 is out of range [1, 1]"},
      {"uv_negative.obj", "f 1/1 2/-4 3/1\n", "texture index"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    write(c.name, head + c.faces);
    const std::string msg =
        scene_error(scene_with(kCamera, R"({"obj": ")" + std::string(c.name) + R"(", "material": "grey"})"));
    EXPECT_NE(msg.find("meshes[0].obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
  }
  write("good.obj", head + "f 1/1/1 2/1/1 3/1/1\nf -3 -2 -1\n");
  EXPECT_EQ(scene_error(scene_with(kCamera, R"({"obj": "good.obj", "material": "grey"})")), "");
}

TEST_F(HostileScene, DevicesAreNotReadAsObjOrSceneFiles) {
  const std::string msg = scene_error(scene_with(kCamera, R"({"obj": "/dev/zero", "material": "grey"})"));
  EXPECT_NE(msg.find("meshes[0].obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
  try {
    load_scene_json("/dev/zero");
    FAIL();
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST_F(HostileScene, DeepNestingDuplicateKeysAndHugeNumbersNameTheFile) {
  std::string msg = scene_error("{\"camera\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
  EXPECT_NE(msg.find("s.json: nesting deeper than"), std::string::npos) << msg;
  msg = scene_error(scene_with(kCamera, kQuad, R"({"width": 8, "width": 9})"));
  EXPECT_NE(msg.find("s.json: duplicate key \"width\""), std::string::npos) << msg;
  msg = scene_error(scene_with(kCamera, kQuad, R"({"width": 1e999})"));
  EXPECT_NE(msg.find("s.json: not valid JSON"), std::string::npos) << msg;
  msg = scene_error(scene_with(kCamera, kQuad, R"({"seed": 18446744073709551615})"));
  EXPECT_NE(msg.find("render.seed"), std::string::npos) << msg;
}

TEST_F(HostileScene, CamerasAndMeshesFarFromTheOriginAreRefused) {
  // Embree asserts (SIGABRT) on ray origins past 1.8e18; these once reached it.
  std::string msg = scene_error(scene_with(R"({"position": [1e18, 0, 0], "look_at": [0, 0, 0]})", kQuad));
  EXPECT_NE(msg.find("camera"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[-1e9, 1e9]"), std::string::npos) << msg;
  msg = scene_error(scene_with(
      R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, -9.2e18], [0, 0, 1, 0], [0, 0, 0, 1]]})", kQuad));
  EXPECT_NE(msg.find("camera matrix[1][3]"), std::string::npos) << msg;
  msg = scene_error(scene_with(kCamera, R"({"positions": [[0, 0, 0], [1e30, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]], "material": "grey"})"));
  EXPECT_NE(msg.find("meshes[0]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[-1e9, 1e9]"), std::string::npos) << msg;
  // A zero axis names the field.
  msg = scene_error(scene_with(
      R"({"matrix": [[0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})", kQuad));
  EXPECT_NE(msg.find("field 'camera'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("zero axis"), std::string::npos) << msg;
}

TEST_F(HostileScene, TileCountPastTwoToThe31DoesNotOverflow) {
  // 2^24 spp in passes of 16 (the passes of partial images: on_pass is set) = 2^20 passes,
  // x 64 x 64 one-pixel tiles = 2^32 tiles.
  LoadedScene s = parse_scene_json(
      scene_with(kCamera, kQuad, R"({"width": 64, "height": 64, "tile_size": 1, "spp": 16777216})"),
      "s.json", dir_.string());
  s.settings.threads = 1;
  RenderCallbacks callbacks;
  uint64_t total = 0;
  callbacks.on_tile = [&](const RenderProgress& p) {
    total = p.tiles_total;
    return false;  // cancel at once
  };
  callbacks.on_pass = [](const Film&, const RenderProgress&) {};
  RenderStats stats;
  render_scene(*s.scene, s.camera, s.settings, callbacks, &stats);
  EXPECT_EQ(total, uint64_t(1) << 32);
  EXPECT_TRUE(stats.cancelled);
}

TEST_F(HostileScene, PngWriteThatFailsIsReportedAndKeepsTheOldImage) {
  // bxdf-render under a 2 KB file-size limit, as on a full disk: writes past it fail with EFBIG
  // (SIGXFSZ ignored). The PNG writer does not notice; the render must fail all the same, and
  // leave the previous image and no temporary behind. (In a child process: OIIO's state after a
  // failed PNG write is not to be trusted in the test process.)
  // One sample per pixel under a grey world, with a floor in front of the wall that blocks part
  // of the world from it: noise, so the PNG is far larger than the limit. (The wall alone would
  // be noise-free: a constant world is found by cosine sampling exactly.)
  const std::string floor =
      R"({"shape": "quad", "corner": [-1, -2, -1], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "grey"})";
  std::string text = scene_with(kCamera, kQuad + ", " + floor, R"({"width": 96, "height": 96, "spp": 1})");
  text.insert(1, R"("world": 0.8, )");
  const std::string scene = write("s.json", text);
  const std::string target = (dir_ / "out.png").string();
  Image old;
  old.width = old.height = 2;
  old.rgba.assign(16, 0.5f);
  write_image(target, old);
  const auto old_size = fs::file_size(target);
  const std::string render = std::string(BXDF_RENDER_EXE) + " " + scene + " -o " + target + " --quiet";
  const std::string limited = "bash -c 'ulimit -f 2; trap \"\" XFSZ; exec " + render + "' 2>&1";
  const auto [exit_code, output] = bxdf::test_support::run_shell(limited);
  EXPECT_EQ(exit_code, 2) << output;
  EXPECT_NE(output.find("incomplete"), std::string::npos) << output;
  EXPECT_EQ(fs::file_size(target), old_size);
  EXPECT_EQ(read_image(target).width, 2);
  EXPECT_EQ(files_in_folder(), 2u);  // the scene and the old image: no temporary left
  // Without the limit the same render writes a PNG that reads back.
  ASSERT_EQ(std::system((render + " > /dev/null 2>&1").c_str()), 0);
  EXPECT_EQ(read_image(target).width, 96);
}

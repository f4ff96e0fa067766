// Material files: round trips, and every kind of bad file names the file and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bxdf/io/atomic_file.h"
#include "bxdf/io/material_json.h"

using namespace bxdf;
namespace fs = std::filesystem;

namespace {

class MaterialJson : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("bxdf_io_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p) << text;
    return p;
  }
  std::string load_error(const std::string& text) {
    const std::string p = write("m.json", text);
    try {
      io::load_material(p);
    } catch (const ParameterError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

}  // namespace

TEST_F(MaterialJson, RoundTripKeepsModelAndParams) {
  ParamSet p;
  p.set("reflectance", RGBValue{0.25, 0.5, 0.75});
  BxDFPtr m = make("lambertian", p);
  const std::string path = (dir_ / "a.json").string();
  io::save_material(*m, path, "test material");
  const io::MaterialDesc d = io::load_material_desc(path);
  EXPECT_EQ(d.name, "test material");
  EXPECT_EQ(d.model, "lambertian");
  EXPECT_TRUE(d.params == m->params());
  BxDFPtr back = io::load_material(path);
  EXPECT_EQ(back->f({0, 0, 1}, {0, 0.6f, 0.8f}).g, m->f({0, 0, 1}, {0, 0.6f, 0.8f}).g);
}

TEST_F(MaterialJson, MissingParamsTakeDefaults) {
  const std::string p = write("d.json", R"({"model": "lambertian"})");
  EXPECT_DOUBLE_EQ(io::load_material_desc(p).params.rgb("reflectance")[0], 0.8);
}

TEST_F(MaterialJson, BadFilesNameTheFileAndTheField) {
  std::string e = load_error("{not json");
  EXPECT_NE(e.find("m.json"), std::string::npos) << e;
  EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;

  e = load_error(R"({"model": "lambertian", "params": {"reflectance": "red"}})");
  EXPECT_NE(e.find("params.reflectance"), std::string::npos) << e;
  EXPECT_NE(e.find("[r, g, b]"), std::string::npos) << e;

  e = load_error(R"({"model": "lambertian", "params": {"reflectance": [1, 2]}})");
  EXPECT_NE(e.find("params.reflectance"), std::string::npos) << e;

  e = load_error(R"({"model": "lambertian", "params": {"reflectance": [0.5, 0.5, 7]}})");
  EXPECT_NE(e.find("m.json"), std::string::npos) << e;
  EXPECT_NE(e.find("'reflectance'"), std::string::npos) << e;
  EXPECT_NE(e.find("[0, 1]"), std::string::npos) << e;

  e = load_error(R"({"model": "velvet"})");
  EXPECT_NE(e.find("'model'"), std::string::npos) << e;
  EXPECT_NE(e.find("velvet"), std::string::npos) << e;

  e = load_error(R"({"params": {}})");
  EXPECT_NE(e.find("'model' is missing"), std::string::npos) << e;

  e = load_error(R"({"model": "lambertian", "colour": 1})");
  EXPECT_NE(e.find("'colour'"), std::string::npos) << e;

  e = load_error(R"({"format": "bxdf-material", "version": 99, "model": "lambertian"})");
  EXPECT_NE(e.find("'version'"), std::string::npos) << e;

  e = load_error(R"({"model": "lambertian", "params": {"albedo": 0.5}})");
  EXPECT_NE(e.find("params.albedo"), std::string::npos) << e;

  e = load_error(R"({"preset": "unobtainium"})");
  EXPECT_NE(e.find("unobtainium"), std::string::npos) << e;

  EXPECT_THROW(io::load_material((dir_ / "missing.json").string()), ParameterError);
}

TEST_F(MaterialJson, FailedWriteLeavesTheOldFileIntact) {
  const std::string path = write("keep.txt", "old contents");
  EXPECT_THROW(io::write_file_atomically(path,
                                         [](const std::string& temp) {
                                           std::ofstream(temp) << "partial";
                                           throw std::runtime_error("cancelled");
                                         }),
               std::runtime_error);
  std::ifstream in(path);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(s, "old contents");
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u) << "the temporary file was not removed";
}

TEST_F(MaterialJson, NodeMaterialsKeepTheirGraph) {
  const std::string text = R"({"format": "bxdf-material", "version": 1, "name": "wood",
    "graph": {"nodes": [{"op": "uv"}], "closures": [{"model": "lambertian"}]}})";
  const std::string p = write("g.json", text);
  const io::MaterialDesc d = io::load_material_desc(p);
  EXPECT_EQ(d.name, "wood");
  EXPECT_TRUE(d.model.empty());
  ASSERT_TRUE(d.graph.is_object());
  EXPECT_EQ(d.graph["nodes"][0]["op"], "uv");
  const std::string saved = (dir_ / "g2.json").string();
  io::save_material(d, saved);
  EXPECT_EQ(io::load_material_desc(saved).graph, d.graph);
  // One model is asked for: refused, saying what the file is.
  EXPECT_NE(load_error(text).find("a node material"), std::string::npos);
  EXPECT_NE(load_error(R"({"graph": 3})").find("field 'graph': expected an object"), std::string::npos);
  EXPECT_NE(load_error(R"({"graph": {}, "model": "lambertian"})").find("field 'model': unknown"),
            std::string::npos);
}

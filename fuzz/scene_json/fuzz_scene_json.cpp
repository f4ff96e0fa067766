// Scene files with their OBJ meshes: the input is the scene JSON, optionally followed by a line
// "#OBJ" and the text of "fuzz.obj", which the scene can name. Any exception other than the
// reader's own SceneFileError/ParameterError is a finding, as is every sanitizer report.
#include <cstdint>
#include <string>

#include "bxdf/params.h"
#include "bxdf/render/scene_json.h"
#include "fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string separator = "\n#OBJ\n";
  const size_t split = input.find(separator);
  const std::string scene = input.substr(0, split);
  const std::string obj = split == std::string::npos ? "" : input.substr(split + separator.size());
  bxdf::fuzz::write_scratch("fuzz.obj", obj.data(), obj.size());
  try {
    bxdf::render::parse_scene_json(scene, "fuzz.json", bxdf::fuzz::scratch_folder());
  } catch (const bxdf::ParameterError&) {
    // A refused file: what the reader is for.
  }
  return 0;
}

// Material files: parse, read the material, make the model (as bxdf.load_material does). Any
// exception other than ParameterError is a finding, as is every sanitizer report.
#include <cstdint>
#include <string>

#include "bxdf/io/json_text.h"
#include "bxdf/io/material_json.h"
#include "bxdf/params.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const bxdf::io::MaterialDesc m =
        bxdf::io::material_from_json(bxdf::io::parse_json(text, "fuzz.json"), "fuzz.json");
    bxdf::io::make_material(m, "fuzz.json");
  } catch (const bxdf::ParameterError&) {
  }
  return 0;
}

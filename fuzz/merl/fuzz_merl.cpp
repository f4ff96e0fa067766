// MERL .binary files: the input is a whole file, read from memory by the MERL reader's own
// code (parse_merl_table, which parse_merl and read_merl call with MERL's 90 x 90 x 180 shape)
// for a table of 3 θh x 4 θd x 5 φd cells, so that a complete file is 1,452 bytes instead of
// 35 MB. The same input is also given to parse_merl, which must refuse it (no input the fuzzer
// makes is 35 MB). Any exception other than ParameterError is a finding, as is every sanitizer
// report and a negative or non-finite value in an accepted table.
#include <cmath>
#include <cstdint>

#include "bxdf/measured/merl.h"
#include "bxdf/params.h"
#include "measured/merl_table.h"

namespace {

constexpr bxdf::MerlShape kSmallShape{3, 4, 5};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const char* bytes = reinterpret_cast<const char*>(data);
  try {
    const bxdf::MerlData d = bxdf::parse_merl_table(bytes, size, "fuzz.binary", kSmallShape);
    if (d.rgb.size() != 3 * kSmallShape.cells()) __builtin_trap();
    for (float x : d.rgb)
      if (!(x >= 0.0f) || !std::isfinite(x)) __builtin_trap();  // the reader promises neither
  } catch (const bxdf::ParameterError&) {
  }
  try {
    bxdf::parse_merl(bytes, size, "fuzz.binary");
    __builtin_trap();  // far too short to be a MERL file
  } catch (const bxdf::ParameterError&) {
  }
  return 0;
}

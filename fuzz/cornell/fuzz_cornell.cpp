// Cornell .brdf files: read, and for files of a few rows also resample into the lookup table
// (which costs time in proportion to the rows). Any exception other than ParameterError is a
// finding, as is every sanitizer report.
#include <cmath>
#include <cstdint>
#include <string>

#include "bxdf/measured/cornell.h"
#include "bxdf/params.h"
#include "fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = bxdf::fuzz::write_scratch("fuzz.brdf", data, size);
  try {
    const std::vector<bxdf::CornellSample> samples = bxdf::read_cornell(path);
    if (samples.size() <= 8) {
      const bxdf::CornellTable table(samples);
      const bxdf::RGB v = table.lookup({0, 0, 1}, {0.6f, 0, 0.8f});
      if (!(v.r >= 0.0f && v.g >= 0.0f && v.b >= 0.0f) || !std::isfinite(v.r + v.g + v.b))
        __builtin_trap();  // the reader promises finite, non-negative values
    }
  } catch (const bxdf::ParameterError&) {
  }
  return 0;
}

// MERL .binary files are 35 MB of doubles, too large to mutate whole. The input is
//   [0, 12)   the header (three int32 dimensions),
//   [12]      how the file ends: 0 = full size, 1 = one double short, 2 = one double long,
//             else that many bytes (x 4096) short,
//   the rest  (uint32 cell, double value) records patched into a file of valid values
// so that the fuzzer controls the header, the size and any value. Any exception other than
// ParameterError is a finding, as is every sanitizer report and a non-finite lookup.
#include <cmath>
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <vector>

#include "bxdf/measured/merl.h"
#include "bxdf/params.h"
#include "fuzz_files.h"

namespace {

// A valid file: the header, then every value 0.25.
const std::vector<char>& valid_file() {
  static const std::vector<char> file = [] {
    std::vector<char> f(bxdf::kMerlFileBytes);
    const int32_t dims[3] = {bxdf::kMerlThetaH, bxdf::kMerlThetaD, bxdf::kMerlPhiD};
    std::memcpy(f.data(), dims, sizeof(dims));
    const double value = 0.25;
    for (size_t at = 12; at < f.size(); at += 8) std::memcpy(f.data() + at, &value, 8);
    return f;
  }();
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const size_t values = 3 * bxdf::kMerlCells;
  std::vector<char> file = valid_file();
  std::memcpy(file.data(), data, std::min<size_t>(size, 12));
  size_t length = file.size();
  if (size > 12) {
    const uint8_t end = data[12];
    if (end == 1) length -= 8;
    else if (end == 2) file.resize(length += 8, 0);
    else if (end > 2) length -= std::min<size_t>(length, size_t(end) * 4096);
  }
  for (size_t at = 13; at + 12 <= size; at += 12) {
    uint32_t cell;
    std::memcpy(&cell, data + at, 4);
    std::memcpy(file.data() + 12 + 8 * (cell % values), data + at + 4, 8);
  }
  const std::string path = bxdf::fuzz::write_scratch("fuzz.binary", file.data(), length);
  try {
    const bxdf::MerlData d = bxdf::read_merl(path);
    for (float x : d.rgb)
      if (!(x >= 0.0f) || !std::isfinite(x)) __builtin_trap();  // the reader promises neither
  } catch (const bxdf::ParameterError&) {
  }
  return 0;
}

// The MERL reader over a table of any shape. MERL's files are 90 θh x 90 θd x 180 φd; the
// fuzzer reads tables of a few cells through the same code, so that each input is a whole file
// of a few hundred bytes instead of 35 MB.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "bxdf/measured/merl.h"

namespace bxdf {

struct MerlShape {
  int32_t theta_h = kMerlThetaH, theta_d = kMerlThetaD, phi_d = kMerlPhiD;

  size_t cells() const { return size_t(theta_h) * size_t(theta_d) * size_t(phi_d); }
  size_t file_bytes() const { return 3 * sizeof(int32_t) + 3 * cells() * sizeof(double); }
  // MERL's cell order (merl_cell for the full shape).
  size_t cell(int h, int t, int p) const {
    return size_t(p) + size_t(phi_d) * (size_t(t) + size_t(theta_d) * size_t(h));
  }
};

// parse_merl for a table of `shape`: the header must give exactly these dimensions.
MerlData parse_merl_table(const char* bytes, size_t size, const std::string& source,
                          const MerlShape& shape);

}  // namespace bxdf

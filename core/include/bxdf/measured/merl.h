// MERL BRDF database files (Matusik et al. 2003, ".binary"): an isotropic BRDF tabulated over
// Rusinkiewicz's half/difference angles, 90 θh × 90 θd × 180 φd cells.
//
// Layout: three int32 (90, 90, 180), then 3 × 1,458,000 float64, all red, then all green, then
// all blue, little-endian; 34,992,012 bytes. Cell index = φd + 180 (θd + 90 θh). Stored values
// are scaled: BRDF = stored × (1/1500, 1.15/1500, 1.66/1500). Negative values mark cells without
// data (mostly configurations below the horizon).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf {

constexpr int kMerlThetaH = 90;
constexpr int kMerlThetaD = 90;
constexpr int kMerlPhiD = 180;
constexpr size_t kMerlCells = size_t(kMerlThetaH) * kMerlThetaD * kMerlPhiD;  // 1,458,000
constexpr size_t kMerlFileBytes = 3 * sizeof(int32_t) + 3 * kMerlCells * sizeof(double);
constexpr double kMerlScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

// Rusinkiewicz half/difference angles of a direction pair (isotropic: φh is dropped).
struct HalfDiff {
  float theta_h = 0, theta_d = 0, phi_d = 0;
};
// wi, wo unit length, both away from the surface. Follows MERL's reference code: h = normalize
// (wi + wo); d = wi rotated about the normal by −φh, then about the binormal by −θh.
HalfDiff half_diff_from_directions(const Vec3& wi, const Vec3& wo);
// The inverse for φh = 0 (double precision, for writers and fitting samples).
void directions_from_half_diff(double theta_h, double theta_d, double phi_d, double wi[3],
                               double wo[3]);

// MERL's cell lookup (floor of each coordinate, clamped; φd folded into [0, π) by reciprocity).
int merl_theta_h_index(float theta_h);
int merl_theta_d_index(float theta_d);
int merl_phi_d_index(float phi_d);
inline size_t merl_cell(int theta_h, int theta_d, int phi_d) {
  return size_t(phi_d) + size_t(kMerlPhiD) * (size_t(theta_d) + size_t(kMerlThetaD) * size_t(theta_h));
}
// Centre of a cell in angles (the inverse of the index functions at the middle of the cell).
HalfDiff merl_cell_center(int theta_h, int theta_d, int phi_d);

// A MERL table in memory: BRDF values (scale applied) as interleaved RGB floats.
struct MerlData {
  std::vector<float> rgb;         // 3 × kMerlCells; missing cells filled as below
  std::vector<uint8_t> measured;  // 1 where the file had data, 0 where it was negative
  size_t missing_cells = 0;

  RGB cell(size_t i) const { return {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]}; }
  // Nearest cell (MERL's own lookup) or trilinear interpolation between cell centres
  // (θh in MERL's square-root coordinate; φd periodic with period π).
  RGB lookup_nearest(const HalfDiff& a) const;
  RGB lookup_trilinear(const HalfDiff& a) const;
};

// Reads a .binary file. Refuses (ParameterError naming the file and the problem) a file that
// cannot be opened, has other dimensions, is truncated or too long, or holds NaN/Inf.
// Missing (negative) cells take the value of the nearest measured cell of lower θd in the same
// (θh, φd) column, or 0 when the column has none: lookups never see a negative value.
MerlData read_merl(const std::string& path);
// The same reader over a file's bytes in memory (read_merl reads the file, then calls this):
// the same checks and messages, with `source` standing for the file name in them.
MerlData parse_merl(const char* bytes, size_t size, const std::string& source);

// Writes BRDF values (per channel, kMerlCells each, MERL index order; negative = missing) in
// the MERL layout, applying the inverse scale. Used by tests and tools that make synthetic data.
void write_merl(const std::string& path, const std::vector<double>& red,
                const std::vector<double>& green, const std::vector<double>& blue);

}  // namespace bxdf

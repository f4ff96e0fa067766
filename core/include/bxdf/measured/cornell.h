// Cornell Program of Computer Graphics measured BRDFs (".brdf" text files): scattered,
// spectral samples of an isotropic BRDF.
//
//   # num wls            (comment lines start with '#'; CR LF or LF line ends)
//   31
//   # wls
//   400 410 ... 700      (may wrap over several lines)
//   # theta i, phi i, theta s, phi s, spectral sample values
//   θi φi θs φs v400 ... v700     (radians; one row per measurement)
//
// Each row is converted to linear Rec.709 RGB (cie1931.h). For lookups the scattered samples are
// resampled once, when the file is loaded, onto a regular (θo, θi, Δφ) grid by inverse-distance
// weighting in a metric that respects reciprocity and isotropy (cornell.cpp).
#pragma once

#include <string>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf {

struct CornellSample {
  float theta_i, phi_i, theta_s, phi_s;  // radians, as in the file
  RGB value;                             // BRDF, linear Rec.709
};

// Parses a .brdf file. Refuses (ParameterError naming the file, the line and the problem) a
// missing or malformed header, wavelengths other than 400–700 nm in 10 nm steps, short or
// truncated rows, non-numbers, NaN/Inf, negative spectral values and angles outside [0, π/2]
// for θ.
std::vector<CornellSample> read_cornell(const std::string& path);

// Direction (away from the surface) of a polar angle pair.
Vec3 direction_from_angles(float theta, float phi);

// The regular grid the samples are resampled onto: nodes every 3° in θo and θi over [0, 90°]
// and in Δφ = |φi − φo| over [0, 180°]; trilinear between nodes.
class CornellTable {
 public:
  static constexpr int kThetaNodes = 31;
  static constexpr int kPhiNodes = 61;

  explicit CornellTable(const std::vector<CornellSample>& samples);
  // wo, wi unit length in the upper hemisphere.
  RGB lookup(const Vec3& wo, const Vec3& wi) const;

 private:
  size_t node(int to, int ti, int dp) const {
    return (size_t(to) * kThetaNodes + size_t(ti)) * kPhiNodes + size_t(dp);
  }
  std::vector<RGB> table_;
};

}  // namespace bxdf

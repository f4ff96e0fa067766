#include "bxdf/measured/cornell.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bxdf/measured/cie1931.h"
#include "bxdf/input_file.h"
#include "bxdf/params.h"

namespace bxdf {

namespace {

[[noreturn]] void refuse(const std::string& path, int line, const std::string& problem) {
  throw ParameterError("Cornell BRDF file '" + printable(path) + "'" +
                       (line > 0 ? ", line " + std::to_string(line) : std::string()) + ": " +
                       problem);
}

struct Token {
  double value;
  int line;
};

// Splits a data line into numbers; refuses anything that is not a number.
void tokenize(const std::string& path, int line_no, const std::string& line,
              std::vector<Token>* out) {
  std::istringstream is(line);
  std::string word;
  while (is >> word) {
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') refuse(path, line_no, "'" + printable(word) + "' is not a number");
    if (!std::isfinite(v)) refuse(path, line_no, "non-finite value '" + printable(word) + "'");
    out->push_back({v, line_no});
  }
}

}  // namespace

Vec3 direction_from_angles(float theta, float phi) {
  const float s = std::sin(theta);
  return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

std::vector<CornellSample> read_cornell(const std::string& path) {
  check_input_file(path, kMaxMeasuredFileBytes, "Cornell BRDF file");
  std::ifstream in(path);
  if (!in) refuse(path, 0, "cannot be opened");

  // Sections are introduced by the comments "# num wls", "# wls" and "# theta ...".
  enum class Section { Preamble, NumWls, Wls, Rows } section = Section::Preamble;
  std::vector<Token> num_wls, wls, rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (line[first] == '#') {
      std::string tag = line.substr(first + 1);
      tag.erase(0, tag.find_first_not_of(" \t"));
      if (tag.rfind("num wls", 0) == 0) section = Section::NumWls;
      else if (tag.rfind("wls", 0) == 0) section = Section::Wls;
      else if (tag.rfind("theta", 0) == 0) section = Section::Rows;
      continue;
    }
    switch (section) {
      case Section::Preamble: refuse(path, line_no, "data before the '# num wls' header");
      case Section::NumWls: tokenize(path, line_no, line, &num_wls); break;
      case Section::Wls: tokenize(path, line_no, line, &wls); break;
      case Section::Rows: tokenize(path, line_no, line, &rows); break;
    }
  }
  if (num_wls.size() != 1)
    refuse(path, 0, "missing or malformed '# num wls' header (expected one number after it)");
  if (num_wls[0].value != kCieSamples)
    refuse(path, num_wls[0].line,
           "has " + std::to_string(num_wls[0].value) +
               " wavelengths; only 31 (400 to 700 nm every 10 nm) are supported");
  if (wls.size() != static_cast<size_t>(kCieSamples))
    refuse(path, 0, "'# wls' lists " + std::to_string(wls.size()) + " wavelengths; expected 31");
  for (int i = 0; i < kCieSamples; ++i) {
    const double expect = kCieFirstWavelength + kCieWavelengthStep * i;
    if (std::fabs(wls[static_cast<size_t>(i)].value - expect) > 1e-6)
      refuse(path, wls[static_cast<size_t>(i)].line,
             "wavelength " + std::to_string(i) + " is " +
                 std::to_string(wls[static_cast<size_t>(i)].value) + " nm; expected " +
                 std::to_string(expect) + " nm");
  }
  constexpr size_t kRow = 4 + kCieSamples;
  if (rows.empty()) refuse(path, 0, "has no measurement rows");
  if (rows.size() % kRow != 0)
    refuse(path, rows[rows.size() - rows.size() % kRow].line,
           "truncated row: " + std::to_string(rows.size() % kRow) + " numbers; a row has " +
               std::to_string(kRow) + " (4 angles and 31 spectral values)");

  std::vector<CornellSample> out;
  out.reserve(rows.size() / kRow);
  for (size_t r = 0; r < rows.size(); r += kRow) {
    const int ln = rows[r].line;
    for (size_t k : {size_t(0), size_t(2)}) {
      const double theta = rows[r + k].value;
      if (theta < 0.0 || theta > kPiOver2 + 1e-5)
        refuse(path, ln, std::string(k == 0 ? "theta i" : "theta s") + " = " +
                             std::to_string(theta) + " is outside [0, pi/2]");
    }
    // The files give φ in [-π, π] or [0, 2π]; far outside, sin and cos of the float lose all
    // precision.
    for (size_t k : {size_t(1), size_t(3)}) {
      const double phi = rows[r + k].value;
      if (!(std::fabs(phi) <= 2.0 * kPi + 1e-5))
        refuse(path, ln, std::string(k == 1 ? "phi i" : "phi s") + " = " + std::to_string(phi) +
                             " is outside [-2 pi, 2 pi]");
    }
    float spectrum[kCieSamples];
    for (int i = 0; i < kCieSamples; ++i) {
      const double v = rows[r + 4 + static_cast<size_t>(i)].value;
      if (v < 0.0)
        refuse(path, ln, "negative spectral value " + std::to_string(v) + " at " +
                             std::to_string(400 + 10 * i) + " nm");
      spectrum[i] = static_cast<float>(v);
      if (!std::isfinite(spectrum[i]))  // finite as a double, Inf as a float
        refuse(path, ln, "spectral value " + std::to_string(v) + " at " +
                             std::to_string(400 + 10 * i) + " nm is too large for a float");
    }
    CornellSample s;
    s.theta_i = static_cast<float>(rows[r].value);
    s.phi_i = static_cast<float>(rows[r + 1].value);
    s.theta_s = static_cast<float>(rows[r + 2].value);
    s.phi_s = static_cast<float>(rows[r + 3].value);
    // Rec.709 can be slightly negative for saturated spectra outside its gamut; a BRDF cannot.
    const RGB rgb = spectrum_to_rgb(spectrum);
    if (!std::isfinite(rgb.r) || !std::isfinite(rgb.g) || !std::isfinite(rgb.b))
      refuse(path, ln, "spectral values too large: their RGB is not finite");
    s.value = RGB(std::max(0.0f, rgb.r), std::max(0.0f, rgb.g), std::max(0.0f, rgb.b));
    out.push_back(s);
  }
  return out;
}

// ---- Resampling ------------------------------------------------------------------------------
//
// A direction pair of an isotropic BRDF is described, up to rotation about the normal, by the
// two directions expressed in the frame whose x axis is the azimuth of their half vector. In
// that frame swapping the two directions (reciprocity) leaves the frame unchanged, and the mirror
// image y → −y is the same configuration again (isotropic BRDFs are also bilaterally symmetric).
// The distance between two configurations is the Euclidean distance of the stacked 6-vectors
// (|Δwo|² + |Δwi|², chord lengths on the sphere), minimised over the swap; the mirror is folded
// out by making wi.y ≥ 0. This is a metric on configurations that does not depend on the order
// or the handedness in which they were measured, so the resampled BRDF is reciprocal and
// isotropic, and its value near a measurement is that measurement.

namespace {

using Config = std::array<float, 6>;

Config canonical_config(const Vec3& wo, const Vec3& wi) {
  const Vec3 h = wo + wi;
  const float r = std::sqrt(h.x * h.x + h.y * h.y);
  float c = 1.0f, s = 0.0f;
  if (r > 1e-7f) {
    c = h.x / r;
    s = h.y / r;
  }
  Config k;
  k[0] = c * wo.x + s * wo.y;
  k[1] = -s * wo.x + c * wo.y;
  k[2] = wo.z;
  k[3] = c * wi.x + s * wi.y;
  k[4] = -s * wi.x + c * wi.y;
  k[5] = wi.z;
  if (k[4] < 0.0f) {  // fold the mirror image
    k[1] = -k[1];
    k[4] = -k[4];
  }
  return k;
}

constexpr int kNeighbours = 4;

// Scattered samples stored as structure of arrays (both orders of each pair), for a
// vectorisable distance loop.
struct ScatteredSet {
  std::array<std::vector<float>, 6> coord;
  std::vector<RGB> value;

  void add(const Config& k, const RGB& v) {
    for (int d = 0; d < 6; ++d) coord[static_cast<size_t>(d)].push_back(k[static_cast<size_t>(d)]);
    value.push_back(v);
  }

  // Inverse-squared-distance weights over the kNeighbours nearest configurations.
  RGB interpolate(const Config& q, std::vector<float>* scratch) const {
    const size_t n = value.size();
    scratch->resize(n);
    float* d2 = scratch->data();
    for (size_t i = 0; i < n; ++i) {
      float s = 0.0f;
      for (int d = 0; d < 6; ++d) {
        const float t = coord[static_cast<size_t>(d)][i] - q[static_cast<size_t>(d)];
        s += t * t;
      }
      d2[i] = s;
    }
    float best_d[kNeighbours];
    size_t best_i[kNeighbours];
    int count = 0;
    for (size_t i = 0; i < n; ++i) {
      if (count == kNeighbours && d2[i] >= best_d[kNeighbours - 1]) continue;
      int j = count < kNeighbours ? count++ : kNeighbours - 1;
      while (j > 0 && best_d[j - 1] > d2[i]) {
        best_d[j] = best_d[j - 1];
        best_i[j] = best_i[j - 1];
        --j;
      }
      best_d[j] = d2[i];
      best_i[j] = i;
    }
    if (count == 0) return RGB(0.0f);
    if (best_d[0] < 1e-12f) return value[best_i[0]];
    RGB sum(0.0f);
    float wsum = 0.0f;
    for (int j = 0; j < count; ++j) {
      const float w = 1.0f / best_d[j];
      sum += value[best_i[j]] * w;
      wsum += w;
    }
    return sum / wsum;
  }
};

float node_theta(int i) { return kPiOver2 * static_cast<float>(i) / (CornellTable::kThetaNodes - 1); }
float node_phi(int i) { return kPi * static_cast<float>(i) / (CornellTable::kPhiNodes - 1); }

}  // namespace

CornellTable::CornellTable(const std::vector<CornellSample>& samples) {
  ScatteredSet set;
  for (const CornellSample& s : samples) {
    const Vec3 wi = direction_from_angles(s.theta_i, s.phi_i);
    const Vec3 wo = direction_from_angles(s.theta_s, s.phi_s);
    set.add(canonical_config(wo, wi), s.value);
    set.add(canonical_config(wi, wo), s.value);
  }
  table_.assign(size_t(kThetaNodes) * kThetaNodes * kPhiNodes, RGB(0.0f));
  std::vector<float> scratch;
  // The metric is symmetric under the swap, so only θo ≤ θi is computed and then mirrored:
  // the table is exactly reciprocal.
  for (int to = 0; to < kThetaNodes; ++to) {
    const Vec3 wo = direction_from_angles(node_theta(to), 0.0f);
    for (int ti = to; ti < kThetaNodes; ++ti) {
      for (int dp = 0; dp < kPhiNodes; ++dp) {
        const Vec3 wi = direction_from_angles(node_theta(ti), node_phi(dp));
        const RGB v = set.interpolate(canonical_config(wo, wi), &scratch);
        table_[node(to, ti, dp)] = v;
        table_[node(ti, to, dp)] = v;
      }
    }
  }
}

RGB CornellTable::lookup(const Vec3& wo, const Vec3& wi) const {
  const float to = std::atan2(std::sqrt(wo.x * wo.x + wo.y * wo.y), wo.z);
  const float ti = std::atan2(std::sqrt(wi.x * wi.x + wi.y * wi.y), wi.z);
  const float dphi = std::atan2(std::fabs(wo.x * wi.y - wo.y * wi.x), wo.x * wi.x + wo.y * wi.y);
  auto split = [](float u, int n, int* i0, float* t) {
    u = clamp(u, 0.0f, static_cast<float>(n - 1));
    *i0 = std::min(static_cast<int>(u), n - 2);
    *t = u - static_cast<float>(*i0);
  };
  int a, b, c;
  float ta, tb, tc;
  split(to / kPiOver2 * (kThetaNodes - 1), kThetaNodes, &a, &ta);
  split(ti / kPiOver2 * (kThetaNodes - 1), kThetaNodes, &b, &tb);
  split(dphi / kPi * (kPhiNodes - 1), kPhiNodes, &c, &tc);
  RGB out(0.0f);
  for (int i = 0; i < 2; ++i) {
    const float wa = i ? ta : 1.0f - ta;
    for (int j = 0; j < 2; ++j) {
      const float wb = j ? tb : 1.0f - tb;
      for (int k = 0; k < 2; ++k) {
        const float w = wa * wb * (k ? tc : 1.0f - tc);
        out += table_[node(a + i, b + j, c + k)] * w;
      }
    }
  }
  return out;
}

}  // namespace bxdf

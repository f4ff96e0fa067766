#include "bxdf/measured/merl.h"

#include <cmath>
#include <cstring>
#include <fstream>

#include "bxdf/input_file.h"
#include "bxdf/params.h"
#include "merl_table.h"

namespace bxdf {

namespace {

constexpr double kPiD = 3.14159265358979323846;

[[noreturn]] void refuse(const std::string& source, const std::string& problem) {
  throw ParameterError("MERL file '" + printable(source) + "': " + problem);
}

}  // namespace

HalfDiff half_diff_from_directions(const Vec3& wi, const Vec3& wo) {
  HalfDiff a;
  Vec3 h = wi + wo;
  if (!normalize_direction(h)) {  // wi = -wo: no half vector; treat as the most grazing cell
    a.theta_h = kPiOver2;
    a.theta_d = kPiOver2;
    return a;
  }
  const float sin_h = std::sqrt(h.x * h.x + h.y * h.y);
  const float cos_h = h.z;
  a.theta_h = std::atan2(sin_h, cos_h);
  // Rotate wi about the normal by -φh, then about the binormal (y) by -θh.
  float c = 1.0f, s = 0.0f;
  if (sin_h > 0.0f) {
    c = h.x / sin_h;
    s = h.y / sin_h;
  }
  const float x1 = c * wi.x + s * wi.y;
  const float y1 = -s * wi.x + c * wi.y;
  const float z1 = wi.z;
  const float x2 = x1 * cos_h - z1 * sin_h;
  const float z2 = z1 * cos_h + x1 * sin_h;
  a.theta_d = std::atan2(std::sqrt(x2 * x2 + y1 * y1), z2);
  a.phi_d = std::atan2(y1, x2);
  return a;
}

void directions_from_half_diff(double theta_h, double theta_d, double phi_d, double wi[3],
                               double wo[3]) {
  const double dx = std::sin(theta_d) * std::cos(phi_d);
  const double dy = std::sin(theta_d) * std::sin(phi_d);
  const double dz = std::cos(theta_d);
  const double ct = std::cos(theta_h), st = std::sin(theta_h);
  wi[0] = dx * ct + dz * st;
  wi[1] = dy;
  wi[2] = dz * ct - dx * st;
  const double h[3] = {st, 0.0, ct};
  const double hd = 2.0 * (h[0] * wi[0] + h[2] * wi[2]);
  for (int k = 0; k < 3; ++k) wo[k] = hd * h[k] - wi[k];
}

int merl_theta_h_index(float theta_h) {
  if (!(theta_h > 0.0f)) return 0;
  const float deg_index = theta_h / kPiOver2 * kMerlThetaH;
  const int i = static_cast<int>(std::sqrt(deg_index * kMerlThetaH));
  return clamp(i, 0, kMerlThetaH - 1);
}

int merl_theta_d_index(float theta_d) {
  if (!(theta_d > 0.0f)) return 0;
  return clamp(static_cast<int>(theta_d / kPiOver2 * kMerlThetaD), 0, kMerlThetaD - 1);
}

int merl_phi_d_index(float phi_d) {
  if (phi_d < 0.0f) phi_d += kPi;  // reciprocity: (wi, wo) and (wo, wi) differ by π in φd
  if (!(phi_d > 0.0f)) return 0;
  return clamp(static_cast<int>(phi_d / kPi * kMerlPhiD), 0, kMerlPhiD - 1);
}

HalfDiff merl_cell_center(int theta_h, int theta_d, int phi_d) {
  HalfDiff a;
  const double uh = (theta_h + 0.5) / kMerlThetaH;
  a.theta_h = static_cast<float>(uh * uh * kPiD / 2.0);
  a.theta_d = static_cast<float>((theta_d + 0.5) / kMerlThetaD * kPiD / 2.0);
  a.phi_d = static_cast<float>((phi_d + 0.5) / kMerlPhiD * kPiD);
  return a;
}

RGB MerlData::lookup_nearest(const HalfDiff& a) const {
  return cell(merl_cell(merl_theta_h_index(a.theta_h), merl_theta_d_index(a.theta_d),
                        merl_phi_d_index(a.phi_d)));
}

RGB MerlData::lookup_trilinear(const HalfDiff& a) const {
  // Continuous cell coordinates; cell i covers [i, i+1), its centre is at i + 0.5.
  const float th = std::sqrt(std::max(0.0f, a.theta_h) / kPiOver2) * kMerlThetaH - 0.5f;
  const float td = std::max(0.0f, a.theta_d) / kPiOver2 * kMerlThetaD - 0.5f;
  float pd = a.phi_d < 0.0f ? a.phi_d + kPi : a.phi_d;
  pd = pd / kPi * kMerlPhiD - 0.5f;

  auto split = [](float u, int n, int* i0, int* i1, float* t) {
    u = clamp(u, 0.0f, static_cast<float>(n - 1));
    *i0 = std::min(static_cast<int>(u), n - 1);
    *i1 = std::min(*i0 + 1, n - 1);
    *t = u - static_cast<float>(*i0);
  };
  int h0, h1, d0, d1;
  float th_t, td_t;
  split(th, kMerlThetaH, &h0, &h1, &th_t);
  split(td, kMerlThetaD, &d0, &d1, &td_t);
  // φd is periodic with period π (reciprocity), so the last cell blends with the first.
  float pf = std::floor(pd);
  const float pt = pd - pf;
  int p0 = static_cast<int>(pf) % kMerlPhiD;
  if (p0 < 0) p0 += kMerlPhiD;
  const int p1 = (p0 + 1) % kMerlPhiD;

  RGB out(0.0f);
  const int hs[2] = {h0, h1}, ds[2] = {d0, d1}, ps[2] = {p0, p1};
  const float hw[2] = {1.0f - th_t, th_t}, dw[2] = {1.0f - td_t, td_t}, pw[2] = {1.0f - pt, pt};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const float w = hw[i] * dw[j] * pw[k];
        if (w > 0.0f) out += cell(merl_cell(hs[i], ds[j], ps[k])) * w;
      }
  return out;
}

MerlData read_merl(const std::string& path) {
  // A regular file (not /dev/zero or a FIFO); a file somewhat too long still gets the
  // "trailing data" message from parse_merl.
  const std::string bytes = read_input_file(path, kMerlFileBytes + (1u << 20), "MERL file");
  return parse_merl(bytes.data(), bytes.size(), path);
}

MerlData parse_merl(const char* bytes, size_t size, const std::string& source) {
  return parse_merl_table(bytes, size, source, MerlShape{});
}

MerlData parse_merl_table(const char* bytes, size_t size, const std::string& source,
                          const MerlShape& shape) {
  if (size < 3 * sizeof(int32_t))
    refuse(source, "is " + std::to_string(size) + " bytes, too short for the 12-byte header");
  int32_t dims[3];
  std::memcpy(dims, bytes, sizeof(dims));
  if (dims[0] != shape.theta_h || dims[1] != shape.theta_d || dims[2] != shape.phi_d)
    refuse(source, "header gives dimensions " + std::to_string(dims[0]) + " x " +
                       std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + "; expected " +
                       std::to_string(shape.theta_h) + " x " + std::to_string(shape.theta_d) +
                       " x " + std::to_string(shape.phi_d));
  const size_t cells = shape.cells();
  const size_t expected = shape.file_bytes();
  if (size != expected)
    refuse(source, "is " + std::to_string(size) + " bytes; expected " + std::to_string(expected) +
                       " (" + (size < expected ? "truncated" : "trailing data") + ")");
  // The values start at byte 12, so they are not 8-byte aligned: copied out one by one.
  const char* values = bytes + sizeof(dims);

  static const char* kChannel[3] = {"red", "green", "blue"};
  MerlData d;
  d.rgb.resize(3 * cells);
  d.measured.assign(cells, 1);
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 0; i < cells; ++i) {
      double v;
      std::memcpy(&v, values + (c * cells + i) * sizeof(double), sizeof(v));
      if (!std::isfinite(v))
        refuse(source, std::string("holds a non-finite value (") + (std::isnan(v) ? "NaN" : "Inf") +
                           ") in the " + kChannel[c] + " channel at cell " + std::to_string(i));
      if (v < 0.0) d.measured[i] = 0;
      // Checked after the cast: a finite double such as 1e42 becomes Inf as a float.
      const float scaled = static_cast<float>(v * kMerlScale[c]);
      if (!std::isfinite(scaled))
        refuse(source, "holds " + std::to_string(v) + " in the " + kChannel[c] +
                           " channel at cell " + std::to_string(i) +
                           ", too large for a float once scaled");
      d.rgb[3 * i + c] = scaled;
    }
  }
  // Fill missing cells along θd from the nearest measured cell of the same (θh, φd) column.
  for (int h = 0; h < shape.theta_h; ++h) {
    for (int p = 0; p < shape.phi_d; ++p) {
      for (int t = 0; t < shape.theta_d; ++t) {
        const size_t i = shape.cell(h, t, p);
        if (d.measured[i]) continue;
        ++d.missing_cells;
        int best = -1;
        for (int r = 1; r < shape.theta_d && best < 0; ++r) {
          if (t - r >= 0 && d.measured[shape.cell(h, t - r, p)]) best = t - r;
          else if (t + r < shape.theta_d && d.measured[shape.cell(h, t + r, p)]) best = t + r;
        }
        const size_t src = best >= 0 ? shape.cell(h, best, p) : i;
        for (int c = 0; c < 3; ++c) d.rgb[3 * i + c] = best >= 0 ? d.rgb[3 * src + c] : 0.0f;
      }
    }
  }
  return d;
}

void write_merl(const std::string& path, const std::vector<double>& red,
                const std::vector<double>& green, const std::vector<double>& blue) {
  const std::vector<double>* channels[3] = {&red, &green, &blue};
  for (int c = 0; c < 3; ++c)
    if (channels[c]->size() != kMerlCells)
      throw ParameterError("write_merl: channel " + std::to_string(c) + " has " +
                           std::to_string(channels[c]->size()) + " values; expected " +
                           std::to_string(kMerlCells));
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw ParameterError("write_merl: cannot open '" + path + "' for writing");
  const int32_t dims[3] = {kMerlThetaH, kMerlThetaD, kMerlPhiD};
  out.write(reinterpret_cast<const char*>(dims), sizeof(dims));
  std::vector<double> buf(kMerlCells);
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 0; i < kMerlCells; ++i) {
      const double v = (*channels[c])[i];
      buf[i] = v < 0.0 ? -1.0 : v / kMerlScale[c];
    }
    out.write(reinterpret_cast<const char*>(buf.data()),
              static_cast<std::streamsize>(buf.size() * sizeof(double)));
  }
  if (!out) throw ParameterError("write_merl: writing '" + path + "' failed");
}

}  // namespace bxdf

// Color Ramp: Blender evaluates its colour band (BKE_colorband_evaluate) at 256 points and
// Cycles interpolates that table (svm/ramp.h); both steps are reproduced here.
#include <algorithm>

#include "bxdf/params.h"
#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

namespace {

enum class RampInterpolation { Constant, Linear, Ease };

// BKE_colorband_evaluate for RGB blending and constant/linear/ease interpolation.
std::array<float, 4> colorband(const std::vector<std::array<float, 5>>& stops,
                               RampInterpolation interpolation, float in) {
  auto rgba = [](const std::array<float, 5>& s) {
    return std::array<float, 4>{s[1], s[2], s[3], s[4]};
  };
  const size_t n = stops.size();
  if (n == 1 || in <= stops[0][0]) return rgba(stops[0]);
  size_t a = 0;
  while (a < n && !(stops[a][0] > in)) ++a;  // first stop past `in`
  if (a == n || interpolation == RampInterpolation::Constant) return rgba(stops[a - 1]);
  const auto& right = stops[a];
  const auto& left = stops[a - 1];
  float fac = left[0] != right[0] ? (in - right[0]) / (left[0] - right[0]) : 0.0f;
  if (interpolation == RampInterpolation::Ease) {
    const float fac2 = fac * fac;
    fac = 3.0f * fac2 - 2.0f * fac2 * fac;
  }
  const float mfac = 1.0f - fac;
  std::array<float, 4> out;
  for (int c = 0; c < 4; ++c) out[size_t(c)] = mfac * right[size_t(c) + 1] + fac * left[size_t(c) + 1];
  return out;
}

}  // namespace

ColorRampTable color_ramp_table(const std::vector<std::array<float, 5>>& stops,
                                const std::string& interpolation) {
  if (stops.empty()) throw ParameterError("a color ramp needs at least one stop");
  for (size_t i = 1; i < stops.size(); ++i)
    if (stops[i][0] < stops[i - 1][0])
      throw ParameterError("color ramp stops must be sorted by position (stop " +
                           std::to_string(i) + " comes before stop " + std::to_string(i - 1) + ")");
  RampInterpolation mode;
  if (interpolation == "constant") mode = RampInterpolation::Constant;
  else if (interpolation == "linear") mode = RampInterpolation::Linear;
  else if (interpolation == "ease") mode = RampInterpolation::Ease;
  else
    throw ParameterError("color ramp interpolation '" + interpolation +
                         "' is not supported; supported: constant, linear, ease");
  ColorRampTable table;
  for (int i = 0; i < ColorRampTable::kSize; ++i) {
    const auto c = colorband(stops, mode, static_cast<float>(i) /
                                              static_cast<float>(ColorRampTable::kSize - 1));
    table.color[size_t(i)] = Vec3(c[0], c[1], c[2]);
    table.alpha[size_t(i)] = c[3];
  }
  table.interpolate = mode != RampInterpolation::Constant;
  return table;
}

void color_ramp(const ColorRampTable& table, float fac, Vec3* color, float* alpha) {
  const int last = ColorRampTable::kSize - 1;
  const float f = clamp(fac, 0.0f, 1.0f) * static_cast<float>(last);
  const int i = f >= 0.0f ? std::min(static_cast<int>(f), last) : 0;  // NaN → 0
  const float t = f - static_cast<float>(i);
  *color = table.color[size_t(i)];
  *alpha = table.alpha[size_t(i)];
  if (table.interpolate && t > 0.0f) {
    *color = *color * (1.0f - t) + table.color[size_t(i) + 1] * t;
    *alpha = (1.0f - t) * *alpha + t * table.alpha[size_t(i) + 1];
  }
}

}  // namespace bxdf::render

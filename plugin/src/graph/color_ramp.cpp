// Color Ramp: Blender evaluates its colour band (BKE_colorband_evaluate, blenkernel/colorband.c)
// at 256 points and Cycles interpolates that table (svm/ramp.h); both steps are reproduced here.
#include <algorithm>
#include <cmath>

#include "bxdf/params.h"
#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

const std::vector<std::string> kRampInterpolationNames = {"constant", "linear", "ease",
                                                          "cardinal", "b_spline"};
const std::vector<std::string> kRampColorModeNames = {"rgb", "hsv", "hsl"};
const std::vector<std::string> kRampHueNames = {"near", "far", "cw", "ccw"};

namespace {

using Stop = std::array<float, 5>;  // pos, r, g, b, a
using RGBA4 = std::array<float, 4>;

RGBA4 rgba(const Stop& s) { return {s[1], s[2], s[3], s[4]}; }

// Blender's key_curve_position_weights for KEY_CARDINAL and KEY_BSPLINE.
std::array<float, 4> spline_weights(float t, RampInterpolation interpolation) {
  const float t2 = t * t, t3 = t2 * t;
  if (interpolation == RampInterpolation::Cardinal) {
    const float fc = 0.71f;
    return {-fc * t3 + 2.0f * fc * t2 - fc * t, (2.0f - fc) * t3 + (fc - 3.0f) * t2 + 1.0f,
            (fc - 2.0f) * t3 + (3.0f - 2.0f * fc) * t2 + fc * t, fc * t3 - fc * t2};
  }
  return {-0.16666666f * t3 + 0.5f * t2 - 0.5f * t + 0.16666666f, 0.5f * t3 - t2 + 0.66666666f,
          -0.5f * t3 + 0.5f * t2 + 0.5f * t + 0.16666666f, 0.16666666f * t3};
}

// colorband_hue_interp: h1 weighted by mfac, h2 by fac, the way round `hue` asks.
float hue_interp(RampHue hue, float mfac, float fac, float h1, float h2) {
  auto wrap = [](float h) { return h < 1.0f ? h : h - 1.0f; };
  h1 = wrap(h1);
  h2 = wrap(h2);
  int mode = 0;  // 0: straight, 1: h1 + 1, 2: h2 + 1
  switch (hue) {
    case RampHue::Near:
      mode = (h1 < h2 && h2 - h1 > 0.5f) ? 1 : (h1 > h2 && h2 - h1 < -0.5f) ? 2 : 0;
      break;
    case RampHue::Far:
      // A full turn when both stops have the same hue.
      mode = (h1 == h2 || (h1 < h2 && h2 - h1 < 0.5f)) ? 1 : (h1 > h2 && h2 - h1 > -0.5f) ? 2 : 0;
      break;
    case RampHue::CounterClockwise: mode = h1 > h2 ? 2 : 0; break;
    case RampHue::Clockwise: mode = h1 < h2 ? 1 : 0; break;
  }
  if (mode == 1) return wrap(mfac * (h1 + 1.0f) + fac * h2);
  if (mode == 2) return wrap(mfac * h1 + fac * (h2 + 1.0f));
  return mfac * h1 + fac * h2;
}

// BKE_colorband_evaluate. `right` is the first stop past `in` (cbd1), `left` the one before
// (cbd2); fac runs from 0 at `right` to 1 at `left`.
RGBA4 colorband(const std::vector<Stop>& stops, RampInterpolation interpolation_in,
                RampColorMode mode, RampHue hue, float in) {
  // HSV and HSL bands are always interpolated linearly.
  const RampInterpolation interpolation =
      mode == RampColorMode::RGB ? interpolation_in : RampInterpolation::Linear;
  const bool spline = interpolation == RampInterpolation::Cardinal ||
                      interpolation == RampInterpolation::BSpline;
  const size_t n = stops.size();
  if (n == 1 || (in <= stops[0][0] && !spline)) return rgba(stops[0]);
  size_t a = 0;
  while (a < n && !(stops[a][0] > in)) ++a;
  if (a == n && !spline) return rgba(stops[n - 1]);
  // Past the ends, the end stop is repeated at position 1 (right) or 0 (left).
  Stop right = a == n ? stops[n - 1] : stops[a];
  Stop left = a == 0 ? stops[0] : stops[a - 1];
  if (a == n) right[0] = 1.0f;
  if (a == 0) left[0] = 0.0f;
  if (interpolation == RampInterpolation::Constant) return rgba(left);
  float fac = left[0] != right[0] ? (in - right[0]) / (left[0] - right[0])
                                  : (a != n ? 0.0f : 1.0f);
  RGBA4 out;
  if (spline) {
    const Stop& far_right = a + 1 >= n ? right : stops[a + 1];  // cbd0
    const Stop& far_left = a < 2 ? left : stops[a - 2];          // cbd3
    const auto t = spline_weights(std::min(std::max(fac, 0.0f), 1.0f), interpolation);
    for (size_t c = 0; c < 4; ++c)
      out[c] = std::min(std::max(t[3] * far_left[c + 1] + t[2] * left[c + 1] +
                                     t[1] * right[c + 1] + t[0] * far_right[c + 1],
                                 0.0f),
                        1.0f);
    return out;
  }
  if (interpolation == RampInterpolation::Ease) {
    const float fac2 = fac * fac;
    fac = 3.0f * fac2 - 2.0f * fac2 * fac;
  }
  const float mfac = 1.0f - fac;
  if (mode == RampColorMode::RGB) {
    for (size_t c = 0; c < 4; ++c) out[c] = mfac * right[c + 1] + fac * left[c + 1];
    return out;
  }
  const bool hsv = mode == RampColorMode::HSV;
  const Vec3 c1 = hsv ? rgb_to_hsv(Vec3(right[1], right[2], right[3]))
                      : rgb_to_hsl(Vec3(right[1], right[2], right[3]));
  const Vec3 c2 = hsv ? rgb_to_hsv(Vec3(left[1], left[2], left[3]))
                      : rgb_to_hsl(Vec3(left[1], left[2], left[3]));
  const Vec3 mixed(hue_interp(hue, mfac, fac, c1.x, c2.x), mfac * c1.y + fac * c2.y,
                   mfac * c1.z + fac * c2.z);
  const Vec3 rgb = hsv ? hsv_to_rgb(mixed) : hsl_to_rgb(mixed);
  return {rgb.x, rgb.y, rgb.z, mfac * right[4] + fac * left[4]};
}

}  // namespace

ColorRampTable color_ramp_table(const std::vector<Stop>& stops, RampInterpolation interpolation,
                                RampColorMode color_mode, RampHue hue) {
  if (stops.empty()) throw ParameterError("a color ramp needs at least one stop");
  for (size_t i = 1; i < stops.size(); ++i)
    if (stops[i][0] < stops[i - 1][0])
      throw ParameterError("color ramp stops must be sorted by position (stop " +
                           std::to_string(i) + " comes before stop " + std::to_string(i - 1) + ")");
  ColorRampTable table;
  for (int i = 0; i < ColorRampTable::kSize; ++i) {
    const auto c = colorband(stops, interpolation, color_mode, hue,
                             static_cast<float>(i) / static_cast<float>(ColorRampTable::kSize - 1));
    table.color[size_t(i)] = Vec3(c[0], c[1], c[2]);
    table.alpha[size_t(i)] = c[3];
  }
  // Cycles interpolates the table unless the ramp is constant (whatever its colour mode).
  table.interpolate = interpolation != RampInterpolation::Constant;
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

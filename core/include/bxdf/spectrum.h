// Linear RGB (Rec.709 primaries, as Blender and Cycles use): the library's spectrum.
#pragma once

#include <cmath>

#include "bxdf/math.h"

namespace bxdf {

struct RGB {
  float r = 0, g = 0, b = 0;
  constexpr RGB() = default;
  constexpr explicit RGB(float v) : r(v), g(v), b(v) {}
  constexpr RGB(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
  RGB operator+(const RGB& o) const { return {r + o.r, g + o.g, b + o.b}; }
  RGB operator-(const RGB& o) const { return {r - o.r, g - o.g, b - o.b}; }
  RGB operator*(const RGB& o) const { return {r * o.r, g * o.g, b * o.b}; }
  RGB operator/(const RGB& o) const { return {r / o.r, g / o.g, b / o.b}; }
  RGB operator*(float s) const { return {r * s, g * s, b * s}; }
  RGB operator/(float s) const { return *this * (1.0f / s); }
  RGB& operator+=(const RGB& o) { r += o.r; g += o.g; b += o.b; return *this; }
  RGB& operator*=(const RGB& o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
  RGB& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
  bool operator==(const RGB& o) const { return r == o.r && g == o.g && b == o.b; }
  bool is_black() const { return r == 0.0f && g == 0.0f && b == 0.0f; }
  float max_component() const { return std::max(r, std::max(g, b)); }
  float average() const { return (r + g + b) * (1.0f / 3.0f); }
  // Rec.709 luminance weights.
  float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
};
inline RGB operator*(float s, const RGB& c) { return c * s; }
inline RGB sqrt(const RGB& c) { return {std::sqrt(c.r), std::sqrt(c.g), std::sqrt(c.b)}; }
BXDF_KERNEL RGB sanitize_nonnegative(const RGB& c) {
  return {sanitize_nonnegative(c.r), sanitize_nonnegative(c.g), sanitize_nonnegative(c.b)};
}
inline bool finite_nonnegative(const RGB& c) {
  return finite_nonnegative(c.r) && finite_nonnegative(c.g) && finite_nonnegative(c.b);
}

}  // namespace bxdf

// Colour ops of material graphs: Mix RGB, Invert, Gamma, Bright/Contrast, Hue/Saturation/Value
// (Cycles 3.4's svm/color_util.h, invert.h, math_util.h, hsv.h and util/color.h), and the HSL
// conversion of Blender's colour band.
#include <algorithm>
#include <cmath>

#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

const std::vector<std::string> kMixBlendNames = {
    "mix",        "add",     "multiply", "screen",     "overlay",      "subtract",
    "divide",     "difference", "darken", "lighten",   "soft_light",   "linear_light",
    "dodge",      "burn",    "hue",      "saturation", "value",        "color"};

namespace {

float saturate(float x) { return std::min(std::max(x, 0.0f), 1.0f); }
Vec3 saturate(const Vec3& c) { return {saturate(c.x), saturate(c.y), saturate(c.z)}; }
Vec3 mul(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
Vec3 lerp(const Vec3& a, const Vec3& b, float t) { return a * (1.0f - t) + b * t; }
Vec3 splat(float v) { return {v, v, v}; }

float overlay_channel(float t, float a, float b) {
  const float tm = 1.0f - t;
  return a < 0.5f ? a * (tm + 2.0f * t * b) : 1.0f - (tm + 2.0f * t * (1.0f - b)) * (1.0f - a);
}
float divide_channel(float t, float a, float b) {
  return b != 0.0f ? (1.0f - t) * a + t * a / b : a;
}
float dodge_channel(float t, float a, float b) {
  if (a == 0.0f) return a;
  const float d = 1.0f - t * b;
  return d <= 0.0f ? 1.0f : std::min(a / d, 1.0f);
}
float burn_channel(float t, float a, float b) {
  const float d = 1.0f - t + t * b;
  return d <= 0.0f ? 0.0f : saturate(1.0f - (1.0f - a) / d);
}
// svm_mix_hue and svm_mix_color: a's hue (and saturation) replaced by b's, unless b is grey.
Vec3 mix_hue(float t, const Vec3& a, const Vec3& b, bool with_saturation) {
  const Vec3 hsv_b = rgb_to_hsv(b);
  if (hsv_b.y == 0.0f) return a;
  Vec3 hsv_a = rgb_to_hsv(a);
  hsv_a.x = hsv_b.x;
  if (with_saturation) hsv_a.y = hsv_b.y;
  return lerp(a, hsv_to_rgb(hsv_a), t);
}

}  // namespace

Vec3 mix_rgb(MixBlend blend, float fac, const Vec3& a, const Vec3& b, bool clamp) {
  const float t = saturate(fac);
  const Vec3 one = splat(1.0f);
  Vec3 out;
  switch (blend) {
    case MixBlend::Mix: out = lerp(a, b, t); break;
    case MixBlend::Add: out = lerp(a, a + b, t); break;
    case MixBlend::Multiply: out = lerp(a, mul(a, b), t); break;
    case MixBlend::Screen: out = one - mul(splat(1.0f - t) + (one - b) * t, one - a); break;
    case MixBlend::Overlay:
      out = {overlay_channel(t, a.x, b.x), overlay_channel(t, a.y, b.y),
             overlay_channel(t, a.z, b.z)};
      break;
    case MixBlend::Subtract: out = lerp(a, a - b, t); break;
    case MixBlend::Divide:
      out = {divide_channel(t, a.x, b.x), divide_channel(t, a.y, b.y), divide_channel(t, a.z, b.z)};
      break;
    case MixBlend::Difference:
      out = lerp(a, {std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)}, t);
      break;
    case MixBlend::Darken:
      out = lerp(a, {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}, t);
      break;
    case MixBlend::Lighten:
      out = lerp(a, {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}, t);
      break;
    case MixBlend::SoftLight: {
      const Vec3 screen = one - mul(one - b, one - a);
      out = a * (1.0f - t) + (mul(mul(one - a, b), a) + mul(a, screen)) * t;
      break;
    }
    case MixBlend::LinearLight: out = a + (b * 2.0f - one) * t; break;
    case MixBlend::Dodge:
      out = {dodge_channel(t, a.x, b.x), dodge_channel(t, a.y, b.y), dodge_channel(t, a.z, b.z)};
      break;
    case MixBlend::Burn:
      out = {burn_channel(t, a.x, b.x), burn_channel(t, a.y, b.y), burn_channel(t, a.z, b.z)};
      break;
    case MixBlend::Hue: out = mix_hue(t, a, b, false); break;
    case MixBlend::Color: out = mix_hue(t, a, b, true); break;
    case MixBlend::Saturation: {
      Vec3 hsv_a = rgb_to_hsv(a);
      if (hsv_a.y == 0.0f) {
        out = a;
        break;
      }
      hsv_a.y = (1.0f - t) * hsv_a.y + t * rgb_to_hsv(b).y;
      out = hsv_to_rgb(hsv_a);
      break;
    }
    case MixBlend::Value: {
      Vec3 hsv_a = rgb_to_hsv(a);
      hsv_a.z = (1.0f - t) * hsv_a.z + t * rgb_to_hsv(b).z;
      out = hsv_to_rgb(hsv_a);
      break;
    }
  }
  return clamp ? saturate(out) : out;
}

Vec3 invert(float fac, const Vec3& c) {
  auto one = [fac](float x) { return fac * (1.0f - x) + (1.0f - fac) * x; };
  return {one(c.x), one(c.y), one(c.z)};
}

Vec3 gamma(const Vec3& c, float g) {
  if (g == 0.0f) return splat(1.0f);
  return {c.x > 0.0f ? std::pow(c.x, g) : c.x, c.y > 0.0f ? std::pow(c.y, g) : c.y,
          c.z > 0.0f ? std::pow(c.z, g) : c.z};
}

Vec3 bright_contrast(const Vec3& c, float bright, float contrast) {
  const float a = 1.0f + contrast, b = bright - contrast * 0.5f;
  return {std::max(a * c.x + b, 0.0f), std::max(a * c.y + b, 0.0f), std::max(a * c.z + b, 0.0f)};
}

Vec3 rgb_to_hsv(const Vec3& rgb) {
  const float cmax = std::max(rgb.x, std::max(rgb.y, rgb.z));
  const float cmin = std::min(rgb.x, std::min(rgb.y, rgb.z));
  const float cdelta = cmax - cmin;
  const float s = cmax != 0.0f ? cdelta / cmax : 0.0f;
  float h = 0.0f;
  if (s != 0.0f) {
    const Vec3 c = (splat(cmax) - rgb) / cdelta;
    if (rgb.x == cmax) h = c.z - c.y;
    else if (rgb.y == cmax) h = 2.0f + c.x - c.z;
    else h = 4.0f + c.y - c.x;
    h /= 6.0f;
    if (h < 0.0f) h += 1.0f;
  }
  return {h, s, cmax};
}

Vec3 hsv_to_rgb(const Vec3& hsv) {
  float h = hsv.x;
  const float s = hsv.y, v = hsv.z;
  if (s == 0.0f) return splat(v);
  if (h == 1.0f) h = 0.0f;
  h *= 6.0f;
  const float i = std::floor(h), f = h - i;
  const float p = v * (1.0f - s), q = v * (1.0f - s * f), t = v * (1.0f - s * (1.0f - f));
  if (i == 0.0f) return {v, t, p};
  if (i == 1.0f) return {q, v, p};
  if (i == 2.0f) return {p, v, t};
  if (i == 3.0f) return {p, q, v};
  if (i == 4.0f) return {t, p, v};
  return {v, p, q};
}

// Blender's rgb_to_hsl and hsl_to_rgb (blenlib/math_color.c), which its colour band uses.
Vec3 rgb_to_hsl(const Vec3& rgb) {
  const float cmax = std::max(rgb.x, std::max(rgb.y, rgb.z));
  const float cmin = std::min(rgb.x, std::min(rgb.y, rgb.z));
  const float l = std::min(1.0f, (cmax + cmin) * 0.5f);
  if (cmax == cmin) return {0.0f, 0.0f, l};
  const float d = cmax - cmin;
  const float s = l > 0.5f ? d / (2.0f - cmax - cmin) : d / (cmax + cmin);
  float h;
  if (cmax == rgb.x) h = (rgb.y - rgb.z) / d + (rgb.y < rgb.z ? 6.0f : 0.0f);
  else if (cmax == rgb.y) h = (rgb.z - rgb.x) / d + 2.0f;
  else h = (rgb.x - rgb.y) / d + 4.0f;
  return {h / 6.0f, s, l};
}

Vec3 hsl_to_rgb(const Vec3& hsl) {
  const float h = hsl.x, s = hsl.y, l = hsl.z;
  const float r = saturate(std::fabs(h * 6.0f - 3.0f) - 1.0f);
  const float g = saturate(2.0f - std::fabs(h * 6.0f - 2.0f));
  const float b = saturate(2.0f - std::fabs(h * 6.0f - 4.0f));
  const float chroma = (1.0f - std::fabs(2.0f * l - 1.0f)) * s;
  return {(r - 0.5f) * chroma + l, (g - 0.5f) * chroma + l, (b - 0.5f) * chroma + l};
}

Vec3 hsv(float hue, float saturation, float value, float fac, const Vec3& in) {
  Vec3 c = rgb_to_hsv(in);
  c.x = std::fmod(c.x + hue + 0.5f, 1.0f);
  c.y = saturate(c.y * saturation);
  c.z *= value;
  c = hsv_to_rgb(c);
  c = c * fac + in * (1.0f - fac);
  return {std::max(c.x, 0.0f), std::max(c.y, 0.0f), std::max(c.z, 0.0f)};
}

}  // namespace bxdf::render

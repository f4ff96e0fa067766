// Material-graph ops against independent evaluations: Blender's documented formulas written out
// per channel (not the op code's vector forms), std:: functions, and hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/render/graph_ops.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

void expect_vec(const Vec3& got, const Vec3& want, float tol = 1e-6f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

const Vec3 kA(0.2f, 0.6f, 0.9f), kB(0.7f, 0.1f, 0.4f);

}  // namespace

TEST(GraphOps, MixRGBBlendsPerChannel) {
  const float t = 0.3f;
  for (int c = 0; c < 3; ++c) {
    const float a = kA[c], b = kB[c];
    auto channel = [&](MixBlend blend) { return mix_rgb(blend, t, kA, kB, false)[c]; };
    EXPECT_NEAR(channel(MixBlend::Mix), a + t * (b - a), 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Add), a + t * b, 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Multiply), a * (1 - t + t * b), 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Subtract), a - t * b, 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Screen), 1 - (1 - t + t * (1 - b)) * (1 - a), 1e-6f);
    const float overlay = a < 0.5f ? a * (1 - t + 2 * t * b) : 1 - (1 - t + 2 * t * (1 - b)) * (1 - a);
    EXPECT_NEAR(channel(MixBlend::Overlay), overlay, 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Divide), (1 - t) * a + t * a / b, 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Difference), (1 - t) * a + t * std::fabs(a - b), 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Darken), (1 - t) * a + t * std::min(a, b), 1e-6f);
    EXPECT_NEAR(channel(MixBlend::Lighten), (1 - t) * a + t * std::max(a, b), 1e-6f);
    const float screen = 1 - (1 - b) * (1 - a);
    EXPECT_NEAR(channel(MixBlend::SoftLight), (1 - t) * a + t * ((1 - a) * b * a + a * screen), 1e-6f);
    EXPECT_NEAR(channel(MixBlend::LinearLight), a + t * (2 * b - 1), 1e-6f);
  }
  // The factor is saturated; clamp saturates the result; divide by 0 keeps a.
  expect_vec(mix_rgb(MixBlend::Mix, 1.7f, kA, kB, false), kB);
  expect_vec(mix_rgb(MixBlend::Add, 1.0f, kA, kB, true), Vec3(0.9f, 0.7f, 1.0f));
  expect_vec(mix_rgb(MixBlend::Divide, 1.0f, kA, Vec3(0, 0, 0), false), kA);
  EXPECT_EQ(kMixBlendNames.size(), size_t(MixBlend::Color) + 1);
}

TEST(GraphOps, MathMatchesStdAndCyclesSafeForms) {
  const float a = 2.5f, b = -0.75f, c = 0.3f;
  EXPECT_FLOAT_EQ(math(MathOp::Add, a, b, c, false), a + b);
  EXPECT_FLOAT_EQ(math(MathOp::Power, a, 2.0f, c, false), 6.25f);
  EXPECT_EQ(math(MathOp::Power, -2.0f, 0.5f, c, false), 0.0f);  // safe_powf
  EXPECT_FLOAT_EQ(math(MathOp::Power, -2.0f, 3.0f, c, false), -8.0f);
  EXPECT_EQ(math(MathOp::Divide, a, 0.0f, c, false), 0.0f);
  EXPECT_FLOAT_EQ(math(MathOp::Logarithm, 8.0f, 2.0f, c, false), 3.0f);
  EXPECT_EQ(math(MathOp::Sqrt, -4.0f, b, c, false), 0.0f);
  EXPECT_FLOAT_EQ(math(MathOp::InverseSqrt, 4.0f, b, c, false), 0.5f);
  EXPECT_FLOAT_EQ(math(MathOp::Modulo, -5.5f, 2.0f, c, false), std::fmod(-5.5f, 2.0f));
  EXPECT_FLOAT_EQ(math(MathOp::Wrap, 5.5f, 2.0f, 0.0f, false), 1.5f);
  EXPECT_FLOAT_EQ(math(MathOp::Pingpong, 3.0f, 2.0f, c, false), 1.0f);
  EXPECT_FLOAT_EQ(math(MathOp::Snap, 2.7f, 0.5f, c, false), 2.5f);
  EXPECT_FLOAT_EQ(math(MathOp::Round, -1.5f, b, c, false), -1.0f);
  EXPECT_FLOAT_EQ(math(MathOp::Trunc, -1.7f, b, c, false), -1.0f);
  EXPECT_EQ(math(MathOp::Compare, 1.0f, 1.2f, 0.25f, false), 1.0f);
  EXPECT_EQ(math(MathOp::Compare, 1.0f, 1.3f, 0.25f, false), 0.0f);
  // smooth min: min(a, b) − h³k/6 with h = max(k − |a − b|, 0)/k.
  const float h = (1.0f - 0.4f) / 1.0f;
  EXPECT_FLOAT_EQ(math(MathOp::SmoothMin, 0.2f, 0.6f, 1.0f, false), 0.2f - h * h * h / 6.0f);
  EXPECT_FLOAT_EQ(math(MathOp::Arctan2, a, b, c, false), std::atan2(a, b));
  EXPECT_FLOAT_EQ(math(MathOp::Arcsine, 2.0f, b, c, false), std::asin(1.0f));
  EXPECT_FLOAT_EQ(math(MathOp::Degrees, kPi, b, c, false), 180.0f);
  EXPECT_EQ(math(MathOp::Multiply, a, a, c, true), 1.0f);  // clamp
  EXPECT_EQ(math(MathOp::Sign, b, b, c, false), -1.0f);
  EXPECT_EQ(kMathOpNames.size(), size_t(MathOp::Degrees) + 1);
}

TEST(GraphOps, VectorMath) {
  Vec3 v;
  float s = 0.0f;
  vector_math(VectorMathOp::CrossProduct, Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(), 1.0f, &v, &s);
  expect_vec(v, Vec3(0, 0, 1));
  vector_math(VectorMathOp::DotProduct, kA, kB, Vec3(), 1.0f, &v, &s);
  EXPECT_FLOAT_EQ(s, 0.2f * 0.7f + 0.6f * 0.1f + 0.9f * 0.4f);
  vector_math(VectorMathOp::Normalize, Vec3(0, 0, 0), kB, Vec3(), 1.0f, &v, &s);
  expect_vec(v, Vec3(0, 0, 0));
  vector_math(VectorMathOp::Divide, kA, Vec3(2, 0, 4), Vec3(), 1.0f, &v, &s);
  expect_vec(v, Vec3(0.1f, 0.0f, 0.225f));
  vector_math(VectorMathOp::Scale, kA, kB, Vec3(), -2.0f, &v, &s);
  expect_vec(v, kA * -2.0f);
}

TEST(GraphOps, InvertGammaBrightContrast) {
  expect_vec(invert(0.25f, kA), Vec3(0.25f * 0.8f + 0.75f * 0.2f, 0.25f * 0.4f + 0.75f * 0.6f,
                                     0.25f * 0.1f + 0.75f * 0.9f));
  expect_vec(gamma(Vec3(0.25f, -0.5f, 0.0f), 2.0f), Vec3(0.0625f, -0.5f, 0.0f));
  expect_vec(gamma(kA, 0.0f), Vec3(1, 1, 1));
  // a = 1 + contrast, b = bright − contrast/2, max(a·c + b, 0).
  const float bright = 0.1f, contrast = 0.5f;
  expect_vec(bright_contrast(kA, bright, contrast),
             Vec3(1.5f * 0.2f + 0.1f - 0.25f, 1.5f * 0.6f + 0.1f - 0.25f, 1.5f * 0.9f + 0.1f - 0.25f));
  expect_vec(bright_contrast(Vec3(0, 0, 0), -0.5f, 0.0f), Vec3(0, 0, 0));
}

TEST(GraphOps, HueSaturationValue) {
  // Hue 0.5 is no shift; saturation and value scale.
  expect_vec(hsv(0.5f, 1.0f, 1.0f, 1.0f, kA), kA, 1e-6f);
  // Pure red shifted by a third of the circle is pure green.
  expect_vec(hsv(0.5f + 1.0f / 3.0f, 1.0f, 1.0f, 1.0f, Vec3(1, 0, 0)), Vec3(0, 1, 0), 1e-5f);
  // Saturation 0 gives grey at the value (max channel).
  expect_vec(hsv(0.5f, 0.0f, 1.0f, 1.0f, kA), Vec3(0.9f, 0.9f, 0.9f));
  // fac blends with the input.
  expect_vec(hsv(0.5f, 0.0f, 0.5f, 0.5f, kA), (Vec3(0.45f, 0.45f, 0.45f) + kA) * 0.5f);
  const Vec3 c = rgb_to_hsv(Vec3(0.2f, 0.4f, 0.8f));
  EXPECT_NEAR(c.x, (4.0f + (0.8f - 0.4f) / 0.6f - (0.8f - 0.2f) / 0.6f) / 6.0f, 1e-6f);
  expect_vec(hsv_to_rgb(c), Vec3(0.2f, 0.4f, 0.8f), 1e-6f);
}

TEST(GraphOps, ColorRampTableAndLookup) {
  const std::vector<std::array<float, 5>> stops = {{0.2f, 1, 0, 0, 1}, {0.8f, 0, 0, 1, 0}};
  Vec3 c;
  float a = 0.0f;
  const ColorRampTable linear = color_ramp_table(stops, RampInterpolation::Linear);
  color_ramp(linear, 0.5f, &c, &a);  // halfway between the stops
  expect_vec(c, Vec3(0.5f, 0.0f, 0.5f), 2e-3f);
  EXPECT_NEAR(a, 0.5f, 2e-3f);
  color_ramp(linear, 0.1f, &c, &a);  // before the first stop: its colour
  expect_vec(c, Vec3(1, 0, 0));
  color_ramp(linear, 3.0f, &c, &a);  // clamped, no extrapolation
  expect_vec(c, Vec3(0, 0, 1));
  // Table entries are Blender's band at i/255; between them Cycles interpolates linearly.
  const float x = 100.0f / 255.0f, x1 = 101.0f / 255.0f;
  auto band = [](float p) { return (0.8f - p) / 0.6f; };  // red weight on the linear segment
  color_ramp(linear, 0.5f * (x + x1), &c, &a);
  EXPECT_NEAR(c.x, 0.5f * (band(x) + band(x1)), 1e-5f);
  const ColorRampTable constant = color_ramp_table(stops, RampInterpolation::Constant);
  color_ramp(constant, 0.79f, &c, &a);
  expect_vec(c, Vec3(1, 0, 0));
  color_ramp(constant, 0.81f, &c, &a);
  expect_vec(c, Vec3(0, 0, 1));
  const ColorRampTable ease = color_ramp_table(stops, RampInterpolation::Ease);
  const float e = 128.0f / 255.0f;  // a table entry
  const float f = (e - 0.8f) / (0.2f - 0.8f);                  // towards the left stop
  color_ramp(ease, e, &c, &a);
  EXPECT_NEAR(c.x, 3 * f * f - 2 * f * f * f, 1e-5f);
  EXPECT_THROW(color_ramp_table({{0.5f, 1, 1, 1, 1}, {0.1f, 0, 0, 0, 1}}, RampInterpolation::Linear),
               ParameterError);
  EXPECT_THROW(color_ramp_table({}, RampInterpolation::Linear), ParameterError);
}

// Cardinal and B-spline bands weigh four stops with Blender's key_curve_position_weights
// (written out here as the cubic polynomials of the Blender manual's curve types).
TEST(GraphOps, ColorRampSplines) {
  const std::vector<std::array<float, 5>> stops = {
      {0.0f, 0, 0, 0, 1}, {0.25f, 1, 0, 0, 1}, {0.5f, 0, 1, 0, 1}, {1.0f, 0, 0, 1, 1}};
  Vec3 c;
  float a = 0.0f;
  const float e = 96.0f / 255.0f;  // between the stops at 0.25 and 0.5
  const float t = (e - 0.5f) / (0.25f - 0.5f);  // 0 at the right stop, 1 at the left
  // Order from right to left: the stop past the right one, right, left, the one before left.
  const float red[4] = {0, 0, 1, 0}, green[4] = {0, 1, 0, 0}, blue[4] = {1, 0, 0, 0};
  auto weigh = [](const float w[4], const float v[4]) {
    return std::min(std::max(w[0] * v[0] + w[1] * v[1] + w[2] * v[2] + w[3] * v[3], 0.0f), 1.0f);
  };
  const float fc = 0.71f;
  const float cardinal[4] = {-fc * t * t * t + 2 * fc * t * t - fc * t,
                             (2 - fc) * t * t * t + (fc - 3) * t * t + 1,
                             (fc - 2) * t * t * t + (3 - 2 * fc) * t * t + fc * t, fc * t * t * t - fc * t * t};
  color_ramp(color_ramp_table(stops, RampInterpolation::Cardinal), e, &c, &a);
  EXPECT_NEAR(c.x, weigh(cardinal, red), 1e-5f);
  EXPECT_NEAR(c.y, weigh(cardinal, green), 1e-5f);
  EXPECT_NEAR(c.z, weigh(cardinal, blue), 1e-5f);
  const float bspline[4] = {(1 - t) * (1 - t) * (1 - t) / 6, (3 * t * t * t - 6 * t * t + 4) / 6,
                            (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
  color_ramp(color_ramp_table(stops, RampInterpolation::BSpline), e, &c, &a);
  EXPECT_NEAR(c.x, weigh(bspline, red), 1e-5f);
  EXPECT_NEAR(c.y, weigh(bspline, green), 1e-5f);
  EXPECT_NEAR(c.z, weigh(bspline, blue), 1e-5f);
  // A cardinal spline passes through its stops; B-spline does not (it smooths them).
  color_ramp(color_ramp_table(stops, RampInterpolation::Cardinal), 0.5f + 0.5f / 255.0f, &c, &a);
  EXPECT_NEAR(c.y, 1.0f, 2e-2f);
}

// HSV and HSL bands interpolate hue the short way round (Near) or as asked, saturation and
// value/lightness linearly; they ignore ease and spline interpolation.
TEST(GraphOps, ColorRampHueModes) {
  // Red (hue 0) to blue (hue 2/3): the short way passes magenta (hue 5/6), the long way green.
  const std::vector<std::array<float, 5>> stops = {{0.0f, 1, 0, 0, 1}, {1.0f, 0, 0, 1, 1}};
  Vec3 c;
  float a = 0.0f;
  const float mid = 0.5f * (127.0f + 128.0f) / 255.0f;
  color_ramp(color_ramp_table(stops, RampInterpolation::Linear, RampColorMode::HSV), mid, &c, &a);
  expect_vec(c, Vec3(1, 0, 1), 2e-2f);  // hue 5/6 at half way
  color_ramp(color_ramp_table(stops, RampInterpolation::Linear, RampColorMode::HSV, RampHue::Far),
             mid, &c, &a);
  expect_vec(c, Vec3(0, 1, 0.0f), 2e-2f);  // hue 1/3
  color_ramp(color_ramp_table(stops, RampInterpolation::Ease, RampColorMode::HSV), 64.0f / 255.0f,
             &c, &a);
  const Vec3 linear_quarter = hsv_to_rgb(Vec3(1.0f - (64.0f / 255.0f) / 3.0f, 1.0f, 1.0f));
  expect_vec(c, linear_quarter, 1e-5f);
  // HSL: lightness ½ and saturation 1 for both; grey stops keep hue 0 and mix lightness.
  color_ramp(color_ramp_table(stops, RampInterpolation::Linear, RampColorMode::HSL), mid, &c, &a);
  expect_vec(c, Vec3(1, 0, 1), 2e-2f);
  const Vec3 hsl = rgb_to_hsl(Vec3(0.2f, 0.4f, 0.8f));
  EXPECT_NEAR(hsl.z, 0.5f, 1e-6f);
  EXPECT_NEAR(hsl.y, 0.6f / (0.2f + 0.8f), 1e-6f);
  expect_vec(hsl_to_rgb(hsl), Vec3(0.2f, 0.4f, 0.8f), 1e-6f);
}

TEST(GraphOps, MixRGBHsvAndDodgeBurnBlends) {
  const float t = 0.3f;
  for (int c = 0; c < 3; ++c) {
    const float a = kA[c], b = kB[c];
    const float dodge = std::min(a / (1 - t * b), 1.0f);
    EXPECT_NEAR(mix_rgb(MixBlend::Dodge, t, kA, kB, false)[c], dodge, 1e-6f);
    const float burn = std::min(std::max(1 - (1 - a) / (1 - t + t * b), 0.0f), 1.0f);
    EXPECT_NEAR(mix_rgb(MixBlend::Burn, t, kA, kB, false)[c], burn, 1e-6f);
  }
  EXPECT_EQ(mix_rgb(MixBlend::Dodge, 1.0f, Vec3(0.5f, 0, 0.5f), Vec3(1, 1, 0.2f), false),
            Vec3(1.0f, 0.0f, 0.5f / 0.8f));
  const Vec3 ha = rgb_to_hsv(kA), hb = rgb_to_hsv(kB);
  auto lerp = [](const Vec3& x, const Vec3& y, float f) { return x * (1 - f) + y * f; };
  expect_vec(mix_rgb(MixBlend::Hue, t, kA, kB, false), lerp(kA, hsv_to_rgb(Vec3(hb.x, ha.y, ha.z)), t));
  expect_vec(mix_rgb(MixBlend::Color, t, kA, kB, false),
             lerp(kA, hsv_to_rgb(Vec3(hb.x, hb.y, ha.z)), t));
  expect_vec(mix_rgb(MixBlend::Saturation, t, kA, kB, false),
             hsv_to_rgb(Vec3(ha.x, (1 - t) * ha.y + t * hb.y, ha.z)));
  expect_vec(mix_rgb(MixBlend::Value, t, kA, kB, false),
             hsv_to_rgb(Vec3(ha.x, ha.y, (1 - t) * ha.z + t * hb.z)));
  // A grey b has no hue to give; a grey a has no saturation to change.
  expect_vec(mix_rgb(MixBlend::Hue, t, kA, Vec3(0.5f, 0.5f, 0.5f), false), kA);
  expect_vec(mix_rgb(MixBlend::Saturation, t, Vec3(0.5f, 0.5f, 0.5f), kB, false), Vec3(0.5f, 0.5f, 0.5f));
}

// Bump with a linear height h: Cycles' finite differences give normalize(N − distance·∇h)
// whatever the offsets, and strength blends towards N.
TEST(GraphOps, BumpOfALinearHeight) {
  const Vec3 n(0, 0, 1), grad(0.3f, -0.2f, 0.0f);
  BumpInputs in;
  in.normal = n;
  in.height = 0.7f;
  for (const float eps : {1e-3f, 1e-2f}) {
    in.dpdx = Vec3(eps, 0, 0);
    in.dpdy = Vec3(0, -eps, 0);  // left-handed offsets: det < 0 and the sign compensates
    in.height_x = in.height + dot(grad, in.dpdx);
    in.height_y = in.height + dot(grad, in.dpdy);
    in.distance = 0.5f;
    const Vec3 view(0, 0, 1);
    expect_vec(bump_normal(in, n, view), normalize(n - grad * 0.5f), 1e-4f);
    in.invert = true;
    expect_vec(bump_normal(in, n, view), normalize(n + grad * 0.5f), 1e-4f);
    in.invert = false;
    in.strength = 0.25f;
    expect_vec(bump_normal(in, n, view),
               normalize(normalize(n - grad * 0.5f) * 0.25f + n * 0.75f), 1e-4f);
    in.strength = 1.0f;
  }
}

// ensure_valid_reflection leaves a normal whose mirror direction is above the surface, and
// tilts one that would reflect below it until the reflection meets Cycles' threshold.
TEST(GraphOps, EnsureValidReflection) {
  const Vec3 ng(0, 0, 1);
  const Vec3 view = normalize(Vec3(1, 0, 0.2f));
  const Vec3 mild = normalize(Vec3(0.1f, 0, 1));
  expect_vec(ensure_valid_reflection(ng, view, mild), mild);
  const Vec3 steep = normalize(Vec3(-1.5f, 0, 1));  // tilted away: reflects below the surface
  const Vec3 fixed = ensure_valid_reflection(ng, view, steep);
  EXPECT_NEAR(length(fixed), 1.0f, 1e-5f);
  const Vec3 r = fixed * (2 * dot(fixed, view)) - view;
  EXPECT_NEAR(dot(r, ng), std::min(0.9f * view.z, 0.01f), 1e-4f);
  EXPECT_NEAR(fixed.y, 0.0f, 1e-6f);  // stays in the plane of N and Ng
}

TEST(GraphOps, FresnelAndLayerWeight) {
  // Normal incidence: ((η − 1)/(η + 1))².
  const Vec3 n(0, 0, 1);
  EXPECT_NEAR(fresnel_node(1.5f, n, n, false), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_node(1.5f, n, n, true), 0.04f, 1e-6f);  // 1/η gives the same at normal
  float fr = 0.0f, facing = 0.0f;
  layer_weight(0.5f, n, n, false, &fr, &facing);
  EXPECT_NEAR(facing, 0.0f, 1e-6f);
  EXPECT_NEAR(fr, 1.0f / 9.0f, 1e-6f);  // η = 1/(1 − 0.5) = 2
  const Vec3 grazing = normalize(Vec3(1, 0, 0.5f));
  layer_weight(0.25f, grazing, n, false, &fr, &facing);
  EXPECT_NEAR(facing, 1.0f - std::pow(grazing.z, 0.5f), 1e-6f);  // blend < 0.5: exponent 2·blend
  // Total internal reflection on the inside.
  EXPECT_EQ(fresnel_node(1.5f, grazing, n, true), 1.0f);
}

TEST(GraphOps, NormalMapTangentSpace) {
  const Vec3 n(0, 0, 1), t(1, 0, 0);
  // Flat colour (0.5, 0.5, 1) leaves the normal.
  expect_vec(normal_map_tangent(Vec3(0.5f, 0.5f, 1.0f), 1.0f, t, 1.0f, n, n, false), n);
  // Colour (1, 0.5, 0.5): the tangent; sign −1 mirrors the bitangent.
  expect_vec(normal_map_tangent(Vec3(1.0f, 0.5f, 0.5f), 1.0f, t, 1.0f, n, n, false), t);
  expect_vec(normal_map_tangent(Vec3(0.5f, 1.0f, 0.5f), 1.0f, t, -1.0f, n, n, false), Vec3(0, -1, 0));
  // Strength s: normalize(N + (Nmap − N)·s); back faces turn the mapped normal.
  const Vec3 mapped = normalize(Vec3(1, 0, 1));
  expect_vec(normal_map_tangent(Vec3(1.0f, 0.5f, 1.0f), 0.5f, t, 1.0f, n, n, false),
             normalize(n + (mapped - n) * 0.5f));
  expect_vec(normal_map_tangent(Vec3(1.0f, 0.5f, 1.0f), 1.0f, t, 1.0f, n, -n, true), -mapped);
}

TEST(GraphOps, TransformKinds) {
  const std::array<float, 12> m = {2, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3};
  expect_vec(transform(m, TransformKind::Point, Vec3(1, 1, 1), false), Vec3(3, 3, 4));
  expect_vec(transform(m, TransformKind::Vector, Vec3(1, 1, 1), false), Vec3(2, 1, 1));
  expect_vec(transform(m, TransformKind::Vector, Vec3(1, 0, 0), true), Vec3(1, 0, 0));
}

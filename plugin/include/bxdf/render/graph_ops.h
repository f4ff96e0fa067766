// The value ops of material graphs, each Cycles 3.4's formula (kernel/svm/*.h): the program in
// material_graph.cpp calls these, the graph reader maps Blender's names to their enums, and the
// tests check each against an independent evaluation.
#pragma once

#include <string>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/render/material_graph.h"
#include "bxdf/render/valid_reflection.h"  // ensure_valid_reflection, used by bump and normal maps

namespace bxdf::render {

// Cycles' safe_normalize: a zero vector stays zero.
inline Vec3 safe_normalize(const Vec3& v) {
  const float l = length(v);
  return l != 0.0f ? v / l : v;
}

// Names as the graph files spell them (Blender's identifiers, lower case), in enum order.
enum class MixBlend {
  Mix, Add, Multiply, Screen, Overlay, Subtract, Divide, Difference, Darken, Lighten, SoftLight,
  LinearLight, Dodge, Burn, Hue, Saturation, Value, Color,
};
extern const std::vector<std::string> kMixBlendNames;
enum class MathOp {
  Add, Subtract, Multiply, Divide, MultiplyAdd, Power, Logarithm, Sqrt, InverseSqrt, Absolute,
  Exponent, Minimum, Maximum, LessThan, GreaterThan, Sign, Compare, SmoothMin, SmoothMax, Round,
  Floor, Ceil, Trunc, Fract, Modulo, Wrap, Snap, Pingpong, Sine, Cosine, Tangent, Arcsine,
  Arccosine, Arctangent, Arctan2, Sinh, Cosh, Tanh, Radians, Degrees,
};
extern const std::vector<std::string> kMathOpNames;
enum class VectorMathOp {
  Add, Subtract, Multiply, Divide, MultiplyAdd, CrossProduct, DotProduct, Distance, Length, Scale,
  Normalize, Absolute, Minimum, Maximum, Floor, Ceil, Fraction,
};
extern const std::vector<std::string> kVectorMathOpNames;
enum class TransformKind { Point, Vector, Normal };
extern const std::vector<std::string> kTransformKindNames;

// Mix RGB (svm/color_util.h): the factor is saturated; `clamp` saturates the result.
Vec3 mix_rgb(MixBlend blend, float fac, const Vec3& a, const Vec3& b, bool clamp);
// Math node (svm/math_util.h); `clamp` saturates the result.
float math(MathOp op, float a, float b, float c, bool clamp);
// Vector Math node: vector and value outputs.
void vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c, float scale,
                 Vec3* vector, float* value);
Vec3 invert(float fac, const Vec3& color);
Vec3 gamma(const Vec3& color, float gamma);
Vec3 bright_contrast(const Vec3& color, float bright, float contrast);
Vec3 hsv(float hue, float saturation, float value, float fac, const Vec3& color);
Vec3 rgb_to_hsv(const Vec3& rgb);
Vec3 hsv_to_rgb(const Vec3& hsv);
// Fresnel node: Cycles' fresnel_dielectric_cos(dot(I, N), η), η inverted on back faces.
float fresnel_node(float ior, const Vec3& incoming, const Vec3& normal, bool backfacing);
// Layer Weight: fresnel and facing outputs.
void layer_weight(float blend, const Vec3& incoming, const Vec3& normal, bool backfacing,
                  float* fresnel, float* facing);
Vec3 transform(const std::array<float, 12>& m, TransformKind kind, const Vec3& v, bool normalize);

// Color Ramp: Blender's colour band sampled at i/255 (BKE_colorband_evaluate) into Cycles'
// table; stops are (pos, r, g, b, a) sorted by pos.
enum class RampInterpolation { Constant, Linear, Ease, Cardinal, BSpline };
extern const std::vector<std::string> kRampInterpolationNames;
enum class RampColorMode { RGB, HSV, HSL };
extern const std::vector<std::string> kRampColorModeNames;
enum class RampHue { Near, Far, Clockwise, CounterClockwise };
extern const std::vector<std::string> kRampHueNames;
// Throws ParameterError for no stops or unsorted ones.
ColorRampTable color_ramp_table(const std::vector<std::array<float, 5>>& stops,
                                RampInterpolation interpolation,
                                RampColorMode color_mode = RampColorMode::RGB,
                                RampHue hue = RampHue::Near);
Vec3 rgb_to_hsl(const Vec3& rgb);
Vec3 hsl_to_rgb(const Vec3& hsl);
// Cycles' rgb_ramp_lookup without extrapolation.
void color_ramp(const ColorRampTable& table, float fac, Vec3* color, float* alpha);

// Normal Map, tangent space (svm/tex_coord.h), in two steps around the object → world normal
// transform: the mapped normal's direction from `color` in [0, 1]³, the UV map's interpolated
// tangent and sign and the (object-space) smooth normal (not normalised: the caller normalises
// after its transform, which keeps the direction); then turn it for back faces and apply
// Cycles' strength rule about the (world) shading normal. normal_map_tangent does both with
// no transform between.
Vec3 normal_map_direction(const Vec3& color, const Vec3& tangent, float sign, const Vec3& normal);
Vec3 normal_map_finish(Vec3 n, float strength, const Vec3& shading_normal, bool backfacing);
Vec3 normal_map_tangent(const Vec3& color, float strength, const Vec3& tangent, float sign,
                        const Vec3& smooth_normal, const Vec3& shading_normal, bool backfacing);

// Bump (svm/displace.h): the height at the point and at p + dpdx, p + dpdy; `normal` is the
// unperturbed normal (the Normal input or the shading normal). The result has passed
// ensure_valid_reflection.
struct BumpInputs {
  float height = 0.0f, height_x = 0.0f, height_y = 0.0f;
  Vec3 dpdx, dpdy, normal;
  float strength = 1.0f, distance = 1.0f;
  bool invert = false;
};
Vec3 bump_normal(const BumpInputs& in, const Vec3& ng, const Vec3& incoming);

}  // namespace bxdf::render

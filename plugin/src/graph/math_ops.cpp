// Math, Vector Math, Fresnel, Layer Weight and matrix transforms of material graphs (Cycles
// 3.4's svm/math_util.h, svm/fresnel.h, util/math.h).
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

const std::vector<std::string> kMathOpNames = {
    "add",      "subtract",   "multiply",    "divide",     "multiply_add", "power",
    "logarithm", "sqrt",      "inverse_sqrt", "absolute",  "exponent",     "minimum",
    "maximum",  "less_than",  "greater_than", "sign",      "compare",      "smooth_min",
    "smooth_max", "round",    "floor",       "ceil",       "trunc",        "fract",
    "modulo",   "wrap",       "snap",        "pingpong",   "sine",         "cosine",
    "tangent",  "arcsine",    "arccosine",   "arctangent", "arctan2",      "sinh",
    "cosh",     "tanh",       "radians",     "degrees"};
const std::vector<std::string> kVectorMathOpNames = {
    "add",      "subtract", "multiply", "divide", "multiply_add", "cross_product",
    "dot_product", "distance", "length", "scale", "normalize",    "absolute",
    "minimum",  "maximum",  "floor",    "ceil",   "fraction"};
const std::vector<std::string> kTransformKindNames = {"point", "vector", "normal"};

namespace {

float safe_divide(float a, float b) { return b != 0.0f ? a / b : 0.0f; }
float safe_pow(float a, float b) {
  if (a < 0.0f && b != static_cast<float>(static_cast<int>(b))) return 0.0f;
  return std::pow(a, b);
}
float safe_log(float a, float b) {
  if (a <= 0.0f || b <= 0.0f) return 0.0f;
  return safe_divide(std::log(a), std::log(b));
}
float smooth_min(float a, float b, float k) {
  if (k == 0.0f) return std::fmin(a, b);
  const float h = std::fmax(k - std::fabs(a - b), 0.0f) / k;
  return std::fmin(a, b) - h * h * h * k * (1.0f / 6.0f);
}
float wrap(float value, float max, float min) {
  const float range = max - min;
  return range != 0.0f ? value - range * std::floor((value - min) / range) : min;
}
float pingpong(float a, float b) {
  if (b == 0.0f) return 0.0f;
  const float x = (a - b) / (b * 2.0f);
  return std::fabs((x - std::floor(x)) * b * 2.0f - b);
}
float sign(float a) { return a == 0.0f ? 0.0f : (a < 0.0f ? -1.0f : 1.0f); }

// Cycles' fresnel_dielectric_cos.
float fresnel_dielectric_cos(float cosi, float eta) {
  const float c = std::fabs(cosi);
  float g = eta * eta - 1.0f + c * c;
  if (!(g > 0.0f)) return 1.0f;
  g = std::sqrt(g);
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

}  // namespace

float math(MathOp op, float a, float b, float c, bool clamp_result) {
  float r = 0.0f;
  switch (op) {
    case MathOp::Add: r = a + b; break;
    case MathOp::Subtract: r = a - b; break;
    case MathOp::Multiply: r = a * b; break;
    case MathOp::Divide: r = safe_divide(a, b); break;
    case MathOp::MultiplyAdd: r = a * b + c; break;
    case MathOp::Power: r = safe_pow(a, b); break;
    case MathOp::Logarithm: r = safe_log(a, b); break;
    case MathOp::Sqrt: r = std::sqrt(std::max(a, 0.0f)); break;
    case MathOp::InverseSqrt: r = a > 0.0f ? 1.0f / std::sqrt(a) : 0.0f; break;
    case MathOp::Absolute: r = std::fabs(a); break;
    case MathOp::Exponent: r = std::exp(a); break;
    case MathOp::Minimum: r = std::fmin(a, b); break;
    case MathOp::Maximum: r = std::fmax(a, b); break;
    case MathOp::LessThan: r = a < b ? 1.0f : 0.0f; break;
    case MathOp::GreaterThan: r = a > b ? 1.0f : 0.0f; break;
    case MathOp::Sign: r = sign(a); break;
    case MathOp::Compare:
      r = (a == b || std::fabs(a - b) <= std::fmax(c, FLT_EPSILON)) ? 1.0f : 0.0f;
      break;
    case MathOp::SmoothMin: r = smooth_min(a, b, c); break;
    case MathOp::SmoothMax: r = -smooth_min(-a, -b, c); break;
    case MathOp::Round: r = std::floor(a + 0.5f); break;
    case MathOp::Floor: r = std::floor(a); break;
    case MathOp::Ceil: r = std::ceil(a); break;
    case MathOp::Trunc: r = a >= 0.0f ? std::floor(a) : std::ceil(a); break;
    case MathOp::Fract: r = a - std::floor(a); break;
    case MathOp::Modulo: r = b != 0.0f ? std::fmod(a, b) : 0.0f; break;
    case MathOp::Wrap: r = wrap(a, b, c); break;
    case MathOp::Snap: r = std::floor(safe_divide(a, b)) * b; break;
    case MathOp::Pingpong: r = pingpong(a, b); break;
    case MathOp::Sine: r = std::sin(a); break;
    case MathOp::Cosine: r = std::cos(a); break;
    case MathOp::Tangent: r = std::tan(a); break;
    case MathOp::Arcsine: r = std::asin(clamp(a, -1.0f, 1.0f)); break;
    case MathOp::Arccosine: r = std::acos(clamp(a, -1.0f, 1.0f)); break;
    case MathOp::Arctangent: r = std::atan(a); break;
    case MathOp::Arctan2: r = std::atan2(a, b); break;
    case MathOp::Sinh: r = std::sinh(a); break;
    case MathOp::Cosh: r = std::cosh(a); break;
    case MathOp::Tanh: r = std::tanh(a); break;
    case MathOp::Radians: r = a * (kPi / 180.0f); break;
    case MathOp::Degrees: r = a * (180.0f / kPi); break;
  }
  return clamp_result ? clamp(r, 0.0f, 1.0f) : r;
}

void vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c, float scale,
                 Vec3* vector, float* value) {
  *vector = Vec3(0.0f, 0.0f, 0.0f);
  *value = 0.0f;
  auto each = [](const Vec3& x, const Vec3& y, auto f) {
    return Vec3(f(x.x, y.x), f(x.y, y.y), f(x.z, y.z));
  };
  switch (op) {
    case VectorMathOp::Add: *vector = a + b; break;
    case VectorMathOp::Subtract: *vector = a - b; break;
    case VectorMathOp::Multiply: *vector = each(a, b, [](float x, float y) { return x * y; }); break;
    case VectorMathOp::Divide: *vector = each(a, b, safe_divide); break;
    case VectorMathOp::MultiplyAdd:
      *vector = each(a, b, [](float x, float y) { return x * y; }) + c;
      break;
    case VectorMathOp::CrossProduct: *vector = cross(a, b); break;
    case VectorMathOp::DotProduct: *value = dot(a, b); break;
    case VectorMathOp::Distance: *value = length(a - b); break;
    case VectorMathOp::Length: *value = length(a); break;
    case VectorMathOp::Scale: *vector = a * scale; break;
    case VectorMathOp::Normalize: *vector = safe_normalize(a); break;
    case VectorMathOp::Absolute:
      *vector = Vec3(std::fabs(a.x), std::fabs(a.y), std::fabs(a.z));
      break;
    case VectorMathOp::Minimum:
      *vector = each(a, b, [](float x, float y) { return std::fmin(x, y); });
      break;
    case VectorMathOp::Maximum:
      *vector = each(a, b, [](float x, float y) { return std::fmax(x, y); });
      break;
    case VectorMathOp::Floor: *vector = Vec3(std::floor(a.x), std::floor(a.y), std::floor(a.z)); break;
    case VectorMathOp::Ceil: *vector = Vec3(std::ceil(a.x), std::ceil(a.y), std::ceil(a.z)); break;
    case VectorMathOp::Fraction:
      *vector = a - Vec3(std::floor(a.x), std::floor(a.y), std::floor(a.z));
      break;
  }
}

float fresnel_node(float ior, const Vec3& incoming, const Vec3& normal, bool backfacing) {
  float eta = std::fmax(ior, 1e-5f);
  eta = backfacing ? 1.0f / eta : eta;
  return fresnel_dielectric_cos(dot(incoming, normal), eta);
}

void layer_weight(float blend, const Vec3& incoming, const Vec3& normal, bool backfacing,
                  float* fresnel, float* facing) {
  float eta = std::fmax(1.0f - blend, 1e-5f);
  eta = backfacing ? eta : 1.0f / eta;
  *fresnel = fresnel_dielectric_cos(dot(incoming, normal), eta);
  float f = std::fabs(dot(incoming, normal));
  if (blend != 0.5f) {
    float b = clamp(blend, 0.0f, 1.0f - 1e-5f);
    b = b < 0.5f ? 2.0f * b : 0.5f / (1.0f - b);
    f = std::pow(f, b);
  }
  *facing = 1.0f - f;
}

Vec3 transform(const std::array<float, 12>& m, TransformKind kind, const Vec3& v,
               bool normalize_result) {
  // For normals the reader has stored the inverse transpose (and no translation).
  const float w = kind == TransformKind::Point ? 1.0f : 0.0f;
  Vec3 out(m[0] * v.x + m[1] * v.y + m[2] * v.z + m[3] * w,
           m[4] * v.x + m[5] * v.y + m[6] * v.z + m[7] * w,
           m[8] * v.x + m[9] * v.y + m[10] * v.z + m[11] * w);
  if (normalize_result) {
    const float l = length(out);
    if (l != 0.0f) out = out / l;
  }
  return out;
}

}  // namespace bxdf::render

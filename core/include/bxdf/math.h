// Scalar and 3-vector math shared by every model. Directions live in the local
// shading frame (z = normal) unless a name says otherwise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace bxdf {

// Marks the small functions the batch kernels are built from. A loop vectorises only if every
// call in it is inlined, and in a file with many model instantiations GCC's inline budget
// (inline-unit-growth) runs out before it reaches them.
#define BXDF_KERNEL inline __attribute__((always_inline))

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv2Pi = 0.15915494309189533577f;
constexpr float kInv4Pi = 0.07957747154594766788f;
constexpr float kPiOver2 = 1.57079632679489661923f;
constexpr float kPiOver4 = 0.78539816339744830961f;
constexpr float kSqrtPi = 1.77245385090551602730f;
constexpr float kInvSqrtPi = 0.56418958354775628695f;

inline float radians(float deg) { return deg * (kPi / 180.0f); }
inline float degrees(float rad) { return rad * (180.0f / kPi); }

template <class T>
inline T clamp(T v, T lo, T hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// sqrt that treats tiny negative round-off as zero instead of producing NaN.
BXDF_KERNEL float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
inline float safe_acos(float x) { return std::acos(clamp(x, -1.0f, 1.0f)); }

// True for a finite, non-negative number (NaN fails both comparisons).
BXDF_KERNEL bool finite_nonnegative(float x) {
  return x >= 0.0f && x <= std::numeric_limits<float>::max();
}
// Maps NaN, Inf and negatives to 0: the last line of defence before a value leaves a model.
BXDF_KERNEL float sanitize_nonnegative(float x) { return finite_nonnegative(x) ? x : 0.0f; }

// e^x for x in [−87, 88] (a normal result), within 1 ulp of the correctly rounded value:
// Cephes' expf (x = n ln 2 + r with ln 2 in two parts, a degree-5 polynomial in r, times 2^n
// built in the exponent bits). Unlike std::exp it has no call and no branch, so a loop over it
// vectorises; scalar and batch code that both use it agree bit for bit.
BXDF_KERNEL float exp_poly(float x) {
  constexpr float kLog2e = 1.44269504088896341f;
  constexpr float kRound = 12582912.0f;  // 1.5 · 2^23: adding, then subtracting it rounds
  const float n = (x * kLog2e + kRound) - kRound;
  const float r = (x - n * 0.693359375f) - n * -2.12194440e-4f;
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * (r * r) + r + 1.0f;
  const int32_t bits = (static_cast<int32_t>(n) + 127) * (1 << 23);  // 2^n
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

// sin x and cos x for |x| <= π/4, within 2 ulp: Cephes' sinf and cosf polynomials, made for
// that interval (no range reduction, no call).
struct SinCos {
  float sin, cos;
};
inline SinCos sin_cos_within_quarter_pi(float x) {
  const float z = x * x;
  const float s = ((-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f) * z * x + x;
  const float c =
      ((2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f) * z * z -
      0.5f * z + 1.0f;
  return {s, c};
}

// acos(x) for x in [-1, 1], within 2 ulp: Cephes' acosf, through asin(z) = z + z³ P(z²) on
// [0, 1/2] and acos|x| = 2 asin(√((1 − |x|)/2)) above; inline and without a call.
inline float acos_poly(float x) {
  const float a = std::fabs(x);
  const bool wide = a > 0.5f;
  const float z = wide ? 0.5f * (1.0f - a) : a * a;
  const float w = wide ? std::sqrt(z) : a;
  const float asin_w =
      ((((4.2163199048e-2f * z + 2.4181311049e-2f) * z + 4.5470025998e-2f) * z +
        7.4953002686e-2f) * z + 1.6666752422e-1f) * z * w + w;
  const float acos_a = wide ? 2.0f * asin_w : kPiOver2 - asin_w;
  return x < 0.0f ? kPi - acos_a : acos_a;
}

struct Vec3 {
  float x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  Vec3 operator/(float s) const { return *this * (1.0f / s); }
  Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
  bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
};
inline Vec3 operator*(float s, const Vec3& v) { return v * s; }
inline float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float abs_dot(const Vec3& a, const Vec3& b) { return std::fabs(dot(a, b)); }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length_squared(const Vec3& v) { return dot(v, v); }
inline float length(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalize(const Vec3& v) { return v / length(v); }
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// Flips v into the hemisphere of ref.
inline Vec3 face_forward(const Vec3& v, const Vec3& ref) { return dot(v, ref) < 0.0f ? -v : v; }

// A squared length a direction may have: not tiny (zero), not infinite, not NaN.
BXDF_KERNEL bool is_direction_length_squared(float l2) {
  return l2 > 1e-30f && l2 <= std::numeric_limits<float>::max();
}

// A squared length this close to 1 (|v| within about 4 ulps of 1) is a unit vector already:
// rescaling it would change only its last bits.
constexpr float kUnitLengthSquaredTolerance = 1e-6f;
BXDF_KERNEL bool is_unit_length_squared(float l2) {
  return std::fabs(l2 - 1.0f) <= kUnitLengthSquaredTolerance;
}

// The factor that normalises a vector of squared length l2 as normalize_direction() does:
// 1 for a unit vector, and 1 where l2 is refused (tiny or not finite), which callers that
// select instead of branching mask themselves (batch blocks, sampled directions, half vectors).
BXDF_KERNEL float normalizing_scale(float l2) {
  return !is_direction_length_squared(l2) || is_unit_length_squared(l2) ? 1.0f
                                                                         : 1.0f / std::sqrt(l2);
}

// Normalises a direction a caller handed us. Returns false for zero, tiny or non-finite
// vectors, which every model treats as "no direction" and answers with 0. A unit vector is
// kept as it is: the renderer hands every model unit directions, several times per path
// vertex, and the square root and division in series would cost it more than the model's own
// arithmetic for the simple ones (Lambertian).
BXDF_KERNEL bool normalize_direction(Vec3& v) {
  const float l2 = length_squared(v);
  if (!is_direction_length_squared(l2)) return false;
  if (!is_unit_length_squared(l2)) v = v * (1.0f / std::sqrt(l2));
  return true;
}

// A sampled direction returned with the bits f will see: normalised to a fixed point of
// normalize_direction (the normalisation every entry point applies), which one or two passes
// reach. Lobes whose f is steep in float (grazing rough refraction) or hashes its directions
// (multiscatter) need it so that sample_f reports f() of the direction it returns. False for a
// degenerate vector.
inline bool snap_to_unit(Vec3& v) {
  for (int i = 0; i < 4; ++i) {
    Vec3 w = v;
    if (!normalize_direction(w)) return false;
    if (w.x == v.x && w.y == v.y && w.z == v.z) return true;
    v = w;
  }
  return true;
}

// Two-sided coordinate system around a unit vector (Duff et al. 2017, branchless ONB).
inline void coordinate_system(const Vec3& n, Vec3* s, Vec3* t) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  *s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  *t = Vec3(b, sign + n.y * n.y * a, -n.y);
}

struct Point2 {
  float x = 0, y = 0;
  constexpr Point2() = default;
  constexpr Point2(float x_, float y_) : x(x_), y(y_) {}
};

}  // namespace bxdf

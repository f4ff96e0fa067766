// The inline polynomials of math.h that stand in for library calls in the renderer's hot
// paths: each within 2 ulp of the correctly rounded value over the whole range it is used on.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bxdf/math.h"

using namespace bxdf;

namespace {

// One unit in the last place of the float nearest |v| (the smallest subnormal at 0).
double ulp_of(double v) {
  const float f = float(std::fabs(v));
  return double(std::nextafter(f, std::numeric_limits<float>::infinity()) - f);
}

}  // namespace

TEST(MathPolynomials, SinCosWithinQuarterPiAgreeWithTheLibrary) {
  // The concentric map's polynomial sine and cosine: within 2 ulp of sin and cos (in double)
  // over the whole interval it is used on, and exact at 0.
  for (int i = -20000; i <= 20000; ++i) {
    const float x = float(kPiOver4) * float(i) / 20000.0f;
    const SinCos a = sin_cos_within_quarter_pi(x);
    const double s = std::sin(double(x)), c = std::cos(double(x));
    ASSERT_LE(std::fabs(a.sin - s), 2.0 * ulp_of(s)) << "x = " << x;
    ASSERT_LE(std::fabs(a.cos - c), 2.0 * ulp_of(c)) << "x = " << x;
  }
  EXPECT_EQ(sin_cos_within_quarter_pi(0.0f).sin, 0.0f);
  EXPECT_EQ(sin_cos_within_quarter_pi(0.0f).cos, 1.0f);
}

TEST(MathPolynomials, AcosAgreesWithTheLibraryOverMinusOneToOne) {
  for (int i = -100000; i <= 100000; ++i) {
    const float x = float(i) / 100000.0f;
    const double reference = std::acos(double(x));
    ASSERT_LE(std::fabs(acos_poly(x) - reference), 2.0 * ulp_of(reference)) << "x = " << x;
  }
  // Near the ends, where acos is steepest, and at them.
  for (float x = 1.0f; x > 0.999f; x = std::nextafter(x, 0.0f)) {
    for (const float v : {x, -x}) {
      const double reference = std::acos(double(v));
      ASSERT_LE(std::fabs(acos_poly(v) - reference), 2.0 * ulp_of(reference)) << "x = " << v;
    }
  }
  EXPECT_EQ(acos_poly(1.0f), 0.0f);
  EXPECT_EQ(acos_poly(0.0f), float(kPiOver2));
}

// Cycles' shading offset factor (K/closure/bsdf.h, shift_cos_in): the value, the identity at
// offset 0, and 0 at or below the viewer-side horizon (where Cycles' max(cos(·), 0) is 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bxdf/render/shadow_terminator.h"

namespace bxdf::render {
namespace {

TEST(ShadowTerminator, ShadingOffsetFactorIsCyclesShiftCosIn) {
  const float offset = 0.8f;
  const float frequency = 1.0f / (1.0f - 0.5f * offset);
  for (float c : {1.0f, 0.9f, 0.7f, 0.5f, 0.3f}) {
    const float expected = std::max(std::cos(std::acos(c) * frequency), 0.0f) / c;
    EXPECT_NEAR(shading_offset_factor(c, offset), expected, 1e-6f) << "cos_in " << c;
  }
  EXPECT_FLOAT_EQ(shading_offset_factor(1.0f, offset), 1.0f);
  EXPECT_EQ(shading_offset_factor(0.3f, offset), 0.0f);  // 72.5° · 5/3 is past 90°
}

TEST(ShadowTerminator, ShadingOffsetIsOneWithoutOffsetAndZeroBelowTheHorizon) {
  for (float c : {-1.0f, -0.2f, 0.0f, 0.4f, 1.0f}) EXPECT_EQ(shading_offset_factor(c, 0.0f), 1.0f);
  for (float c : {-1.0f, -0.2f, 0.0f, -0.0f}) EXPECT_EQ(shading_offset_factor(c, 0.5f), 0.0f);
  EXPECT_EQ(shading_offset_factor(std::nanf(""), 0.5f), 0.0f);
  EXPECT_TRUE(std::isfinite(shading_offset_factor(1e-30f, 0.1f)));
}

}  // namespace
}  // namespace bxdf::render

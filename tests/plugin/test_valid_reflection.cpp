// Cycles' ensure_valid_reflection: a valid normal is kept; an invalid one is bent, in the plane
// of ng and n, to a unit normal whose mirror direction of the view rises exactly to the
// threshold min(0.9·(ng·wo), 0.01) above the surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bxdf/render/valid_reflection.h"

namespace bxdf::render {
namespace {

Vec3 mirror(const Vec3& n, const Vec3& wo) { return n * (2.0f * dot(n, wo)) - wo; }

TEST(ValidReflection, KeepsANormalWhoseReflectionClearsTheSurface) {
  const Vec3 ng(0, 0, 1);
  const Vec3 n = normalize(Vec3(0.2f, 0.1f, 1.0f));
  const Vec3 wo = normalize(Vec3(-0.3f, 0.2f, 0.9f));
  const Vec3 out = ensure_valid_reflection(ng, wo, n);
  EXPECT_EQ(out.x, n.x);
  EXPECT_EQ(out.y, n.y);
  EXPECT_EQ(out.z, n.z);
}

TEST(ValidReflection, BendsASilhouetteNormalJustEnough) {
  // Grazing views of a facet whose smooth normal leans away from the viewer.
  const Vec3 ng(0, 0, 1);
  for (float lean : {0.2f, 0.5f, 1.0f, 3.0f}) {
    for (float view_z : {0.02f, 0.1f, 0.3f}) {
      const Vec3 n = normalize(Vec3(lean, 0.3f, 1.0f));
      const Vec3 wo = normalize(Vec3(-1.0f, 0.1f, view_z));
      ASSERT_LT(dot(ng, mirror(n, wo)), std::min(0.9f * dot(ng, wo), 0.01f));
      const Vec3 out = ensure_valid_reflection(ng, wo, n);
      const std::string where = "lean " + std::to_string(lean) + " view_z " + std::to_string(view_z);
      EXPECT_NEAR(length(out), 1.0f, 1e-5f) << where;
      EXPECT_NEAR(dot(out, cross(ng, n)), 0.0f, 1e-5f) << where;  // in the plane of ng and n
      EXPECT_GT(dot(out, wo), 0.0f) << where;                      // the viewer sees its front
      EXPECT_NEAR(dot(ng, mirror(out, wo)), std::min(0.9f * dot(ng, wo), 0.01f), 2e-4f) << where;
    }
  }
}

TEST(ValidReflection, FallsBackToTheGeometricNormalAndNeverReturnsNaN) {
  const Vec3 ng(0, 0, 1);
  const Vec3 wo = normalize(Vec3(-1.0f, 0.0f, 0.05f));
  // The shading normal equal to ng but the view below it: nothing to bend.
  const Vec3 same = ensure_valid_reflection(ng, normalize(Vec3(1, 0, -0.1f)), ng);
  EXPECT_TRUE(is_finite(same));
  for (const Vec3& n : {Vec3(0, 0, -1), normalize(Vec3(1, 0, -0.2f)), Vec3(1, 0, 0)}) {
    const Vec3 out = ensure_valid_reflection(ng, wo, n);
    EXPECT_TRUE(is_finite(out));
    EXPECT_NEAR(length(out), 1.0f, 1e-5f);
  }
}

}  // namespace
}  // namespace bxdf::render

// The warps of sampling.h that the renderer's diffuse and microfacet samplers start from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bxdf/sampling.h"

using namespace bxdf;

TEST(Sampling, ConcentricDiskStaysInTheDiskAndKeepsItsQuadrant) {
  for (int i = 0; i < 257; ++i)
    for (int j = 0; j < 257; ++j) {
      const Point2 u(float(i) / 256.0f * 0x1.fffffep-1f, float(j) / 256.0f * 0x1.fffffep-1f);
      const Point2 d = sample_concentric_disk(u);
      ASSERT_LE(d.x * d.x + d.y * d.y, 1.0f + 1e-6f);
      const float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
      // The radius is the square's max norm (the map is area-preserving ring by ring).
      ASSERT_NEAR(std::sqrt(d.x * d.x + d.y * d.y), std::max(std::fabs(ox), std::fabs(oy)), 2e-6f);
      if (ox != 0.0f && oy != 0.0f) {
        ASSERT_GE(d.x * ox, -1e-6f);
        ASSERT_GE(d.y * oy, -1e-6f);
      }
    }
}

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
      const float r = std::max(std::fabs(ox), std::fabs(oy));
      ASSERT_NEAR(std::sqrt(d.x * d.x + d.y * d.y), r, 2e-6f);
      if (ox != 0.0f && oy != 0.0f) {
        ASSERT_GE(d.x * ox, -1e-6f);
        ASSERT_GE(d.y * oy, -1e-6f);
      }
      // Shirley and Chiu's map as written with the library's cos and sin, in double.
      if (r == 0.0f) continue;
      const bool x_major = std::fabs(ox) > std::fabs(oy);
      const double radius = x_major ? ox : oy;
      const double theta = x_major ? kPiOver4 * (double(oy) / ox)
                                   : kPiOver2 - kPiOver4 * (double(ox) / oy);
      ASSERT_NEAR(d.x, radius * std::cos(theta), 1e-6) << ox << ", " << oy;
      ASSERT_NEAR(d.y, radius * std::sin(theta), 1e-6) << ox << ", " << oy;
    }
}

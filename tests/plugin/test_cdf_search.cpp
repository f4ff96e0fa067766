// first_above: the index std::upper_bound gives, for the counted few entries as for the
// searched many, with empty intervals (repeated entries) and numbers on the entries themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "bxdf/render/cdf_search.h"
#include "bxdf/rng.h"

using bxdf::render::first_above;

TEST(CdfSearch, FirstAboveIsUpperBound) {
  bxdf::PCG32 rng(3, 5);
  for (size_t n = 1; n <= 20; ++n) {
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<float> cdf(n);
      float sum = 0.0f;
      for (size_t k = 0; k < n; ++k) {
        // About one interval in four is empty: its entry repeats the one before.
        sum += rng.uniform() < 0.25f ? 0.0f : rng.uniform();
        cdf[k] = sum;
      }
      std::vector<float> xs = {0.0f, sum, sum * 2.0f, -1.0f};
      for (float c : cdf) xs.push_back(c);  // exactly on an entry
      for (int k = 0; k < 20; ++k) xs.push_back(rng.uniform() * sum);
      for (float x : xs) {
        const auto expected = static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), x) -
                                                  cdf.begin());
        ASSERT_EQ(first_above(cdf, x), expected) << n << " entries, x = " << x;
      }
    }
  }
}

// The Owen-scrambled Sobol sampler (plugin/src/sampler): the Sobol generator itself, the
// stratification the scrambling must keep, unbiasedness on known integrals, the variance it buys
// over independent numbers, and decorrelation between a path's dimension sets.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "sampler/path_sampler.h"
#include "sampler/sobol_burley.h"
#include "sampler/sobol_burley_batch.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

// Does every elementary interval of 2^-a by 2^-b (a + b = m) hold exactly one of the 2^m points?
bool is_zero_m_two_net(const std::vector<std::array<float, 2>>& pts, int m) {
  for (int a = 0; a <= m; ++a) {
    const int b = m - a;
    std::vector<int> count(size_t(1) << m, 0);
    for (const auto& p : pts) {
      const int i = static_cast<int>(std::ldexp(p[0], a)), j = static_cast<int>(std::ldexp(p[1], b));
      ++count[(static_cast<size_t>(i) << b) | static_cast<size_t>(j)];
    }
    for (int c : count)
      if (c != 1) return false;
  }
  return true;
}

// One point per interval of 2^-m.
bool is_stratified_1d(const std::vector<float>& xs, int m) {
  std::set<int> cells;
  for (float x : xs) cells.insert(static_cast<int>(std::ldexp(x, m)));
  return cells.size() == xs.size() && xs.size() == (size_t(1) << m);
}

}  // namespace

TEST(SobolBurley, UnscrambledPointsAreSobols) {
  // Dimension 0 is van der Corput; dimension 1 (polynomial x + 1) starts 0, 1/2, 3/4, 1/4, 5/8 ...
  const float dim0[8] = {0, 0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
  const float dim1[8] = {0, 0.5f, 0.75f, 0.25f, 0.625f, 0.125f, 0.375f, 0.875f};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol::to_unit_float(sobol::sobol(i, 0)), dim0[i]) << i;
    EXPECT_EQ(sobol::to_unit_float(sobol::sobol(i, 1)), dim1[i]) << i;
  }
  // The byte-table product equals the generator matrix times the index, for full 32-bit indices.
  uint32_t index = 0x12345678u;
  for (int k = 0; k < 1000; ++k, index = sobol::hash(index)) {
    for (int d = 0; d < sobol::kDimensions; ++d) {
      uint32_t expected = 0;
      for (int bit = 0; bit < 32; ++bit)
        if ((index >> bit) & 1u) expected ^= sobol::directions(d)[size_t(bit)];
      EXPECT_EQ(sobol::sobol(index, d), expected) << "dim " << d << " index " << index;
    }
  }
  // Every generator matrix is invertible (triangular with a unit diagonal): column i is m_i / 2^i
  // with m_i odd, so its lowest set bit is 2^-i.
  for (int d = 0; d < sobol::kDimensions; ++d) {
    for (int i = 0; i < 32; ++i) {
      const uint64_t v = sobol::directions(d)[size_t(i)];
      EXPECT_EQ((v >> (31 - i)) & 1u, 1u) << d << " " << i;
      EXPECT_EQ((v << (i + 1)) & 0xffffffffu, 0u) << d << " " << i;
    }
  }
}

TEST(SobolBurley, OwenScrambleIsAPermutationOfEachLevel) {
  // Nested scrambling maps the 2^k intervals of each level onto each other one to one.
  for (uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
    std::set<uint32_t> images;
    for (uint32_t x = 0; x < 256; ++x) images.insert(sobol::owen_scramble(x << 24, seed) >> 24);
    EXPECT_EQ(images.size(), 256u) << seed;
  }
}

TEST(SobolBurley, PrefixesAreStratifiedForAnySeed) {
  for (uint32_t seed : {0u, 7u, 123456u, 0xffffffffu}) {
    for (int m = 0; m <= 10; ++m) {
      const uint32_t n = 1u << m;
      std::vector<std::array<float, 2>> pairs;
      std::vector<std::vector<float>> coords(sobol::kDimensions);
      for (uint32_t i = 0; i < n; ++i) {
        const auto p2 = sobol::sample<2>(i, seed);
        pairs.push_back(p2);
        const auto p4 = sobol::sample<4>(i, seed);
        for (int d = 0; d < sobol::kDimensions; ++d) coords[size_t(d)].push_back(p4[size_t(d)]);
      }
      EXPECT_TRUE(is_zero_m_two_net(pairs, m)) << "seed " << seed << ", 2^" << m << " points";
      for (int d = 0; d < sobol::kDimensions; ++d)
        EXPECT_TRUE(is_stratified_1d(coords[size_t(d)], m)) << "seed " << seed << " dim " << d;
    }
  }
}

TEST(SobolBurley, EstimatesAreUnbiasedAndLessNoisyThanIndependentSamples) {
  // Two integrals over [0,1)^3: a disc's indicator (discontinuous) and a smooth product.
  struct Integrand {
    const char* name;
    double exact;
    double (*f)(double, double, double);
  };
  const Integrand integrands[] = {
      {"quarter disc", M_PI / 4.0, [](double x, double y, double) { return x * x + y * y < 1.0 ? 1.0 : 0.0; }},
      {"x e^y z^2", 0.5 * (std::exp(1.0) - 1.0) / 3.0,
       [](double x, double y, double z) { return x * std::exp(y) * z * z; }},
  };
  constexpr int kSamples = 64, kSeeds = 4000;
  for (const Integrand& g : integrands) {
    double sum = 0.0, sum_sq = 0.0, f_sum = 0.0, f_sum_sq = 0.0;
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
      double estimate = 0.0;
      for (uint32_t i = 0; i < kSamples; ++i) {
        const auto u = sobol::sample<3>(i, sobol::hash(seed));
        const double v = g.f(u[0], u[1], u[2]);
        estimate += v;
        f_sum += v;
        f_sum_sq += v * v;
      }
      estimate /= kSamples;
      sum += estimate;
      sum_sq += estimate * estimate;
    }
    const double mean = sum / kSeeds;
    const double variance = sum_sq / kSeeds - mean * mean;
    const double f_mean = f_sum / (double(kSamples) * kSeeds);
    const double independent_variance = (f_sum_sq / (double(kSamples) * kSeeds) - f_mean * f_mean) / kSamples;
    EXPECT_NEAR(mean, g.exact, 5.0 * std::sqrt(variance / kSeeds) + 1e-7) << g.name;
    EXPECT_LT(variance, 0.25 * independent_variance) << g.name;
  }
}

TEST(SobolBurley, SampleEqualsItsDefinitionBitForBit) {
  // sample() runs in the bit-reversed domain with reversed tables; it must give exactly the
  // points of the plain definition (shuffle the index, take the Sobol coordinate, scramble).
  uint32_t seed = 12345u, index = 0u;
  for (int k = 0; k < 20000; ++k, seed = sobol::hash(seed + 1u)) {
    index = k < 10000 ? uint32_t(k) : sobol::hash(index ^ seed);  // small and full 32-bit indices
    const uint32_t shuffled = sobol::owen_scramble(index, sobol::hash(seed ^ sobol::kSalt[sobol::kDimensions]));
    const auto got = sobol::sample<4>(index, seed);
    for (int d = 0; d < sobol::kDimensions; ++d) {
      const float expected = sobol::to_unit_float(
          sobol::owen_scramble(sobol::sobol(shuffled, d), sobol::hash(seed ^ sobol::kSalt[d])));
      ASSERT_EQ(got[size_t(d)], expected) << "dim " << d << " index " << index << " seed " << seed;
    }
  }
}

TEST(SobolBurley, ReverseBitsReverses) {
  for (uint32_t bit = 0; bit < 32; ++bit)
    EXPECT_EQ(sobol::reverse_bits(1u << bit), 1u << (31 - bit)) << bit;
  EXPECT_EQ(sobol::reverse_bits(0x12345678u), 0x1e6a2c48u);
}

TEST(SobolBurley, ReversedToUnitFloatIsTheFloatOfTheReversal) {
  uint32_t x = 1u;
  for (int k = 0; k < 100000; ++k, x = sobol::hash(x + uint32_t(k)))
    ASSERT_EQ(sobol::reversed_to_unit_float(x), sobol::to_unit_float(sobol::reverse_bits(x))) << x;
  for (uint32_t bit = 0; bit < 32; ++bit)
    EXPECT_EQ(sobol::reversed_to_unit_float(1u << bit),
              sobol::to_unit_float(sobol::reverse_bits(1u << bit))) << bit;
}

TEST(PathSampler, DimensionSetsAreDecorrelated) {
  // E[u v] = 1/4 for independent uniforms; the same seed reused for two purposes would give
  // E[u^2] = 1/3. Taken over many pixels and samples.
  double light_bsdf = 0.0, bounce_pair = 0.0, filter_rr = 0.0;
  int n = 0;
  for (uint32_t px = 0; px < 64; ++px) {
    const uint32_t seed = PathSampler::pixel_seed(px, 3, 42);
    for (uint32_t s = 0; s < 64; ++s, ++n) {
      const PathSampler sampler(seed, s);
      light_bsdf += double(sampler.light(1).y) * sampler.bsdf(1).x;
      bounce_pair += double(sampler.bsdf(0).x) * sampler.bsdf(1).x;
      filter_rr += double(sampler.filter().y) * sampler.russian_roulette(0);
      for (float u : {sampler.light(2).x, sampler.light(2).y}) {
        EXPECT_GE(u, 0.0f);
        EXPECT_LT(u, 1.0f);
      }
    }
  }
  // Standard deviation of a mean of n products of independent uniforms: sqrt(7/144 / n).
  const double tolerance = 5.0 * std::sqrt(7.0 / 144.0 / n);
  EXPECT_NEAR(light_bsdf / n, 0.25, tolerance);
  EXPECT_NEAR(bounce_pair / n, 0.25, tolerance);
  EXPECT_NEAR(filter_rr / n, 0.25, tolerance);
}

TEST(PathSampler, PixelsGetDifferentSequencesAndSeedsChangeThem) {
  const PathSampler a(PathSampler::pixel_seed(10, 20, 0), 0);
  const PathSampler b(PathSampler::pixel_seed(11, 20, 0), 0);
  const PathSampler c(PathSampler::pixel_seed(10, 20, 1), 0);
  EXPECT_NE(a.bsdf(0).x, b.bsdf(0).x);
  EXPECT_NE(a.bsdf(0).x, c.bsdf(0).x);
  EXPECT_EQ(a.bsdf(0).x, PathSampler(PathSampler::pixel_seed(10, 20, 0), 0).bsdf(0).x);
}

TEST(PathSampler, DrawsAreTheSetsSobolBurleyPointsAtEveryBounce) {
  // The sampler reverses the index once and looks the first sets' hashes up in a table; its
  // numbers must stay those of sample(index, pixel seed ^ hash(set number)), with set number
  // bounce * 4 + purpose (filter, light, BSDF, Russian roulette), also past the table.
  uint32_t index = 0u;
  for (uint32_t k = 0; k < 200; ++k) {
    index = k < 100 ? k : sobol::hash(index + k);  // small and full 32-bit indices
    const uint32_t seed = PathSampler::pixel_seed(k % 7, k / 7, 99);
    const PathSampler sampler(seed, index);
    const auto filter = sobol::sample<2>(index, seed ^ sobol::hash(0));
    ASSERT_EQ(sampler.filter().x, filter[0]);
    ASSERT_EQ(sampler.filter().y, filter[1]);
    for (int bounce = 0; bounce < 40; ++bounce) {
      const uint32_t set = static_cast<uint32_t>(bounce) * 4u;
      const auto light = sobol::sample<2>(index, seed ^ sobol::hash(set + 1u));
      const auto bsdf = sobol::sample<2>(index, seed ^ sobol::hash(set + 2u));
      const auto rr = sobol::sample<1>(index, seed ^ sobol::hash(set + 3u));
      ASSERT_EQ(sampler.light(bounce).x, light[0]) << "bounce " << bounce << " index " << index;
      ASSERT_EQ(sampler.light(bounce).y, light[1]) << "bounce " << bounce << " index " << index;
      ASSERT_EQ(sampler.bsdf(bounce).x, bsdf[0]) << "bounce " << bounce;
      ASSERT_EQ(sampler.bsdf(bounce).y, bsdf[1]) << "bounce " << bounce;
      ASSERT_EQ(sampler.russian_roulette(bounce), rr[0]) << "bounce " << bounce;
    }
  }
}

TEST(SobolBurley, DimensionOneByBitOperationsIsTheGeneratorMatrix) {
  for (uint32_t i = 0; i < 4096; ++i)
    ASSERT_EQ(sobol::reversed_sobol_dimension1(i), sobol::reverse_bits(sobol::sobol(i, 1))) << i;
  uint32_t index = 0x9e3779b9u;
  for (int k = 0; k < 100000; ++k, index = sobol::hash(index + 1u))
    ASSERT_EQ(sobol::reversed_sobol_dimension1(index), sobol::reverse_bits(sobol::sobol(index, 1)))
        << index;
}

TEST(SobolBurley, BatchDrawsEqualSingleDrawsBitForBit) {
  // Every length, so that both the eight-wide part (where the CPU has AVX2) and the remainder
  // are compared; indices small and full 32-bit.
  constexpr int kMax = 100;
  uint32_t reversed[kMax], seed[kMax];
  float x[kMax], y[kMax], x1[kMax];
  uint32_t h = 7u;
  for (int n = 0; n <= kMax; ++n) {
    for (int i = 0; i < n; ++i) {
      h = sobol::hash(h + 1u);
      reversed[i] = sobol::reverse_bits(n % 2 ? uint32_t(i) : h);
      seed[i] = sobol::hash(h ^ 0x51u);
    }
    sobol::sample_reversed_2d(reversed, seed, n, x, y);
    sobol::sample_reversed_1d(reversed, seed, n, x1);
    for (int i = 0; i < n; ++i) {
      const auto u = sobol::sample_reversed<2>(reversed[i], seed[i]);
      ASSERT_EQ(x[i], u[0]) << "n " << n << " i " << i;
      ASSERT_EQ(y[i], u[1]) << "n " << n << " i " << i;
      ASSERT_EQ(x1[i], sobol::sample_reversed<1>(reversed[i], seed[i])[0]) << "n " << n << " i " << i;
    }
  }
}

TEST(PathSampler, NumbersDrawnAheadAreTheSamplersOwn) {
  constexpr int kN = 150;  // more than one chunk of draw_vertices
  uint32_t seeds[kN], indices[kN];
  int vertices[kN];
  for (int i = 0; i < kN; ++i) {
    seeds[i] = PathSampler::pixel_seed(uint32_t(i % 13), uint32_t(i / 13), 5);
    indices[i] = i < 100 ? uint32_t(i) : sobol::hash(uint32_t(i));
    vertices[i] = i % 23;  // also past the tabulated sets' hashes
  }
  Point2 filters[kN];
  VertexNumbers numbers[kN], without_light[kN];
  float roulette[kN];
  PathSampler::draw_filters(seeds, indices, kN, filters);
  PathSampler::draw_vertices(seeds, indices, vertices, kN, true, numbers);
  PathSampler::draw_vertices(seeds, indices, vertices, kN, false, without_light);
  PathSampler::draw_roulette(seeds, indices, vertices, kN, roulette);
  for (int i = 0; i < kN; ++i) {
    numbers[i].russian_roulette = roulette[i];
    numbers[i].has_roulette = true;
  }
  for (int i = 0; i < kN; ++i) {
    // Drawn without the light's or the roulette's numbers, a sampler draws those itself.
    const PathSampler own(seeds[i], indices[i]);
    const PathSampler own_light(seeds[i], indices[i], &without_light[i]);
    ASSERT_EQ(without_light[i].bsdf.x, numbers[i].bsdf.x) << i;
    ASSERT_EQ(without_light[i].bsdf.y, numbers[i].bsdf.y) << i;
    ASSERT_EQ(own_light.light(vertices[i]).x, own.light(vertices[i]).x) << i;
    ASSERT_EQ(own_light.light(vertices[i]).y, own.light(vertices[i]).y) << i;
    ASSERT_EQ(own_light.russian_roulette(vertices[i]), own.russian_roulette(vertices[i])) << i;
    ASSERT_EQ(filters[i].x, own.filter().x) << i;
    ASSERT_EQ(filters[i].y, own.filter().y) << i;
    ASSERT_EQ(numbers[i].vertex, vertices[i]);
    ASSERT_EQ(numbers[i].light.x, own.light(vertices[i]).x) << i;
    ASSERT_EQ(numbers[i].light.y, own.light(vertices[i]).y) << i;
    ASSERT_EQ(numbers[i].bsdf.x, own.bsdf(vertices[i]).x) << i;
    ASSERT_EQ(numbers[i].bsdf.y, own.bsdf(vertices[i]).y) << i;
    ASSERT_EQ(numbers[i].russian_roulette, own.russian_roulette(vertices[i])) << i;
    // A sampler given them returns them for that vertex and draws any other itself.
    const PathSampler ahead(seeds[i], indices[i], &numbers[i]);
    ASSERT_EQ(ahead.bsdf(vertices[i]).x, numbers[i].bsdf.x);
    ASSERT_EQ(ahead.light(vertices[i]).y, numbers[i].light.y);
    ASSERT_EQ(ahead.russian_roulette(vertices[i]), numbers[i].russian_roulette);
    ASSERT_EQ(ahead.bsdf(vertices[i] + 1).x, own.bsdf(vertices[i] + 1).x);
    ASSERT_EQ(ahead.russian_roulette(vertices[i] + 1), own.russian_roulette(vertices[i] + 1));
  }
}

namespace {

// True when the points (32-bit fractions, 2^m of them) have exactly one point in every
// elementary interval of area 2^-m: a (0, m, 2)-net.
bool is_0m2_net(const std::vector<std::array<uint32_t, 2>>& points, int m) {
  for (int a = 0; a <= m; ++a) {
    std::vector<uint8_t> seen(size_t(1) << m, 0);
    for (const auto& p : points) {
      const uint32_t x = a == 0 ? 0u : p[0] >> (32 - a);
      const uint32_t y = a == m ? 0u : p[1] >> (32 - (m - a));
      uint8_t& cell = seen[(size_t(x) << (m - a)) | y];
      if (cell) return false;
      cell = 1;
    }
  }
  return true;
}

std::array<uint32_t, 2> fraction_bits(float x, float y) {
  return {uint32_t(double(x) * 0x1p32), uint32_t(double(y) * 0x1p32)};
}

}  // namespace

TEST(PathSampler, LightAndBsdfPointsOfAPixelAreZeroM2Nets) {
  // Every 2D draw of a vertex comes from Sobol dimensions 0 and 1, the pair whose every
  // power-of-two prefix is a (0, m, 2)-net (Owen scrambling and the index shuffle keep that):
  // the light point as much as the BSDF direction. Dimensions 1 and 2 fail already at m = 2.
  for (uint32_t px = 0; px < 4; ++px) {
    const uint32_t seed = PathSampler::pixel_seed(px, 7, 5);
    for (int bounce = 0; bounce < 3; ++bounce)
      for (int m = 1; m <= 8; ++m) {
        std::vector<std::array<uint32_t, 2>> light, bsdf;
        for (uint32_t s = 0; s < (1u << m); ++s) {
          const PathSampler sampler(seed, s);
          light.push_back(fraction_bits(sampler.light(bounce).x, sampler.light(bounce).y));
          bsdf.push_back(fraction_bits(sampler.bsdf(bounce).x, sampler.bsdf(bounce).y));
        }
        EXPECT_TRUE(is_0m2_net(light, m)) << "light, pixel " << px << " bounce " << bounce << " m " << m;
        EXPECT_TRUE(is_0m2_net(bsdf, m)) << "bsdf, pixel " << px << " bounce " << bounce << " m " << m;
      }
  }
  // The check itself tells the pairs apart (dimensions 1 and 2 happen to be a net at m = 3).
  for (int m : {2, 4, 5, 6, 7, 8}) {
    std::vector<std::array<uint32_t, 2>> dims12;
    for (uint32_t s = 0; s < (1u << m); ++s) dims12.push_back({sobol::sobol(s, 1), sobol::sobol(s, 2)});
    EXPECT_FALSE(is_0m2_net(dims12, m)) << "m " << m;
  }
}

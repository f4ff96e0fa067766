// Adaptive sampling as Cycles does it: its automatic threshold and minimum, when the check runs,
// the convergence test, the neighbours' dilation and the viewport's noise floor on films made by
// hand, and renders where pixels stop (still sampled pixels keep the plain render's bits; a
// constant image stops at the first check).
#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_sampling.h"
#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

RenderSettings adaptive_settings(float threshold, int min_samples, int spp) {
  RenderSettings s;
  s.samples_per_pixel = spp;
  s.adaptive_sampling = true;
  s.adaptive_threshold = threshold;
  s.adaptive_min_samples = min_samples;
  return s;
}

CameraSettings camera_at(const Vec3& eye, const Vec3& target) {
  CameraSettings c;
  c.camera_to_world = look_at(eye, target, Vec3(0, 0, 1));
  return c;
}

}  // namespace

TEST(AdaptiveSampling, AutomaticThresholdAndMinimumAreCycles) {
  EXPECT_FALSE(AdaptiveSampling::of(RenderSettings{}).use);
  // Cycles' comment: threshold 0.1 → 32, 0.01 → 64, 0.001 → 128 minimum samples.
  EXPECT_EQ(AdaptiveSampling::of(adaptive_settings(0.1f, 0, 1024)).min_samples, 32);
  EXPECT_EQ(AdaptiveSampling::of(adaptive_settings(0.01f, 0, 1024)).min_samples, 64);
  EXPECT_EQ(AdaptiveSampling::of(adaptive_settings(0.001f, 0, 1024)).min_samples, 128);
  EXPECT_FLOAT_EQ(AdaptiveSampling::of(adaptive_settings(0.01f, 0, 1024)).threshold, 0.05f);
  // Threshold 0: max(0.001, 1/samples), then times 5.
  EXPECT_FLOAT_EQ(AdaptiveSampling::of(adaptive_settings(0.0f, 0, 256)).threshold, 5.0f / 256.0f);
  EXPECT_FLOAT_EQ(AdaptiveSampling::of(adaptive_settings(0.0f, 0, 4096)).threshold, 0.005f);
  // A minimum set by hand is at least 4.
  EXPECT_EQ(AdaptiveSampling::of(adaptive_settings(0.01f, 2, 64)).min_samples, 4);
  EXPECT_EQ(AdaptiveSampling::of(adaptive_settings(0.01f, 40, 64)).min_samples, 40);
}

TEST(AdaptiveSampling, PassesEndWhereTheCheckRuns) {
  for (const int min_samples : {4, 16, 40, 64}) {
    AdaptiveSampling a;
    a.use = true;
    a.min_samples = min_samples;
    for (int start = 0; start < 200; ++start)
      for (int n = 1; n < 70; ++n) {
        // Cycles' naive definition, which align_samples computes in closed form.
        int count = 1;
        while (!a.need_filter(start + count - 1) && count < n) ++count;
        ASSERT_EQ(a.align_samples(start, n), count) << min_samples << " " << start << " " << n;
      }
    // The first check after more than min_samples samples, at the end of a block of 16.
    int first = 0;
    while (!a.need_filter(first)) ++first;
    EXPECT_EQ(first, (min_samples + 1) | 15);
    EXPECT_TRUE(a.need_filter(first + 16));
    EXPECT_FALSE(a.need_filter(first + 8));
  }
  AdaptiveSampling off;
  EXPECT_EQ(off.align_samples(3, 50), 50);
  EXPECT_FALSE(off.need_filter(79));
}

TEST(AdaptiveSampling, ClassAIsHalfOfEveryBlockOfFour) {
  for (uint32_t block = 0; block < 1000; ++block) {
    int a = 0;
    for (uint32_t s = 4 * block; s < 4 * block + 4; ++s) a += sample_is_class_a(s);
    EXPECT_EQ(a, 2) << block;
  }
  EXPECT_FALSE(sample_is_class_a(0));
  EXPECT_FALSE(sample_is_class_a(1));
  EXPECT_TRUE(sample_is_class_a(2));
  EXPECT_TRUE(sample_is_class_a(3));
}

TEST(AdaptiveSampling, ConvergenceTestAndNeighbourDilation) {
  // A 7x5 film of 16 samples of 1.0 per pixel, each class-A sample counted twice in the half
  // sum: those pixels' mean and half mean agree, so they have converged. One pixel differs.
  Film film(7, 5);
  film.enable_adaptive();
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      for (uint32_t s = 0; s < 16; ++s) {
        RGB v(1.0f);
        if (x == 3 && y == 2) v = RGB(sample_is_class_a(s) ? 0.0f : 3.0f);  // half sum 0
        film.add_sample(x, y, v, 1.0f);
        if (sample_is_class_a(s)) film.add_half_sample(x, y, v);
      }
  // Its error, Cycles' formula on the film's sums (equal channels): the channels' summed
  // difference of the sum and the half sum over the samples, over √(summed mean).
  const double* I = film.sum(3, 2);
  const double* A = film.half_sum(3, 2);
  const float diff = float(std::fabs(I[0] - A[0]) * 3) / 16.0f;
  const float norm = std::sqrt(float(I[0] * 3) / 16.0f);
  const float error = diff / (0.0001f + norm);
  EXPECT_GT(error, 0.0f);
  // Just above the error the pixel converges; just below it it does not.
  EXPECT_EQ(update_converged_pixels(film, error * 1.001f, false), 0u);
  EXPECT_TRUE(film.converged(3, 2));
  // Judged again (reset) below its error: it and its row's, then their columns', neighbours are
  // sampled again, a 3x3 block.
  EXPECT_EQ(update_converged_pixels(film, error * 0.999f, true), 9u);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      EXPECT_EQ(film.converged(x, y), !(std::abs(x - 3) <= 1 && std::abs(y - 2) <= 1)) << x << y;
  // Without reset a stopped pixel stays stopped, whatever the threshold.
  EXPECT_EQ(update_converged_pixels(film, error * 1.001f, false), 0u);
  EXPECT_EQ(update_converged_pixels(film, 0.0f, false), 0u);
  // The other pixels: no difference, so any threshold above 0 stops them.
  EXPECT_EQ(update_converged_pixels(film, 1e-6f, true), 9u);
}

namespace {

// A 5x5 film of 16 samples per pixel, each pixel's mean 1 and its half mean 1 + d(x, y): its
// error is 3 |d| / (0.0001 + √3) (the convergence test on three equal channels).
Film film_with_differences(float centre_difference) {
  Film film(5, 5);
  film.enable_adaptive();
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      const float d = x == 2 && y == 2 ? centre_difference : 0.0f;
      for (uint32_t s = 0; s < 16; ++s) {
        film.add_sample(x, y, RGB(1.0f), 1.0f);
        // The class-A samples (8 of 16), twice each, sum to 16 (1 + d).
        if (sample_is_class_a(s)) film.add_half_sample(x, y, RGB(1.0f + d));
      }
    }
  return film;
}

float error_of(float difference) { return 3.0f * difference / (0.0001f + std::sqrt(3.0f)); }

}  // namespace

TEST(AdaptiveSampling, TheViewportsNoiseFloorHalvesUntilAPixelFailsIt) {
  AdaptiveSampling adaptive;
  adaptive.use = true;
  adaptive.threshold = 0.05f;  // Noise Threshold 0.01
  // The centre's error 0.15: it meets 0.4 and 0.2 but not 0.1.
  const float d = 0.15f / error_of(1.0f);
  {
    Film film = film_with_differences(d);
    ConvergenceChecks viewport(adaptive, true);
    EXPECT_FLOAT_EQ(viewport.threshold(), 0.4f);
    EXPECT_FALSE(viewport.all_converged(film));
    EXPECT_FLOAT_EQ(viewport.threshold(), 0.1f);  // 0.4 and 0.2 met by all, then judged again
    EXPECT_FALSE(film.converged(2, 2));
    EXPECT_FALSE(film.converged(1, 2));  // its neighbours go on with it
    EXPECT_TRUE(film.converged(0, 0));
  }
  {
    // A final render judges against 0.05 at once.
    Film film = film_with_differences(d);
    ConvergenceChecks final_render(adaptive, false);
    EXPECT_FLOAT_EQ(final_render.threshold(), 0.05f);
    EXPECT_FALSE(final_render.all_converged(film));
    EXPECT_FLOAT_EQ(final_render.threshold(), 0.05f);
  }
  {
    // Error 0.03, below every floor: the viewport goes down to 0.05 in one check and is done.
    Film film = film_with_differences(0.03f / error_of(1.0f));
    ConvergenceChecks viewport(adaptive, true);
    EXPECT_TRUE(viewport.all_converged(film));
    EXPECT_FLOAT_EQ(viewport.threshold(), 0.05f);
  }
}

TEST(AdaptiveSampling, AConstantImageStopsAtTheFirstCheck) {
  Scene scene;  // nothing but a grey world: every sample of every pixel is 0.25
  scene.set_world(RGB(0.25f));
  scene.commit();
  RenderSettings s = adaptive_settings(0.01f, 0, 256);
  s.width = 20;
  s.height = 12;
  RenderStats stats;
  const Film film = render_scene(scene, camera_at(Vec3(0, -5, 0), Vec3(0, 0, 0)), s, {}, &stats);
  EXPECT_TRUE(stats.converged);
  EXPECT_FALSE(stats.cancelled);
  EXPECT_EQ(stats.samples_per_pixel, 80);  // the first check: after sample (64 + 1) | 15
  EXPECT_EQ(stats.camera_samples, 80u * 20u * 12u);
  float px[4];
  film.pixel(7, 5, px);
  EXPECT_FLOAT_EQ(px[0], 0.25f);
}

TEST(AdaptiveSampling, SampledPixelsKeepThePlainRendersBitsAndStoppedOnesAreClose) {
  // A diffuse sphere on a floor under a point light and a grey world: the floor's lit and
  // shadowed parts and the world converge at different rates.
  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  scene.add_mesh(make_uv_sphere(Vec3(0, 0, 0), 1.0f, 32, 16, 0).view());
  scene.add_mesh(make_quad(Vec3(-4, -4, -1), Vec3(8, 0, 0), Vec3(0, 8, 0), 0).view());
  scene.add_light(point_light(Vec3(2, -2, 3), RGB(20.0f)));
  scene.set_world(RGB(0.1f));
  scene.commit();
  const CameraSettings camera = camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0));
  RenderSettings plain;
  plain.width = 32;
  plain.height = 24;
  plain.samples_per_pixel = 160;
  plain.max_bounces = 3;
  RenderSettings adaptive = plain;
  adaptive.adaptive_sampling = true;
  adaptive.adaptive_threshold = 0.01f;
  adaptive.adaptive_min_samples = 16;
  RenderStats plain_stats, adaptive_stats;
  const Film reference = render_scene(scene, camera, plain, {}, &plain_stats);
  adaptive.threads = 1;
  const Film one = render_scene(scene, camera, adaptive, {}, &adaptive_stats);
  adaptive.threads = 2;
  const Film two = render_scene(scene, camera, adaptive, {});
  EXPECT_EQ(one.rgba(), two.rgba());  // the thread count changes no bit
  int stopped = 0, sampled = 0;
  double diff = 0.0, sum = 0.0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      const uint32_t n = one.samples(x, y);
      EXPECT_EQ(n, two.samples(x, y));
      float a[4], b[4];
      one.pixel(x, y, a);
      reference.pixel(x, y, b);
      if (n == 160u) {
        ++sampled;
        for (int c = 0; c < 4; ++c) EXPECT_EQ(a[c], b[c]) << x << " " << y;
      } else {
        ++stopped;
        // Stopped after a check: 16 + 1 | 15 = 31 samples, then every 16.
        EXPECT_EQ((n - 32u) % 16u, 0u) << n;
        EXPECT_GE(n, 32u);
      }
      for (int c = 0; c < 3; ++c) {
        diff += std::fabs(a[c] - b[c]);
        sum += b[c];
      }
    }
  EXPECT_GT(stopped, 0);
  EXPECT_GT(sampled, 0);
  EXPECT_LT(adaptive_stats.camera_samples, plain_stats.camera_samples);
  EXPECT_LT(diff / sum, 0.05);  // the stopped pixels' means are near the full render's
  EXPECT_FALSE(adaptive_stats.cancelled);
}

TEST(AdaptiveSampling, RefusesBadSettingsByName) {
  Scene scene;
  scene.set_world(RGB(0.25f));
  scene.commit();
  const CameraSettings camera = camera_at(Vec3(0, -5, 0), Vec3(0, 0, 0));
  for (const float bad : {-0.1f, 1.5f, std::nanf("")}) {
    RenderSettings s = adaptive_settings(bad, 0, 16);
    try {
      render_scene(scene, camera, s);
      ADD_FAILURE() << bad;
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find("adaptive_threshold"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("[0, 1]"), std::string::npos) << e.what();
    }
  }
  RenderSettings s = adaptive_settings(0.01f, 5000, 16);
  try {
    render_scene(scene, camera, s);
    ADD_FAILURE();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("adaptive_min_samples"), std::string::npos) << e.what();
  }
}

// The render loop: deterministic images whatever the thread count, progress and pass callbacks,
// cancelling, refusing bad settings, pixel filter distributions, area lights, and no NaN or Inf
// reaching the film.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "bxdf/microfacet/multiscatter_ggx.h"
#include "bxdf/microfacet/walk_numbers.h"
#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"
#include "progressive_pass.h"
#include "bxdf/rng.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

CameraSettings camera_at(const Vec3& eye, const Vec3& target) {
  CameraSettings c;
  c.camera_to_world = look_at(eye, target, Vec3(0, 0, 1));
  return c;
}

// A small scene with a diffuse sphere, a floor, a point light and a grey world.
struct SmallScene {
  Scene scene;
  SmallScene() {
    scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
    const Mesh sphere = make_uv_sphere(Vec3(0, 0, 0), 1.0f, 32, 16, 0);
    const Mesh floor = make_quad(Vec3(-4, -4, -1), Vec3(8, 0, 0), Vec3(0, 8, 0), 0);
    scene.add_mesh(sphere.view());
    scene.add_mesh(floor.view());
    scene.add_light(point_light(Vec3(2, -2, 3), RGB(20.0f)));
    scene.set_world(RGB(0.1f));
    scene.commit();
  }
};

RenderSettings small_settings() {
  RenderSettings s;
  s.width = 24;
  s.height = 20;
  s.samples_per_pixel = 8;
  s.max_bounces = 3;
  s.tile_size = 8;
  return s;
}

// A closed Lambertian box around the origin (half-size 2), the camera's room in the roulette
// tests; with `white_world` a world the box hides from every ray.
void add_closed_lambertian_box(Scene& scene, const RGBValue& reflectance, bool white_world) {
  ParamSet p;
  p.set("reflectance", reflectance);
  scene.add_material(Material{{make("lambertian", p)}, RGB(0.0f)});
  const Mesh box = make_box(Vec3(-2, -2, -2), Vec3(2, 2, 2), 0);
  scene.add_mesh(box.view());
  if (white_world) scene.set_world(RGB(1.0f));
}

}  // namespace

TEST(Renderer, ImageDoesNotDependOnThreadCount) {
  SmallScene sc;
  RenderSettings s = small_settings();
  s.threads = 1;
  const std::vector<float> one = render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s).rgba();
  s.threads = 2;
  s.samples_per_pass = 3;  // another pass split
  const std::vector<float> two = render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s).rgba();
  s.samples_per_pass = 0;
  const std::vector<float> two_same_passes =
      render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s).rgba();
  EXPECT_EQ(one, two_same_passes);  // bit for bit
  // Another pass split draws other random numbers, but estimates the same image.
  double diff = 0, sum = 0;
  for (size_t i = 0; i < one.size(); ++i) {
    diff += std::fabs(one[i] - two[i]);
    sum += one[i];
  }
  EXPECT_LT(diff / sum, 0.1);
  EXPECT_GT(sum, 0.0);
}

// Multiscatter GGX walks are salted per camera sample and draw each vertex's walk numbers,
// through each render thread's slots: the image is the same bits at any thread count, and the
// thread that rendered is left with neither (an evaluation after the render is the unsalted f
// again).
TEST(Renderer, MultiscatterWalksAreSaltedPerSampleAndTheSaltIsRestored) {
  Scene scene;
  ParamSet multiscatter;
  multiscatter.set("distribution", std::string("multi_ggx"));
  multiscatter.set("roughness", 0.6);
  const BxDFPtr glossy = make("cycles_glossy", multiscatter);
  scene.add_material(Material{{glossy}, RGB(0.0f)});
  scene.add_mesh(make_uv_sphere(Vec3(0, 0, 0), 1.0f, 32, 16, 0).view());
  scene.add_light(point_light(Vec3(2, -2, 3), RGB(20.0f)));
  scene.set_world(RGB(0.2f));
  scene.commit();
  const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 0.9f)), wi = normalize(Vec3(-0.5f, 0.2f, 0.6f));
  const RGB unsalted = glossy->f(wo, wi);
  RenderSettings s = small_settings();
  s.threads = 1;
  const std::vector<float> one = render_scene(scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s).rgba();
  EXPECT_EQ(microfacet::MultiscatterWalkSalt::current(), 0u);
  EXPECT_EQ(microfacet::MultiscatterWalkNumbers::current(), nullptr);
  EXPECT_EQ(glossy->f(wo, wi).r, unsalted.r);
  s.threads = 2;
  const std::vector<float> two = render_scene(scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s).rgba();
  EXPECT_EQ(one, two);
  EXPECT_EQ(microfacet::MultiscatterWalkSalt::current(), 0u);
  EXPECT_EQ(microfacet::MultiscatterWalkNumbers::current(), nullptr);
  double sum = 0.0;
  for (float v : one) sum += v;
  EXPECT_GT(sum, 0.0);
}

TEST(Renderer, ProgressPassesAndCancel) {
  SmallScene sc;
  RenderSettings s = small_settings();
  s.samples_per_pass = 2;  // 4 passes of 3 x 3 tiles
  s.threads = 2;
  int tiles = 0, passes = 0, last_samples = 0;
  RenderCallbacks cb;
  cb.on_tile = [&](const RenderProgress& p) {
    ++tiles;
    EXPECT_EQ(p.tiles_total, 4u * 9u);
    EXPECT_LE(p.tiles_done, p.tiles_total);
    return true;
  };
  cb.on_pass = [&](const Film& film, const RenderProgress& p) {
    ++passes;
    EXPECT_EQ(p.pass, passes);
    EXPECT_EQ(p.samples_done, last_samples + 2);
    last_samples = p.samples_done;
    EXPECT_EQ(film.samples(0, 0), static_cast<uint32_t>(p.samples_done));
  };
  RenderStats stats;
  render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s, cb, &stats);
  EXPECT_EQ(tiles, 36);
  EXPECT_EQ(passes, 4);
  EXPECT_FALSE(stats.cancelled);
  EXPECT_EQ(stats.samples_per_pixel, 8);
  EXPECT_EQ(stats.camera_samples, 24u * 20u * 8u);
  EXPECT_GT(stats.rays, stats.camera_samples);
  // The threads' time in tiles: some, and no more than they had.
  EXPECT_EQ(stats.threads, s.threads);
  EXPECT_GT(stats.tile_seconds, 0.0);
  EXPECT_LE(stats.tile_seconds, stats.threads * stats.seconds);
  // Their CPU time in tiles: some, and no more than the tiles' wall time (a little slack for
  // the two clocks' granularity).
  EXPECT_GT(stats.tile_cpu_seconds, 0.0);
  EXPECT_LE(stats.tile_cpu_seconds, stats.tile_seconds * 1.05 + 1e-3);

  // Returning false from the tile callback stops before the next tiles.
  int seen = 0;
  RenderCallbacks stop;
  stop.on_tile = [&](const RenderProgress&) { return ++seen < 5; };
  RenderStats cancelled;
  s.threads = 1;
  render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s, stop, &cancelled);
  EXPECT_TRUE(cancelled.cancelled);
  EXPECT_EQ(seen, 5);
  EXPECT_EQ(cancelled.samples_per_pixel, 0);

  // A cancel flag set beforehand renders nothing.
  std::atomic<bool> flag{true};
  RenderCallbacks flagged;
  flagged.cancel = &flag;
  RenderStats none;
  render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s, flagged, &none);
  EXPECT_TRUE(none.cancelled);
  EXPECT_EQ(none.camera_samples, 0u);
}

// Passes are for partial images: without on_pass the render is one pass (one tile callback per
// tile), with the same bits as the passes on_pass asks for; a cancel reaches a tile between its
// batches, so even one long tile stops early.
TEST(Renderer, OnePassWithoutPartialImagesAndCancelInsideATile) {
  SmallScene sc;
  RenderSettings s = small_settings();
  s.threads = 2;
  int tiles = 0, passes = 0;
  RenderCallbacks no_pass;
  no_pass.on_tile = [&](const RenderProgress& p) {
    ++tiles;
    EXPECT_EQ(p.tiles_total, 9u);
    return true;
  };
  const std::vector<float> one_pass =
      render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s, no_pass).rgba();
  EXPECT_EQ(tiles, 9);
  RenderCallbacks with_pass;
  with_pass.on_pass = [&](const Film&, const RenderProgress&) { ++passes; };
  const std::vector<float> in_passes =
      render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s, with_pass).rgba();
  EXPECT_EQ(passes, 8);  // about spp/8 samples each: one
  EXPECT_EQ(one_pass, in_passes);  // bit for bit

  // One tile of 24 x 20 pixels at 2^14 samples (several seconds), cancelled after 50 ms.
  s.tile_size = 32;
  s.samples_per_pixel = 1 << 14;
  s.threads = 1;
  std::atomic<bool> flag{false};
  RenderCallbacks flagged;
  flagged.cancel = &flag;
  RenderStats stats;
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    flag = true;
  });
  render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s, flagged, &stats);
  canceller.join();
  EXPECT_TRUE(stats.cancelled);
  EXPECT_EQ(stats.samples_per_pixel, 0);
  EXPECT_GT(stats.camera_samples, 0u);
  EXPECT_LT(stats.camera_samples, 24u * 20u * (1u << 14) / 4);
}

// Progressive passes (a viewport's): one sample first, then passes sized to Cycles' display
// interval for the time rendered; the same bits as one pass, and every tile-sample counted.
TEST(Renderer, ProgressivePassesStartWithOneSampleAndKeepTheImage) {
  EXPECT_EQ(progressive_pass_samples(0.0, 0, 64), 1);
  EXPECT_EQ(progressive_pass_samples(0.05, 1, 64), 2);    // 0.05 s a sample: two fit 0.1 s
  EXPECT_EQ(progressive_pass_samples(0.5, 1, 64), 1);     // at least one
  EXPECT_EQ(progressive_pass_samples(1.5, 32, 64), 5);    // 0.047 s a sample, 0.25 s from 1 s on
  EXPECT_EQ(progressive_pass_samples(3.0, 60, 4), 4);     // 0.5 s from 2 s on, but only 4 remain
  EXPECT_EQ(progressive_pass_samples(3.0, 60, 64), 10);   // 0.5 s at 0.05 s a sample
  EXPECT_EQ(progressive_pass_samples(9.0, 96, 1000), 21); // 2 s past 8 s and 32 samples
  EXPECT_DOUBLE_EQ(display_update_interval(9.0, 31), 1.0);

  SmallScene sc;
  RenderSettings s = small_settings();
  s.samples_per_pixel = 40;
  s.threads = 2;
  const CameraSettings camera = camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0));
  const std::vector<float> one_pass = render_scene(sc.scene, camera, s).rgba();
  s.progressive = true;
  std::vector<int> pass_samples;
  uint64_t tiles_done = 0, tiles_total = 0;
  RenderCallbacks cb;
  cb.on_tile = [&](const RenderProgress& p) {
    tiles_done = p.tiles_done;
    tiles_total = p.tiles_total;
    return true;
  };
  cb.on_pass = [&](const Film& film, const RenderProgress& p) {
    EXPECT_EQ(p.passes, 0);  // not known ahead
    pass_samples.push_back(p.samples_done);
    EXPECT_EQ(film.samples(0, 0), static_cast<uint32_t>(p.samples_done));
  };
  RenderStats stats;
  const std::vector<float> progressive = render_scene(sc.scene, camera, s, cb, &stats).rgba();
  EXPECT_EQ(progressive, one_pass);  // bit for bit
  ASSERT_GE(pass_samples.size(), 2u);
  EXPECT_EQ(pass_samples.front(), 1);
  EXPECT_EQ(pass_samples.back(), 40);
  // A 24 x 20 image renders in well under 0.1 s a sample: the second pass takes the rest.
  EXPECT_LT(pass_samples.size(), 10u);
  EXPECT_EQ(tiles_total, 40u * 9u);
  EXPECT_EQ(tiles_done, tiles_total);
  EXPECT_EQ(stats.samples_per_pixel, 40);

  // Without partial images to show, one pass as ever.
  uint64_t total_without_images = 0;
  RenderCallbacks tiles_only;
  tiles_only.on_tile = [&](const RenderProgress& p) {
    total_without_images = p.tiles_total;
    return true;
  };
  EXPECT_EQ(render_scene(sc.scene, camera, s, tiles_only).rgba(), one_pass);
  EXPECT_EQ(total_without_images, 9u);

  // Passes that size themselves cannot also be given a size.
  s.samples_per_pass = 4;
  try {
    render_scene(sc.scene, camera, s);
    ADD_FAILURE() << "progressive passes with samples_per_pass 4 were not refused";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("samples_per_pass"), std::string::npos) << e.what();
  }
}

TEST(Renderer, RefusesBadSettingsByName) {
  SmallScene sc;
  const auto message = [&](RenderSettings s) -> std::string {
    try {
      render_scene(sc.scene, camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0)), s);
    } catch (const ParameterError& e) {
      return e.what();
    }
    return "";
  };
  RenderSettings s = small_settings();
  s.samples_per_pixel = 0;
  EXPECT_NE(message(s).find("samples_per_pixel"), std::string::npos);
  s = small_settings();
  s.max_bounces = -1;
  EXPECT_NE(message(s).find("max_bounces"), std::string::npos);
  s = small_settings();
  s.transparent_max_bounces = -1;
  EXPECT_NE(message(s).find("transparent_max_bounces' is -1; valid range [0, inf)"),
            std::string::npos);
  s = small_settings();
  s.filter_width = 0.0f;
  EXPECT_NE(message(s).find("filter width"), std::string::npos);
  s = small_settings();
  s.region = PixelRect{4, 2, 4, 10};  // empty
  EXPECT_NE(message(s).find("'region' is (4, 2, 4, 10); valid: (x_min, y_min, x_max, y_max) with "
                            "0 <= x_min < x_max <= width 24 and 0 <= y_min < y_max <= height 20"),
            std::string::npos);
  s.region = PixelRect{0, 0, 24, 21};  // past the bottom
  EXPECT_NE(message(s).find("'region' is (0, 0, 24, 21)"), std::string::npos);
  Scene uncommitted;
  EXPECT_THROW(render_scene(uncommitted, CameraSettings(), small_settings()), ParameterError);
}

// Blender's Render Region: a film of the region's size whose pixels are the whole render's, bit
// for bit (the camera, the pixel seeds and the tiles keep the whole image's coordinates).
TEST(Renderer, ARegionRendersItsPixelsAsTheWholeImageDoes) {
  SmallScene sc;
  const CameraSettings camera = camera_at(Vec3(0, -5, 1), Vec3(0, 0, 0));
  RenderSettings s = small_settings();
  const Film whole = render_scene(sc.scene, camera, s);
  s.region = PixelRect{5, 3, 19, 17};
  RenderStats stats;
  const Film part = render_scene(sc.scene, camera, s, {}, &stats);
  ASSERT_EQ(part.width(), 14);
  ASSERT_EQ(part.height(), 14);
  EXPECT_EQ(stats.camera_samples, 14u * 14u * 8u);  // only the region's samples were traced
  float a[4], b[4];
  double sum = 0.0;
  for (int y = 0; y < part.height(); ++y)
    for (int x = 0; x < part.width(); ++x) {
      part.pixel(x, y, a);
      whole.pixel(x + 5, y + 3, b);
      for (int c = 0; c < 4; ++c) EXPECT_EQ(a[c], b[c]) << "pixel " << x << ", " << y;
      sum += a[0];
    }
  EXPECT_GT(sum, 0.0);
  s.region = PixelRect{0, 0, 24, 20};  // the whole image as a region
  EXPECT_EQ(render_scene(sc.scene, camera, s).rgba(), whole.rgba());
}

TEST(Renderer, SceneRefusesBadMeshesByArrayAndEntry) {
  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t bad_indices[3] = {0, 1, 3};
  MeshView m;
  m.positions = positions;
  m.num_vertices = 3;
  m.indices = bad_indices;
  m.num_triangles = 1;
  try {
    scene.add_mesh(m);
    FAIL() << "index 3 of 3 vertices accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("indices[0]"), std::string::npos) << e.what();
  }
  const uint32_t indices[3] = {0, 1, 2};
  m.indices = indices;
  m.material = 4;
  EXPECT_THROW(scene.add_mesh(m), ParameterError);
  m.material = 0;
  const float nan_positions[9] = {0, 0, 0, 1, std::nanf(""), 0, 0, 1, 0};
  m.positions = nan_positions;
  EXPECT_THROW(scene.add_mesh(m), ParameterError);
}

TEST(PixelFilter, DistributionsMatchTheirDefinitions) {
  PCG32 rng(5);
  const int n = 200000;
  const PixelFilter gauss(FilterType::Gaussian, 1.5f), box(FilterType::Box, 1.0f),
      centre(FilterType::PixelCenter, 1.0f);
  double gx2 = 0, gmax = 0, bx2 = 0, bmax = 0;
  for (int i = 0; i < n; ++i) {
    const Point2 u(rng.uniform(), rng.uniform());
    const Point2 g = gauss.sample(u), b = box.sample(u), c = centre.sample(u);
    gx2 += g.x * g.x;
    gmax = std::max(gmax, double(std::fabs(g.x)));
    bx2 += b.x * b.x;
    bmax = std::max(bmax, double(std::fabs(b.x)));
    ASSERT_EQ(c.x, 0.0f);
    ASSERT_EQ(c.y, 0.0f);
  }
  // Cycles' Gaussian of width w: σ = w/4, support ±1.5 w.
  EXPECT_NEAR(std::sqrt(gx2 / n), 1.5 / 4, 0.005);
  EXPECT_LE(gmax, 1.5 * 1.5);
  // Box of width 1: uniform on [-1/2, 1/2], variance 1/12.
  EXPECT_NEAR(bx2 / n, 1.0 / 12, 0.001);
  EXPECT_LE(bmax, 0.5);
  EXPECT_THROW(PixelFilter(FilterType::Box, -1.0f), ParameterError);
  EXPECT_THROW(parse_filter("mitchell"), ParameterError);
}

// Cycles' default filter (scene/film.cpp): the four-term Blackman-Harris window, with the width
// doubled, so width 1.5 spans ±1.5 px. The sampled offsets' CDF at bin edges against the
// window's integral, written out here independently of filter.cpp. Like Cycles' own 1024-entry
// table, ours interpolates the inverse CDF linearly, which moves probability by less than one
// table step (1/1023) within a step; hence that slack beside 5 standard deviations.
TEST(PixelFilter, BlackmanHarrisMatchesCyclesWindow) {
  EXPECT_EQ(parse_filter("blackman_harris"), FilterType::BlackmanHarris);
  const float width = 1.5f;
  const PixelFilter bh(FilterType::BlackmanHarris, width);
  const int bins = 30, n = 400000;
  std::vector<double> count(bins, 0.0);
  PCG32 rng(11);
  for (int i = 0; i < n; ++i) {
    const Point2 s = bh.sample(Point2(rng.uniform(), rng.uniform()));
    ASSERT_LE(std::fabs(s.x), width);
    ASSERT_LE(std::fabs(s.y), width);
    count[size_t(std::min(bins - 1, int((s.x + width) / (2 * width) * bins)))] += 1.0;
  }
  auto window = [&](double x) {
    const double v = 2 * M_PI * (x / (2.0 * width) + 0.5);
    return 0.35875 - 0.48829 * std::cos(v) + 0.14128 * std::cos(2 * v) - 0.01168 * std::cos(3 * v);
  };
  std::vector<double> expected(bins, 0.0);
  double total = 0;
  for (int b = 0; b < bins; ++b) {
    for (int k = 0; k < 200; ++k)
      expected[size_t(b)] += window(-width + (b + (k + 0.5) / 200) * (2.0 * width / bins));
    total += expected[size_t(b)];
  }
  double cdf = 0, empirical = 0, centre_mass = 0;
  for (int b = 0; b < bins; ++b) {
    cdf += expected[size_t(b)] / total;
    empirical += count[size_t(b)] / n;
    if (b >= bins / 3 && b < 2 * bins / 3) centre_mass += count[size_t(b)] / n;
    EXPECT_NEAR(empirical, cdf, 5 * std::sqrt(cdf * (1 - cdf) / n) + 1.0 / 1023) << "edge " << b;
  }
  // The window's middle third (±0.5 px) holds 76.3% of it; a Gaussian of σ = w/4 would hold 82%.
  EXPECT_NEAR(centre_mass, 0.763, 0.005);
}

// An emissive enclosure of radiance 1 around a grey Lambertian sphere: the sphere reflects
// ρ·1 from every point (area-light sampling and BSDF hits on the emitter, weighted by MIS),
// and the enclosure itself is seen at its radiance.
// Russian roulette where Cycles plays it (Min Light Bounces 0 is russian_roulette_depth 1): no
// path ends at random before it has scattered depth + 1 times; the roll is made at the hit the
// next ray finds (so that ray is always traced and what it brings back counts), not at a vertex
// that only adds emission, and the path goes on with probability √(max throughput). Counted in
// rays, inside a closed box of albedo 1/4 (every ray hits; a cosine sample's throughput is
// exactly the albedo, so the probabilities are known): each path's camera ray, one ray per
// scattering, and none after the path ends. With a white world (never seen from inside the box,
// and not light-sampled) a ray could bring light back by itself, so every ray is traced; with a
// black one nothing a ray finds counts before its vertex scatters, so the ray a roll would end
// and the ray towards a vertex that only adds emission are not traced, and the image is the same.
TEST(Renderer, RussianRouletteStartsWhereCyclesDoesAndRollsAtTheHit) {
  const auto rays_per_path = [](bool white_world, int max_bounces, int depth) {
    Scene scene;
    add_closed_lambertian_box(scene, RGBValue{0.25, 0.25, 0.25}, white_world);
    scene.commit();
    EXPECT_EQ(scene.rays_find_light(), white_world);
    RenderSettings s;
    s.width = s.height = 24;
    s.samples_per_pixel = 16;
    s.max_bounces = max_bounces;
    s.russian_roulette_depth = depth;
    RenderStats stats;
    const Film film = render_scene(scene, camera_at(Vec3(0, -1, 0), Vec3(0, 1, 0)), s, {}, &stats);
    EXPECT_EQ(stats.shadow_rays, 0u);  // no lights
    float px[4];
    film.pixel(12, 12, px);
    EXPECT_EQ(px[0], 0.0f);  // nothing inside the box emits, and the world is never seen
    return std::pair<uint64_t, uint64_t>(stats.rays, stats.camera_samples);
  };
  for (const bool white_world : {true, false}) {
    SCOPED_TRACE(white_world ? "white world" : "black world");
    // Traced per path besides its camera ray and one ray per scattering: the ray towards the
    // vertex that only adds emission, only where a ray can find light.
    const uint64_t emission_ray = white_world ? 1 : 0;
    // max_bounces 1: two scatterings, then the vertex that only adds emission, where depth 1
    // does not roll.
    {
      const auto [rays, paths] = rays_per_path(white_world, 1, 1);
      EXPECT_EQ(rays, (2 + emission_ray) * paths);
    }
    // max_bounces 2, depth 1: the third ray is rolled for with p = √(1/16) = 1/4 (at its hit
    // where it is traced), and a survivor scatters a third time: 2 + (white world: 1) + p rays
    // on average.
    {
      const auto [rays, paths] = rays_per_path(white_world, 2, 1);
      const uint64_t sure = (white_world ? 3 : 2) * paths;
      ASSERT_GE(rays, sure);
      const double survivors = double(rays - sure);
      const double sigma = std::sqrt(double(paths) * 0.25 * 0.75);
      EXPECT_NEAR(survivors, 0.25 * double(paths), 5.0 * sigma);
    }
    // max_bounces 2, depth 3: never rolled.
    {
      const auto [rays, paths] = rays_per_path(white_world, 2, 3);
      EXPECT_EQ(rays, (3 + emission_ray) * paths);
    }
  }
}

// The rays not traced where no ray can find light change no pixel. A closed box lit by a point
// light (not hittable: radius 0) is rendered with a black world, and again with a white one that
// no ray can reach but that makes every ray be traced and rolled for at its hit: the same bits,
// with fewer rays.
TEST(Renderer, RaysThatCannotFindLightAreNotTracedAndChangeNoPixel) {
  const auto render = [](bool white_world, RenderStats* stats) {
    Scene scene;
    add_closed_lambertian_box(scene, RGBValue{0.5, 0.6, 0.7}, white_world);
    scene.add_light(point_light(Vec3(0.5f, 0.5f, 1.5f), RGB(10.0f)));
    scene.commit();
    RenderSettings s;
    s.width = s.height = 16;
    s.samples_per_pixel = 16;
    s.max_bounces = 4;
    return render_scene(scene, camera_at(Vec3(0, -1, 0), Vec3(0, 1, 0)), s, {}, stats);
  };
  RenderStats black_stats, white_stats;
  const Film black = render(false, &black_stats), white = render(true, &white_stats);
  EXPECT_EQ(black_stats.shadow_rays, white_stats.shadow_rays);
  EXPECT_LT(double(black_stats.rays), 0.95 * double(white_stats.rays));
  double sum = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      float a[4], b[4];
      black.pixel(x, y, a);
      white.pixel(x, y, b);
      for (int c = 0; c < 4; ++c) ASSERT_EQ(a[c], b[c]) << "pixel " << x << ", " << y;
      sum += a[0];
    }
  EXPECT_GT(sum, 0.0);
}

TEST(AreaLight, EmissiveEnclosureLightsASphereToItsAlbedo) {
  Scene scene;
  ParamSet grey;
  grey.set("reflectance", RGBValue{0.5, 0.5, 0.5});
  scene.add_material(Material{{make("lambertian", grey)}, RGB(0.0f)});
  scene.add_material(Material{{}, RGB(1.0f)});
  const Mesh sphere = make_uv_sphere(Vec3(0, 0, 0), 1.0f, 32, 16, 0);
  const Mesh enclosure = make_uv_sphere(Vec3(0, 0, 0), 6.0f, 24, 12, 1);
  scene.add_mesh(sphere.view());
  scene.add_mesh(enclosure.view());
  scene.commit();
  ASSERT_EQ(scene.lights().size(), 1u);
  EXPECT_EQ(scene.lights()[0].type, LightType::Mesh);
  RenderSettings s;
  s.width = s.height = 24;
  s.samples_per_pixel = 64;
  s.max_bounces = 0;
  RenderStats stats;
  const Film film = render_scene(scene, camera_at(Vec3(0, -3.5f, 0), Vec3(0, 0, 0)), s, {}, &stats);
  double sphere_sum = 0;
  int sphere_pixels = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      float px[4];
      film.pixel(x, y, px);
      const bool centre = std::hypot(x + 0.5 - 12, y + 0.5 - 12) < 4.0;  // well inside the sphere
      const bool outside = std::hypot(x + 0.5 - 12, y + 0.5 - 12) > 11.0;
      if (outside) {
        EXPECT_NEAR(px[0], 1.0f, 1e-5f);
      }
      if (!centre) continue;
      EXPECT_NEAR(px[0], 0.5f, 0.1f);
      sphere_sum += px[0];
      ++sphere_pixels;
    }
  ASSERT_GT(sphere_pixels, 30);
  EXPECT_NEAR(sphere_sum / sphere_pixels, 0.5, 0.01);
}

namespace {

// A model whose every sample has an enormous weight, so that the path throughput overflows.
class Overflowing final : public BxDFImpl<Overflowing> {
 public:
  Overflowing() : BxDFImpl(kReflection | kDiffuse) {}
  RGB eval(const Vec3&, const Vec3&) const { return RGB(3e38f); }
  BxDFSample sample(const Vec3& wo, Point2) const {
    BxDFSample s;
    s.wi = Vec3(0.3f, 0.1f, wo.z > 0 ? 0.9f : -0.9f);
    s.pdf = 1e-30f;
    s.f = RGB(3e38f);
    s.flags = kReflection | kDiffuse;
    return s;
  }
  float density(const Vec3&, const Vec3&) const { return 1e-30f; }
};

}  // namespace

TEST(Renderer, OverflowingSamplesAreRejectedAndCounted) {
  Scene scene;
  scene.add_material(Material{{std::make_shared<Overflowing>()}, RGB(0.0f)});
  const Mesh sphere = make_uv_sphere(Vec3(0, 0, 0), 1.0f, 16, 8, 0);
  scene.add_mesh(sphere.view());
  scene.set_world(RGB(1.0f));
  scene.commit();
  RenderSettings s;
  s.width = s.height = 8;
  s.samples_per_pixel = 2;
  s.max_bounces = 2;
  RenderStats stats;
  const Film film = render_scene(scene, camera_at(Vec3(0, -4, 0), Vec3(0, 0, 0)), s, {}, &stats);
  EXPECT_GT(stats.rejected_samples, 0u);
  for (float v : film.rgba()) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
}

// The world: Cycles' equirectangular mapping, the importance-sampling distribution against its
// own density (χ² over the sphere) and against the radiance it is built from, a rotated image,
// a diffuse sphere under a known low-frequency sky against the closed form, and the constant
// furnace, which BSDF sampling alone renders without noise.
#include <gtest/gtest.h>

#include "../scratch_folder.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "bxdf/registry.h"
#include "bxdf/sampling.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"
#include "bxdf/rng.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

// A lumpy image: a smooth gradient plus a few bright blobs, W × H.
EquirectImage blob_image(int w, int h) {
  EquirectImage img;
  img.width = w;
  img.height = h;
  img.rgb.resize(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float u = (x + 0.5f) / w, v = (y + 0.5f) / h;
      float value = 0.05f + 0.1f * v;
      const float centres[3][2] = {{0.2f, 0.7f}, {0.65f, 0.4f}, {0.9f, 0.85f}};
      for (const auto& c : centres) {
        const float du = u - c[0], dv = v - c[1];
        value += 20.0f * std::exp(-(du * du + dv * dv) / 0.002f);
      }
      for (int k = 0; k < 3; ++k) img.rgb[(size_t(y) * w + x) * 3 + k] = value * (0.8f + 0.2f * k);
    }
  return img;
}

EnvironmentSettings rotated_blobs() {
  EnvironmentSettings s;
  s.image = blob_image(64, 32);
  s.weight = RGB(1.0f);
  // A rotation by 50° about Z and 20° about X (Mapping's rotation), as a 3×4 matrix.
  const float a = radians(50.0f), b = radians(20.0f);
  const float rz[9] = {std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1};
  const float rx[9] = {1, 0, 0, 0, std::cos(b), -std::sin(b), 0, std::sin(b), std::cos(b)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      float m = 0;
      for (int k = 0; k < 3; ++k) m += rx[3 * i + k] * rz[3 * k + j];
      s.matrix[4 * i + j] = m;
    }
  return s;
}

// Wilson–Hilferty: the χ² statistic with k degrees of freedom as an approximately standard
// normal z-score.
double chi2_z(double statistic, int k) {
  const double c = 2.0 / (9.0 * k);
  return (std::cbrt(statistic / k) - (1.0 - c)) / std::sqrt(c);
}

}  // namespace

TEST(Environment, EquirectMappingIsCycles) {
  // v = 1 at +Z; u = 0.5 along +X, u increases clockwise seen from above (towards −Y).
  const Point2 up = direction_to_equirect(Vec3(0, 0, 1));
  EXPECT_NEAR(up.y, 1.0f, 1e-6f);
  const Point2 x = direction_to_equirect(Vec3(1, 0, 0));
  EXPECT_NEAR(x.x, 0.5f, 1e-6f);
  EXPECT_NEAR(x.y, 0.5f, 1e-6f);
  EXPECT_NEAR(direction_to_equirect(Vec3(0, -1, 0)).x, 0.75f, 1e-6f);
  PCG32 rng(1, 1);
  for (int i = 0; i < 100; ++i) {
    const float u = rng.uniform(), v = 0.01f + 0.98f * rng.uniform();
    const Point2 back = direction_to_equirect(equirect_to_direction(u, v));
    EXPECT_NEAR(back.x, u, 1e-4f);
    EXPECT_NEAR(back.y, v, 1e-4f);
  }
}

TEST(Environment, SampledDirectionsFollowThePdfChi2OverTheSphere) {
  const Environment env(rotated_blobs());
  ASSERT_TRUE(env.importance_sampled());
  EXPECT_EQ(env.map_width(), 64);  // Auto: the image's own size
  EXPECT_EQ(env.map_height(), 32);
  // Bins on an area-preserving (φ, cos θ) grid that does not line up with the map's cells;
  // expected counts integrate the pdf over each bin by a 32 × 32 midpoint rule (fine enough
  // for a bin crossed by the edge of a cell of a sharply varying map).
  const int nphi = 48, ncos = 40, sub = 32;
  const int64_t n = 400000;
  std::vector<double> observed(nphi * ncos, 0.0), expected(nphi * ncos, 0.0);
  PCG32 rng(5, 9);
  int64_t disagree = 0;
  for (int64_t i = 0; i < n; ++i) {
    float pdf;
    const Vec3 d = env.sample(Point2(rng.uniform(), rng.uniform()), &pdf);
    ASSERT_GT(pdf, 0.0f);
    // The density the sample reports and the one its direction looks up agree, except where
    // float rounding puts the direction into the neighbouring map cell (as in Cycles).
    if (std::fabs(pdf - env.pdf(d)) > 0.02f * pdf) ++disagree;
    const float phi = std::atan2(d.y, d.x) + kPi;
    const int ip = std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi));
    const int ic = std::min(ncos - 1, static_cast<int>((d.z + 1.0f) * 0.5f * ncos));
    observed[ic * nphi + ip] += 1;
  }
  double integral = 0;
  for (int ic = 0; ic < ncos; ++ic)
    for (int ip = 0; ip < nphi; ++ip) {
      double sum = 0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double z = -1.0 + 2.0 * (ic + (a + 0.5) / sub) / ncos;
          const double phi = 2 * M_PI * (ip + (b + 0.5) / sub) / nphi - M_PI;
          const double s = std::sqrt(std::max(0.0, 1 - z * z));
          sum += env.pdf(Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)));
        }
      const double cell = sum / (sub * sub) * (4 * M_PI / (nphi * ncos));
      expected[ic * nphi + ip] = cell * n;
      integral += cell;
    }
  EXPECT_LT(disagree, n / 1000);
  EXPECT_NEAR(integral, 1.0, 2e-3);
  // Pool low-expectation bins, then the statistic.
  double stat = 0, pooled_o = 0, pooled_e = 0;
  int dof = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    pooled_o += observed[i];
    pooled_e += expected[i];
    if (pooled_e < 20) continue;
    stat += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++dof;
    pooled_o = pooled_e = 0;
  }
  EXPECT_LT(chi2_z(stat, dof - 1), 4.0) << "chi2 " << stat << " dof " << dof;
}

namespace {

// The world's mean radiance (solid-angle weighted) and ∫ (average(L) − mean)⁺ dω, by uniform
// directions.
void radiance_mean_and_excess(const Environment& env, float* mean, float* excess) {
  PCG32 rng(3, 4);
  const int n = 400000;
  std::vector<float> values(n);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    values[size_t(i)] = env.eval(sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()))).average();
    sum += values[size_t(i)];
  }
  *mean = float(sum / n);
  double above = 0.0;
  for (float v : values) above += std::max(v - *mean, 0.0f);
  *excess = float(above / n * 4.0 * M_PI);
}

}  // namespace

TEST(Environment, PdfNeverFallsFarBelowTheRadianceAboveTheMean) {
  // The map samples what lies above the world's mean (MIS compensation). MIS weights stay
  // bounded only if the density follows that excess: nowhere well above the mean may
  // (L − mean)/∫(L − mean)⁺ exceed the pdf by more than a small factor, however the image is
  // rotated against the map. (Cells take the largest L of nine points, so a texel peak is seen
  // at ≥ 0.56 of its value.)
  EnvironmentSettings s = rotated_blobs();
  s.weight = RGB(2.0f);
  s.constant = RGB(0.01f);
  const Environment env(s);
  float mean = 0.0f, excess = 0.0f;
  radiance_mean_and_excess(env, &mean, &excess);
  PCG32 rng(8, 8);
  float worst = 0.0f;
  int above = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 d = equirect_to_direction(rng.uniform(), 0.02f + 0.96f * rng.uniform());
    const float l = env.eval(d).average();
    if (!(l > 2.0f * mean)) continue;
    ++above;
    worst = std::max(worst, (l - mean) / (env.pdf(d) * excess));
  }
  ASSERT_GT(above, 1000);
  EXPECT_LT(worst, 4.0f);
  EXPECT_GT(worst, 0.5f);
}

TEST(Environment, MapLeavesWhatLiesBelowTheMeanToBsdfSampling) {
  // Below the mean the density is zero: BSDF sampling alone finds those directions (their MIS
  // weight is 1), which for a smooth sky is far less noisy than sharing them.
  EnvironmentSettings s = rotated_blobs();
  const Environment env(s);
  float mean = 0.0f, excess = 0.0f;
  radiance_mean_and_excess(env, &mean, &excess);
  PCG32 rng(2, 6);
  int below = 0, sampled_below = 0;
  for (int i = 0; i < 100000; ++i) {
    const Vec3 d = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    if (!(env.eval(d).average() < 0.5f * mean)) continue;
    ++below;
    sampled_below += env.pdf(d) > 0.0f;
  }
  EXPECT_GT(below, 10000);
  // Only the cells at a blob's rim, whose largest point is above the mean, keep a density.
  EXPECT_LT(sampled_below, below / 20) << sampled_below << " of " << below;
  // Samples never land there, nor anywhere of density zero (the CDFs end exactly at 1).
  for (int i = 0; i < 100000; ++i) {
    float pdf = 0.0f;
    env.sample(Point2(rng.uniform(), rng.uniform()), &pdf);
    ASSERT_GT(pdf, 0.0f);
  }
  for (const Point2 u : {Point2(0.0f, 0.0f), Point2(0x1.fffffep-1f, 0x1.fffffep-1f),
                         Point2(0.0f, 0x1.fffffep-1f), Point2(0x1.fffffep-1f, 0.0f)}) {
    float pdf = 0.0f;
    env.sample(u, &pdf);
    EXPECT_GT(pdf, 0.0f) << u.x << " " << u.y;
  }
  // A smooth sky of 0.6 + 0.4 z: its upper part, above the mean, keeps a density; the lower
  // half has none.
  EnvironmentSettings sky;
  sky.image.width = 64;
  sky.image.height = 32;
  sky.image.rgb.resize(size_t(64) * 32 * 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int k = 0; k < 3; ++k)
        sky.image.rgb[(size_t(y) * 64 + x) * 3 + k] = 0.6f + 0.4f * equirect_to_direction(0.0f, (y + 0.5f) / 32).z;
  sky.weight = RGB(1.0f);
  const Environment gradient(sky);
  ASSERT_TRUE(gradient.importance_sampled());
  EXPECT_GT(gradient.pdf(normalize(Vec3(1, 0, 5))), 0.0f);
  EXPECT_GT(gradient.pdf(normalize(Vec3(0, 1, 0.5f))), 0.0f);
  EXPECT_EQ(gradient.pdf(normalize(Vec3(1, 0, -5))), 0.0f);
  EXPECT_EQ(gradient.pdf(normalize(Vec3(1, 0, -0.2f))), 0.0f);
}

TEST(Environment, MapResolutionFollowsCyclesRules) {
  EnvironmentSettings s;
  s.image = blob_image(64, 32);
  s.weight = RGB(1.0f);
  s.map_resolution = 128;  // Manual: R × R/2
  const Environment manual(s);
  EXPECT_EQ(manual.map_width(), 128);
  EXPECT_EQ(manual.map_height(), 64);
  s.importance_sample = false;  // Blender's sampling method None
  EXPECT_FALSE(Environment(s).importance_sampled());
  EnvironmentSettings constant;
  constant.constant = RGB(1.0f);
  EXPECT_FALSE(Environment(constant).importance_sampled());  // Cycles: no MIS for a constant world
  s.map_resolution = 3;
  EXPECT_THROW(Environment{s}, ParameterError);
}

// The map is built in parallel: at one thread and at two it is the same bits (same samples,
// same densities, same power).
TEST(Environment, MapIsTheSameAtAnyThreadCount) {
  EnvironmentSettings s = rotated_blobs();
  s.map_resolution = 0;  // Automatic: the image's 64 × 32
  const auto build = [&](int threads) {
    tbb::task_arena arena(threads);
    std::unique_ptr<Environment> env;
    arena.execute([&] { env = std::make_unique<Environment>(s); });
    return env;
  };
  const auto one = build(1), two = build(2);
  ASSERT_TRUE(one->importance_sampled());
  EXPECT_EQ(one->power(1.0f), two->power(1.0f));
  PCG32 rng(17);
  for (int i = 0; i < 2000; ++i) {
    const Point2 u(rng.uniform(), rng.uniform());
    float pdf_one = 0.0f, pdf_two = 0.0f;
    const Vec3 a = one->sample(u, &pdf_one), b = two->sample(u, &pdf_two);
    ASSERT_TRUE(a == b && pdf_one == pdf_two) << i;
    ASSERT_EQ(one->pdf(a), two->pdf(a)) << i;
  }
}

namespace {

// A width x height RGB PFM (little-endian) of one value, written over `path`.
void write_uniform_pfm(const std::string& path, int width, int height, float value) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << "PF\n" << width << " " << height << "\n-1.0\n";
  for (int i = 0; i < 3 * width * height; ++i)
    f.write(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

// load_equirect_image keeps the images it read: an unchanged file comes back equal (from the
// cache), a rewritten one (same name, same size, other pixels) is read again, and a file that
// is gone is an error, not a cached image.
TEST(Environment, ReloadedImageIsTheFilesCurrentContents) {
  const std::string path = bxdf::test_support::process_temp_path("equirect_cache.pfm");
  const auto write = [&](float value) { write_uniform_pfm(path, 2, 1, value); };
  write(0.25f);
  const EquirectImage first = load_equirect_image(path);
  ASSERT_EQ(first.width, 2);
  EXPECT_EQ(first.rgb[0], 0.25f);
  EXPECT_EQ(load_equirect_image(path).rgb, first.rgb);
  // File times tick at the kernel's clock granularity (a few ms): wait past it.
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  write(0.75f);
  EXPECT_EQ(load_equirect_image(path).rgb[5], 0.75f);
  std::filesystem::remove(path);
  EXPECT_THROW(load_equirect_image(path), std::runtime_error);
}

// shared_environment builds a world once: the same file and settings give the same Environment,
// other settings or a rewritten file another one, with the file's current pixels; a file that
// is gone is an error.
TEST(Environment, SharedWorldIsBuiltOncePerFileAndSettings) {
  const std::string path = bxdf::test_support::process_temp_path("shared_world.pfm");
  const auto write = [&](float value) { write_uniform_pfm(path, 4, 2, value); };
  write(0.25f);
  EnvironmentSettings settings;
  settings.weight = RGB(1.0f);
  const auto first = shared_environment(path, settings);
  EXPECT_NEAR(first->eval(Vec3(0, 0, 1)).r, 0.25f, 1e-6f);
  EXPECT_EQ(shared_environment(path, settings), first);  // the same object
  EnvironmentSettings brighter = settings;
  brighter.weight = RGB(2.0f);
  const auto other = shared_environment(path, brighter);
  EXPECT_NE(other, first);
  EXPECT_NEAR(other->eval(Vec3(0, 0, 1)).r, 0.5f, 1e-6f);
  EnvironmentSettings unsampled = settings;
  unsampled.importance_sample = false;
  EXPECT_NE(shared_environment(path, unsampled), first);
  // File times tick at the kernel's clock granularity (a few ms): wait past it.
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  write(0.75f);
  const auto rewritten = shared_environment(path, settings);
  EXPECT_NE(rewritten, first);
  EXPECT_NEAR(rewritten->eval(Vec3(0, 0, 1)).r, 0.75f, 1e-6f);
  EXPECT_NEAR(first->eval(Vec3(0, 0, 1)).r, 0.25f, 1e-6f);  // a scene holding it keeps it
  // A scene takes the shared world as it is.
  Scene scene;
  scene.set_world(rewritten);
  EXPECT_EQ(&scene.world(), rewritten.get());
  std::filesystem::remove(path);
  EXPECT_THROW(shared_environment(path, settings), std::runtime_error);
}

TEST(Environment, RotatedImageIsTheImageSeenAlongTheRotatedDirection) {
  const EnvironmentSettings rotated = rotated_blobs();
  EnvironmentSettings plain = rotated;
  const float m[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::copy(m, m + 12, plain.matrix);
  const Environment a(rotated), b(plain);
  PCG32 rng(2, 3);
  for (int i = 0; i < 200; ++i) {
    Vec3 d(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    if (!normalize_direction(d)) continue;
    const float* r = rotated.matrix;
    const Vec3 rd(r[0] * d.x + r[1] * d.y + r[2] * d.z, r[4] * d.x + r[5] * d.y + r[6] * d.z,
                  r[8] * d.x + r[9] * d.y + r[10] * d.z);
    EXPECT_NEAR(a.eval(d).r, b.eval(rd).r, 1e-4f * (1 + b.eval(rd).r));
  }
  // The brightest sampled direction of the rotated world lies where its radiance peaks.
  float pdf;
  PCG32 s(4, 4);
  double best = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = a.sample(Point2(s.uniform(), s.uniform()), &pdf);
    best = std::max(best, double(a.eval(d).r));
  }
  EXPECT_GT(best, 10.0);
}

namespace {

struct SphereUnderSky {
  Scene scene;
  CameraSettings camera;
  RenderSettings settings;
  explicit SphereUnderSky(EnvironmentSettings world, float reflectance) {
    ParamSet p;
    p.set("reflectance", RGBValue{reflectance, reflectance, reflectance});
    scene.add_material(Material{{make("lambertian", p)}, RGB(0.0f)});
    scene.add_mesh(make_uv_sphere(Vec3(0, 0, 0), 1.0f, 128, 64, 0).view());
    scene.set_world(std::move(world));
    scene.commit();
    camera.camera_to_world = look_at(Vec3(0, -5, 0), Vec3(0, 0, 0), Vec3(0, 0, 1));
    settings.width = settings.height = 24;
    settings.max_bounces = 0;
    settings.filter = FilterType::PixelCenter;
    settings.threads = 2;
  }
};

// The unit-sphere normal seen through pixel (x, y) of the camera above, or false.
bool sphere_normal(const CameraSettings& cam, int w, int h, int x, int y, Vec3* n) {
  const Camera c(cam, w, h);
  const Ray r = c.generate_ray(x + 0.5f, y + 0.5f);
  const float b = dot(r.origin, r.dir), cc = dot(r.origin, r.origin) - 1.0f;
  const float disc = b * b - cc;
  if (disc < 0.05f) return false;  // keep away from the silhouette
  const float t = -b - std::sqrt(disc);
  *n = r.origin + r.dir * t;
  return normalize_direction(*n);
}

}  // namespace

TEST(Environment, DiffuseSphereUnderLinearSkyMatchesClosedForm) {
  // L(ω) = a + b ω_z: irradiance at normal n is π a + (2π/3) b n_z, so a Lambertian sphere
  // of reflectance ρ shows ρ (a + (2/3) b n_z).
  const int w = 256, h = 128;
  const float a = 1.0f, b = 0.8f;
  EnvironmentSettings sky;
  sky.image.width = w;
  sky.image.height = h;
  sky.image.rgb.resize(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k)
        sky.image.rgb[(size_t(y) * w + x) * 3 + k] = a + b * equirect_to_direction(0.0f, (y + 0.5f) / h).z;
  sky.weight = RGB(1.0f);
  SphereUnderSky s(sky, 0.8f);
  s.settings.samples_per_pixel = 1024;
  const Film film = render_scene(s.scene, s.camera, s.settings);
  double err = 0, signed_err = 0;
  int count = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      Vec3 n;
      if (!sphere_normal(s.camera, 24, 24, x, y, &n)) continue;
      float px[4];
      film.pixel(x, y, px);
      const double truth = 0.8 * (a + 2.0 / 3.0 * b * n.z);
      err += std::fabs(px[0] - truth) / truth;
      signed_err += (px[0] - truth) / truth;
      ++count;
    }
  ASSERT_GT(count, 100);
  EXPECT_LT(err / count, 0.015);                      // noise: ~1% per pixel at 1024 spp
  EXPECT_LT(std::fabs(signed_err / count), 0.002);    // bias
}

TEST(Environment, ConstantFurnaceIsNoiseFreeAsCycles) {
  // Cycles does not light-sample a constant world: cosine-sampled BSDF rays find it with
  // weight ρ, so a white sphere is 1 in every pixel at any sample count but where a sample is
  // lost below a triangle's plane (0 in Cycles). Here the lobe is sampled above that plane
  // (cosine_above_plane.h): a sample weighs ρ or ρ·cos δ, δ the angle between the shading
  // and the triangle's normal (under 2.5° on this sphere), and is never lost.
  EnvironmentSettings world;
  world.constant = RGB(1.0f);
  SphereUnderSky s(world, 1.0f);
  s.settings.samples_per_pixel = 2;
  const Film film = render_scene(s.scene, s.camera, s.settings);
  double worst = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      float px[4];
      film.pixel(x, y, px);
      worst = std::max(worst, std::fabs(px[0] - 1.0));
    }
  EXPECT_LT(worst, 1e-3);
}

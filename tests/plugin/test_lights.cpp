// Cycles' lights: each kind's light samples integrate to the analytic irradiance (computed here
// independently, by closed forms or double-precision quadrature), the density a BSDF ray finds
// on a light equals the density of sampling that direction, area lights emit from the front
// only, and the light sampler picks by power. Renders check the integrator's MIS, camera
// visibility, cast_shadow and the terminator offset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"
#include "bxdf/rng.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

// Irradiance at p on a surface with normal n: the mean of L·cos/pdf over light samples.
double estimate_irradiance(const Light& light, const Vec3& p, const Vec3& n, int samples) {
  PCG32 rng(7, 11);
  double sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    const LightSample s = sample_light(light, p, Point2(rng.uniform(), rng.uniform()));
    if (!(s.pdf > 0.0f)) continue;
    const double c = std::max(0.0f, dot(s.wi, n));
    sum += s.radiance.average() * c / s.pdf;
  }
  return sum / samples;
}

// ∫ L cosθ cosθ' / d² dA over a planar light by the midpoint rule in double precision: the
// light lies in the plane z = h above p = origin, normal facing down, shading normal +z.
template <typename Inside>
double quadrature_irradiance(double radiance, double h, double sx, double sy, Inside inside) {
  const int n = 800;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = ((i + 0.5) / n - 0.5) * sx, y = ((j + 0.5) / n - 0.5) * sy;
      if (!inside(x / (0.5 * sx), y / (0.5 * sy))) continue;
      const double d2 = x * x + y * y + h * h;
      sum += h * h / (d2 * d2);
    }
  return radiance * sum * (sx / n) * (sy / n);
}

// A sampled direction towards a hittable light must be found again by a ray, with the same pdf.
void expect_hit_pdf_matches_sample_pdf(const Light& light, const Vec3& p) {
  PCG32 rng(3, 5);
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const LightSample s = sample_light(light, p, Point2(rng.uniform(), rng.uniform()));
    if (!(s.pdf > 0.0f)) continue;
    LightHit h;
    ASSERT_TRUE(intersect_light(light, p, s.wi, 1e30f, &h)) << i;
    EXPECT_NEAR(h.t, s.distance, 1e-3f * s.distance);
    EXPECT_NEAR(h.pdf, s.pdf, 2e-3f * s.pdf) << i;
    EXPECT_NEAR(h.radiance.average(), s.radiance.average(), 1e-4f * s.radiance.average());
    ++checked;
  }
  EXPECT_GT(checked, 150);
}

}  // namespace

TEST(Lights, SphereLightIsCyclesFacingDiskOfIntensityOverPiRSquared) {
  // Cycles: a disk of radius r facing the point, radiance I/(π r²). Straight below it at
  // distance d, the irradiance is π L sin²α with tan α = r/d: I/(d² + r²).
  const float d = 2.0f, r = 0.5f;
  const Light l = point_light_from_power(Vec3(0, 0, d), 1000.0f, RGB(1.0f), r);
  const double I = 1000.0 / (4.0 * M_PI);
  EXPECT_NEAR(estimate_irradiance(l, Vec3(0, 0, 0), Vec3(0, 0, 1), 20000), I / (d * d + r * r),
              2e-3 * I / (d * d));
  EXPECT_FALSE(l.is_delta());
  expect_hit_pdf_matches_sample_pdf(l, Vec3(0.3f, -0.2f, 0.0f));
  // Radius 0 is the delta point light: I/d².
  const Light p = point_light_from_power(Vec3(0, 0, d), 1000.0f, RGB(1.0f));
  EXPECT_TRUE(p.is_delta());
  EXPECT_NEAR(estimate_irradiance(p, Vec3(0, 0, 0), Vec3(0, 0, 1), 4), I / (d * d), 1e-4 * I);
  EXPECT_THROW(point_light(Vec3(0, 0, 0), RGB(1.0f), -0.1f), ParameterError);
}

TEST(Lights, SpotLightWithRadiusKeepsItsConeMask) {
  const Light s = spot_light(Vec3(0, 0, 2), Vec3(0, 0, -1), RGB(10.0f), 0.6f, 0.2f, 0.1f);
  // Inside the cone's core the mask is the cosine to the axis, ~1 straight below.
  const double e = estimate_irradiance(s, Vec3(0, 0, 0), Vec3(0, 0, 1), 20000);
  EXPECT_NEAR(e, 10.0 / (4.0 + 0.01), 0.01);
  // Far outside the cone nothing arrives.
  EXPECT_EQ(estimate_irradiance(s, Vec3(3, 0, 0), Vec3(0, 0, 1), 1000), 0.0);
  expect_hit_pdf_matches_sample_pdf(s, Vec3(0.05f, 0.0f, 0.0f));
}

TEST(Lights, SunAngleIsCyclesDiskAtUnitDistance) {
  // Every sample carries E (radiance = E·pdf), so a surface facing the sun receives
  // E·mean(cos θ) over the disk of radius R = tan(angle/2): E·2(√(1+R²) − 1)/R².
  const float angle = 0.5f;
  const Light sun = sun_light(Vec3(0, 0, -1), RGB(3.0f), angle);
  const double R = std::tan(0.5 * angle);
  const double expected = 3.0 * 2.0 * (std::sqrt(1.0 + R * R) - 1.0) / (R * R);
  EXPECT_NEAR(estimate_irradiance(sun, Vec3(0, 0, 0), Vec3(0, 0, 1), 20000), expected, 2e-3);
  // An escaped ray inside the cone sees the same radiance and pdf as the sample.
  PCG32 rng(1, 2);
  for (int i = 0; i < 50; ++i) {
    const LightSample s = sample_light(sun, Vec3(0, 0, 0), Point2(rng.uniform(), rng.uniform()));
    RGB le;
    float pdf = 0.0f;
    ASSERT_TRUE(sun_radiance(sun, s.wi, &le, &pdf));
    EXPECT_NEAR(pdf, s.pdf, 1e-3f * s.pdf);
    EXPECT_NEAR(le.r, s.radiance.r, 1e-3f * s.radiance.r);
  }
  RGB le;
  float pdf;
  EXPECT_FALSE(sun_radiance(sun, Vec3(0, 1, 0), &le, &pdf));
}

TEST(Lights, AreaLightShapesMatchQuadratureAndAreOneSided) {
  const float h = 1.5f;
  struct Case {
    AreaShape shape;
    float sx, sy;
  };
  for (const Case& c : {Case{AreaShape::Rectangle, 2.0f, 2.0f}, Case{AreaShape::Rectangle, 3.0f, 1.0f},
                        Case{AreaShape::Ellipse, 2.0f, 2.0f}, Case{AreaShape::Ellipse, 3.0f, 1.0f}}) {
    const bool round = c.shape == AreaShape::Ellipse;
    const Light l = area_light_from_power(Vec3(0, 0, h), Vec3(c.sx, 0, 0), Vec3(0, c.sy, 0),
                                          Vec3(0, 0, -1), c.shape, 100.0f, RGB(1.0f));
    // Cycles' radiance: P/(4·area).
    const double area = c.sx * c.sy * (round ? M_PI / 4 : 1.0);
    EXPECT_NEAR(l.radiance.r, 100.0 / (4.0 * area), 1e-4);
    const double truth = quadrature_irradiance(l.radiance.r, h, c.sx, c.sy, [&](double x, double y) {
      return round ? x * x + y * y <= 1.0 : true;
    });
    EXPECT_NEAR(estimate_irradiance(l, Vec3(0, 0, 0), Vec3(0, 0, 1), 40000), truth, 4e-3 * truth)
        << (round ? "ellipse " : "rectangle ") << c.sx << "x" << c.sy;
    expect_hit_pdf_matches_sample_pdf(l, Vec3(0.7f, -0.4f, 0.0f));
    // Behind the light: no samples, and rays from behind pass through.
    EXPECT_EQ(estimate_irradiance(l, Vec3(0, 0, 3), Vec3(0, 0, -1), 100), 0.0);
    LightHit hit;
    EXPECT_FALSE(intersect_light(l, Vec3(0, 0, 3), Vec3(0, 0, -1), 1e30f, &hit));
    EXPECT_TRUE(intersect_light(l, Vec3(0, 0, 0), Vec3(0, 0, 1), 1e30f, &hit));
  }
}

TEST(Lights, MeshLightSamplesMatchQuadratureAndTheDensityARayFinds) {
  // An emissive quad of 2 × 1.2 m (two triangles), 0.9 m above the origin.
  const float h = 0.9f, sx = 2.0f, sy = 1.2f;
  Scene scene;
  scene.add_material(Material{{}, RGB(3.0f)});
  const Mesh quad = make_quad(Vec3(-0.5f * sx, -0.5f * sy, h), Vec3(sx, 0, 0), Vec3(0, sy, 0), 0);
  scene.add_mesh(quad.view());
  scene.commit();
  ASSERT_EQ(scene.lights().size(), 1u);
  const Light& light = scene.lights()[0];
  ASSERT_EQ(light.type, LightType::Mesh);
  ASSERT_EQ(light.triangles.size(), 2u);
  const double truth = quadrature_irradiance(3.0, h, sx, sy, [](double, double) { return true; });
  EXPECT_NEAR(estimate_irradiance(light, Vec3(0, 0, 0), Vec3(0, 0, 1), 40000), truth, 4e-3 * truth);
  // Each sample's pdf is the density a BSDF ray that finds the same point weighs it with.
  const Vec3 p(0.7f, -0.4f, 0.0f);
  PCG32 rng(3, 5);
  for (int i = 0; i < 500; ++i) {
    const LightSample s = sample_light(light, p, Point2(rng.uniform(), rng.uniform()));
    ASSERT_GT(s.pdf, 0.0f) << i;
    ASSERT_GE(s.triangle, 0);
    const Vec3 q = p + s.wi * s.distance;
    EXPECT_NEAR(q.z, h, 1e-5f) << i;
    const float found = mesh_light_pdf(light, p, q, light.triangles[size_t(s.triangle)].normal);
    EXPECT_NEAR(found, s.pdf, 1e-4f * s.pdf) << i;
  }
}

TEST(Lights, SamplerPicksByPower) {
  std::vector<Light> lights = {point_light_from_power(Vec3(0, 0, 1), 1000.0f, RGB(1.0f)),
                               point_light_from_power(Vec3(0, 0, 1), 10.0f, RGB(1.0f)),
                               point_light_from_power(Vec3(0, 0, 1), 0.0f, RGB(1.0f))};
  const LightSampler sampler(lights, nullptr, 1.0f);
  EXPECT_NEAR(sampler.probability(0), 1000.0f / 1010.0f, 1e-6f);
  EXPECT_NEAR(sampler.probability(1), 10.0f / 1010.0f, 1e-6f);
  EXPECT_EQ(sampler.probability(2), 0.0f);
  int counts[3] = {0, 0, 0};
  float p;
  for (int i = 0; i < 101000; ++i) ++counts[sampler.sample((i + 0.5f) / 101000.0f, &p)];
  EXPECT_NEAR(counts[1], 1000, 2);
  EXPECT_EQ(counts[2], 0);
}

TEST(Lights, SamplerRemapsTheNumberWithinThePickedLight) {
  // The number that picks a light is, rescaled to the light's interval, uniform again: the
  // stratified numbers landing on a light stay stratified over [0, 1).
  std::vector<Light> lights = {point_light_from_power(Vec3(0, 0, 1), 30.0f, RGB(1.0f)),
                               point_light_from_power(Vec3(0, 0, 1), 0.0f, RGB(1.0f)),
                               point_light_from_power(Vec3(0, 0, 1), 70.0f, RGB(1.0f))};
  const LightSampler sampler(lights, nullptr, 1.0f);
  const int n = 100000;
  std::vector<float> remapped[3];
  for (int i = 0; i < n; ++i) {
    const float u = (i + 0.5f) / n;
    float p = 0.0f, r = -1.0f;
    const size_t k = sampler.sample(u, &p, &r);
    ASSERT_GE(r, 0.0f) << u;
    ASSERT_LT(r, 1.0f) << u;
    EXPECT_EQ(p, sampler.probability(k));
    remapped[k].push_back(r);
  }
  EXPECT_TRUE(remapped[1].empty());
  for (size_t k : {size_t(0), size_t(2)}) {
    const std::vector<float>& r = remapped[k];
    ASSERT_FALSE(r.empty());
    // In order, evenly spread from 0 to 1 (the picked numbers are evenly spaced).
    EXPECT_TRUE(std::is_sorted(r.begin(), r.end())) << k;
    EXPECT_LT(r.front(), 2.0f / float(r.size())) << k;
    EXPECT_GT(r.back(), 1.0f - 2.0f / float(r.size())) << k;
    for (size_t j = 1; j < r.size(); ++j)
      ASSERT_NEAR(r[j] - r[j - 1], 1.0f / float(r.size()), 1e-3f) << k << " " << j;
  }
  // u = 1 - ulp lands in the last light, still below 1 once remapped.
  float p = 0.0f, r = 0.0f;
  EXPECT_EQ(sampler.sample(0x1.fffffep-1f, &p, &r), 2u);
  EXPECT_LT(r, 1.0f);
}

namespace {

// Four local lights around the origin: two area lights facing down, one facing up, a point.
std::vector<Light> spread_lights() {
  return {area_light_from_power(Vec3(-2, 0, 1), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0),
                                Vec3(0, 0, -1), AreaShape::Rectangle, 40.0f, RGB(1.0f)),
          area_light_from_power(Vec3(2, 1, 1.5f), Vec3(1, 0, 0), Vec3(0, 0.4f, 0),
                                Vec3(0.3f, 0, -1), AreaShape::Ellipse, 40.0f, RGB(1.0f)),
          area_light_from_power(Vec3(0, 0, 0.5f), Vec3(0.3f, 0, 0), Vec3(0, 0.3f, 0),
                                Vec3(0, 0, 1), AreaShape::Ellipse, 40.0f, RGB(1.0f)),
          point_light_from_power(Vec3(0, 3, 2), 400.0f, RGB(1.0f), 0.1f)};
}

}  // namespace

TEST(Lights, SpatialSamplerPicksEachLightWithTheProbabilityItReports) {
  // At a shading point the local lights' share is split by importance; sample() must pick
  // each entry as often as probability(r, i) says (the MIS weight of a BSDF ray that finds
  // it), report that same number, and the probabilities must add up to 1.
  const std::vector<Light> lights = spread_lights();
  const LightSampler sampler(lights, nullptr, 5.0f);
  ASSERT_TRUE(sampler.spatial());
  const LightReceiver receivers[] = {{Vec3(-1.8f, 0.1f, 0), Vec3(0, 0, 1), false},
                                     {Vec3(1.5f, 0.5f, 0), Vec3(0, 0, 1), false},
                                     {Vec3(0, 2.0f, 0.3f), Vec3(0, -1, 0), true},
                                     {Vec3(0.2f, 0, 1.0f), Vec3(1, 0, 0), false}};
  for (const LightReceiver& r : receivers) {
    double total = 0.0;
    for (size_t i = 0; i < sampler.size(); ++i) total += sampler.probability(r, i);
    EXPECT_NEAR(total, 1.0, 1e-5);
    const int n = 200000;
    std::vector<int> counts(sampler.size(), 0);
    for (int j = 0; j < n; ++j) {
      LightReceiver at = r;
      float p = 0.0f, remapped = -1.0f;
      const size_t i = sampler.sample(at, (j + 0.5f) / n, &p, &remapped);
      ASSERT_LT(i, sampler.size());
      ASSERT_GE(remapped, 0.0f);
      ASSERT_LT(remapped, 1.0f);
      // The same bits from the receiver sample() normalised and from a fresh one.
      ASSERT_EQ(p, sampler.probability(at, i));
      ASSERT_EQ(p, sampler.probability(r, i));
      ++counts[i];
    }
    for (size_t i = 0; i < sampler.size(); ++i)
      EXPECT_NEAR(counts[i] / double(n), sampler.probability(r, i), 2e-5) << i;
  }
}

TEST(Lights, SpatialSamplerFavoursNearLightsAndNeverPicksOneFromBehind) {
  const std::vector<Light> lights = spread_lights();
  const LightSampler sampler(lights, nullptr, 5.0f);
  // Under the first light the first gets most samples (the point light, ten times as
  // powerful but over five times as far, under half its global share); the third (facing up,
  // above r) none.
  const LightReceiver under_first{Vec3(-2, 0, 0.3f), Vec3(0, 0, 1), false};
  EXPECT_GT(sampler.probability(under_first, 0), 0.7f);
  EXPECT_LT(sampler.probability(under_first, 3), 0.5f * sampler.probability(3));
  EXPECT_EQ(sampler.probability(under_first, 2), 0.0f);
  // Every light that can reach r keeps at least its part of the power share, whatever the
  // bounds say (here r's normal faces away from all of them).
  const LightReceiver facing_away{Vec3(0, 0, 0.8f), Vec3(0, 0, -1), false};
  for (size_t i : {size_t(0), size_t(1), size_t(3)})
    EXPECT_GE(sampler.probability(facing_away, i),
              0.99f * LightSampler::kPowerShare * sampler.probability(i)) << i;
  // Behind both downward lights' planes and the upward one's: only the point light is left.
  std::vector<Light> one_sided = {lights[0], lights[1], lights[3]};
  one_sided[2] = area_light_from_power(Vec3(0, 0, 0.5f), Vec3(0.3f, 0, 0), Vec3(0, 0.3f, 0),
                                       Vec3(0, 0, -1), AreaShape::Ellipse, 40.0f, RGB(1.0f));
  const LightSampler above_all(one_sided, nullptr, 5.0f);
  LightReceiver high{Vec3(0, 0, 3), Vec3(0, 0, 1), false};
  float p = 1.0f;
  EXPECT_EQ(above_all.sample(high, 0.5f, &p), above_all.size());  // nothing to pick
  EXPECT_EQ(p, 0.0f);
  for (size_t i = 0; i < above_all.size(); ++i) EXPECT_EQ(above_all.probability(high, i), 0.0f);
  // A NaN normal gives finite probabilities that still add up to 1.
  const LightReceiver nan_normal{Vec3(0, 0, 0), Vec3(NAN, 0, 0), false};
  double total = 0.0;
  for (size_t i = 0; i < sampler.size(); ++i) {
    EXPECT_TRUE(std::isfinite(sampler.probability(nan_normal, i)));
    total += sampler.probability(nan_normal, i);
  }
  EXPECT_NEAR(total, 1.0, 1e-5);
  // One local light, or more than kMaxSpatialLights: the global distribution everywhere.
  EXPECT_FALSE(LightSampler({lights[0]}, nullptr, 5.0f).spatial());
  EXPECT_FALSE(LightSampler(std::vector<Light>(LightSampler::kMaxSpatialLights + 1, lights[3]),
                            nullptr, 5.0f).spatial());
}

namespace {

// A white Lambertian floor (z = 0, 20 m wide) seen from straight above by a narrow camera.
struct Floor {
  Scene scene;
  CameraSettings camera;
  RenderSettings settings;
  Floor() {
    ParamSet white;
    white.set("reflectance", RGBValue{0.8, 0.8, 0.8});
    scene.add_material(Material{{make("lambertian", white)}, RGB(0.0f)});
    scene.add_mesh(make_quad(Vec3(-10, -10, 0), Vec3(20, 0, 0), Vec3(0, 20, 0), 0).view());
    camera.camera_to_world = look_at(Vec3(0, 0, 4), Vec3(0, 0, 0), Vec3(0, 1, 0));
    camera.lens_mm = 2000.0f;  // 7 cm across: the irradiance is constant over it within 0.1%
    settings.width = settings.height = 8;
    settings.samples_per_pixel = 256;
    settings.max_bounces = 0;
    settings.threads = 2;
  }
  double mean() {
    scene.commit();
    const Film film = render_scene(scene, camera, settings);
    double sum = 0;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        float px[4];
        film.pixel(x, y, px);
        sum += px[0];
      }
    return sum / 64;
  }
};

}  // namespace

TEST(Lights, RenderedAreaLightMatchesQuadratureThroughBothStrategies) {
  // MIS between light and BSDF sampling must add up to the irradiance (0.8/π · E); the light
  // is invisible to the camera, which looks through it.
  Floor f;
  const float h = 1.0f;
  const Light l = area_light_from_power(Vec3(0, 0, h), Vec3(1.5f, 0, 0), Vec3(0, 1.0f, 0),
                                        Vec3(0, 0, -1), AreaShape::Ellipse, 50.0f, RGB(1.0f));
  f.scene.add_light(l);
  const double e = quadrature_irradiance(l.radiance.r, h, 1.5, 1.0,
                                         [](double x, double y) { return x * x + y * y <= 1.0; });
  EXPECT_NEAR(f.mean(), 0.8 / M_PI * e, 0.01 * 0.8 / M_PI * e);
}

TEST(Lights, RenderedLightsPickedByImportanceAddUpToTheirIrradiance) {
  // Three local lights (so light selection depends on the shading point) over the floor, and
  // one facing away below the camera: MIS with the per-point probabilities must still add up to
  // the sum of the irradiances.
  Floor f;
  const Light ellipse = area_light_from_power(Vec3(0, 0, 1), Vec3(1.5f, 0, 0), Vec3(0, 1, 0),
                                              Vec3(0, 0, -1), AreaShape::Ellipse, 50.0f, RGB(1.0f));
  const Light square =
      area_light_from_power(Vec3(0, 0, 2), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, -1),
                            AreaShape::Rectangle, 80.0f, RGB(1.0f));
  const Light point = point_light_from_power(Vec3(0, 0, 3), 300.0f, RGB(1.0f), 0.05f);
  const Light away = area_light_from_power(Vec3(0, 0, 2.5f), Vec3(1, 0, 0), Vec3(0, 1, 0),
                                           Vec3(0, 0, 1), AreaShape::Rectangle, 100.0f, RGB(1.0f));
  for (const Light& l : {ellipse, square, point, away}) f.scene.add_light(l);
  const auto disk = [](double x, double y) { return x * x + y * y <= 1.0; };
  const auto all = [](double, double) { return true; };
  // The point light's sphere of radius 0.05 at height 3: E = I / h² within 0.03%.
  const double e = quadrature_irradiance(ellipse.radiance.r, 1.0, 1.5, 1.0, disk) +
                   quadrature_irradiance(square.radiance.r, 2.0, 2.0, 2.0, all) +
                   point.intensity.r / 9.0;
  EXPECT_NEAR(f.mean(), 0.8 / M_PI * e, 0.01 * 0.8 / M_PI * e);
}

TEST(Lights, CameraSeesAreaLightOnlyWhenVisible) {
  for (bool visible : {false, true}) {
    Floor f;
    Light l = area_light_from_power(Vec3(0, 0, 2), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 1),
                                    AreaShape::Rectangle, 100.0f, RGB(1.0f));  // faces the camera
    l.visibility.camera = visible;
    f.scene.add_light(l);
    const double m = f.mean();  // the floor is behind the light: it gets nothing
    EXPECT_NEAR(m, visible ? 100.0 / (4.0 * 16.0) : 0.0, 1e-4) << visible;
  }
}

TEST(Lights, CastShadowOffLetsLightThroughOccluders) {
  for (bool cast : {true, false}) {
    Floor f;
    ParamSet grey;
    grey.set("reflectance", RGBValue{0.5, 0.5, 0.5});
    const uint32_t m = f.scene.add_material(Material{{make("lambertian", grey)}, RGB(0.0f)});
    // A blocker between the floor and the light, invisible to the camera.
    Mesh blocker = make_quad(Vec3(-2, -2, 2), Vec3(4, 0, 0), Vec3(0, 4, 0), m);
    blocker.visibility.camera = false;
    f.scene.add_mesh(blocker.view());
    Light l = point_light(Vec3(0, 0, 3), RGB(9.0f));
    l.visibility.cast_shadow = cast;
    f.scene.add_light(l);
    EXPECT_NEAR(f.mean(), cast ? 0.0 : 0.8 / M_PI * 1.0, 0.01) << cast;
  }
}

TEST(Lights, WideSunIsSeenByTheCameraOnlyWhenVisible) {
  for (bool visible : {false, true}) {
    Floor f;
    f.camera.camera_to_world = look_at(Vec3(0, 0, 1), Vec3(0, 0, 5), Vec3(0, 1, 0));  // looks up
    Light sun = sun_light(Vec3(0, 0, -1), RGB(2.0f), radians(10.0f));
    sun.visibility.camera = visible;
    f.scene.add_light(sun);
    // Straight into the sun's disk: radiance E·pdf = E / (π tan²(5°)) near its centre.
    const double centre = 2.0 / (M_PI * std::pow(std::tan(radians(5.0f)), 2));
    EXPECT_NEAR(f.mean(), visible ? centre : 0.0, 2e-3 * centre) << visible;
  }
}

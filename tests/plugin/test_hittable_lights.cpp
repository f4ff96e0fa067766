// The vector pre-test of the lights a ray can hit (hittable_lights.h): it may keep a light the
// ray misses (intersect_light() decides), but must never leave out one that intersect_light()
// finds, also at the rectangle's edges and corners and where the light lies at the ray's tmax;
// it lists the lights in increasing order, only those rays of the kind see, and leaves out the
// area lights a ray misses.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bxdf/render/hittable_lights.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

// Six hittable lights (two groups of four, the second part-filled) among lights rays cannot
// hit: area rectangles and ellipses facing several ways, point and spot lights with a radius.
std::vector<Light> mixed_lights() {
  std::vector<Light> lights;
  lights.push_back(point_light_from_power(Vec3(0, 0, 3), 100.0f, RGB(1.0f)));  // delta
  lights.push_back(area_light_from_power(Vec3(-1, 0, 1), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0),
                                         Vec3(0, 0, -1), AreaShape::Rectangle, 40.0f, RGB(1.0f)));
  lights.push_back(area_light_from_power(Vec3(1, 0.5f, 1.2f), Vec3(1, 0, 0.3f),
                                         Vec3(0, 0.4f, 0), normalize(Vec3(0.3f, 0, -1)),
                                         AreaShape::Ellipse, 40.0f, RGB(1.0f)));
  lights.push_back(point_light_from_power(Vec3(0, 1.5f, 1), 400.0f, RGB(1.0f), 0.1f));
  lights.push_back(sun_light(Vec3(0, 0, -1), RGB(1.0f), 0.1f));
  lights.push_back(area_light_from_power(Vec3(0, -1, 0.2f), Vec3(0.3f, 0, 0), Vec3(0, 0, 0.6f),
                                         Vec3(0, 1, 0), AreaShape::Rectangle, 40.0f, RGB(1.0f)));
  lights.push_back(area_light_from_power(Vec3(0.5f, 0.5f, -0.8f), Vec3(2, 0, 0),
                                         Vec3(0, 0.05f, 0), Vec3(0, 0, 1), AreaShape::Rectangle,
                                         40.0f, RGB(1.0f)));
  lights.push_back(spot_light_from_power(Vec3(-1, -1, 1), Vec3(1, 1, -1), 300.0f, RGB(1.0f),
                                         1.0f, 0.2f, 0.2f));
  return lights;
}

std::vector<uint32_t> candidates(const HittableLights& h, const Vec3& o, const Vec3& d,
                                 float tmax, bool camera_ray) {
  std::vector<uint32_t> out;
  h.for_each_candidate(o, d, tmax, camera_ray, [&](uint32_t i) { out.push_back(i); });
  return out;
}

bool contains(const std::vector<uint32_t>& v, uint32_t i) {
  for (uint32_t j : v)
    if (j == i) return true;
  return false;
}

}  // namespace

TEST(HittableLights, KeepsEveryLightARayHitsInOrderAndFewItMisses) {
  std::vector<Light> lights = mixed_lights();
  for (Light& l : lights) l.visibility.camera = true;
  const HittableLights hittable(lights);
  ASSERT_FALSE(hittable.empty());
  PCG32 rng(3, 5);
  int hits = 0, area_misses_kept = 0, area_misses = 0;
  for (int n = 0; n < 200000; ++n) {
    const Vec3 o((rng.uniform() - 0.5f) * 4.0f, (rng.uniform() - 0.5f) * 4.0f,
                 (rng.uniform() - 0.5f) * 4.0f);
    const Vec3 d = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const float tmax = n % 3 == 0 ? INFINITY : rng.uniform() * 3.0f;
    const std::vector<uint32_t> kept = candidates(hittable, o, d, tmax, n % 2 == 0);
    for (size_t k = 1; k < kept.size(); ++k) ASSERT_LT(kept[k - 1], kept[k]);
    for (uint32_t i = 0; i < lights.size(); ++i) {
      LightHit h;
      const bool hit = intersect_light(lights[i], o, d, tmax, &h);
      if (hit) {
        ++hits;
        ASSERT_TRUE(contains(kept, i)) << "light " << i << " ray " << n;
      } else if (lights[i].type == LightType::Area) {
        ++area_misses;
        area_misses_kept += contains(kept, i);
      }
      if (!lights[i].is_hittable()) {
        EXPECT_FALSE(contains(kept, i)) << i;
      }
    }
  }
  EXPECT_GT(hits, 1000);
  // The pre-test keeps only the ellipse's bounding-rectangle corners and the like.
  EXPECT_LT(area_misses_kept, area_misses / 100) << area_misses;
}

TEST(HittableLights, KeepsHitsAtTheEdgesCornersAndTmax) {
  const std::vector<Light> lights = mixed_lights();
  const HittableLights hittable(lights);
  PCG32 rng(9, 1);
  int tested = 0;
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type != LightType::Area) continue;
    for (int n = 0; n < 20000; ++n) {
      // A point on the rectangle's border (or just past it), seen from in front of the light.
      float x = rng.uniform() * 2.0f - 1.0f, y = rng.uniform() * 2.0f - 1.0f;
      const float edge = n % 4 < 2 ? 1.0f : 1.0f + 1e-6f * float(n % 7);
      if (n % 2 == 0) x = std::copysign(edge, x);
      else y = std::copysign(edge, y);
      if (n % 16 == 0) x = std::copysign(edge, x), y = std::copysign(edge, y);  // a corner
      const Vec3 target = l.position + l.axis_u * (0.5f * x) + l.axis_v * (0.5f * y);
      const Vec3 o = target + l.direction * (0.2f + 3.0f * rng.uniform()) +
                     Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
      const Vec3 d = normalize(target - o);
      LightHit h;
      if (!intersect_light(l, o, d, INFINITY, &h)) continue;
      // The light where the ray ends (a surface at the light's plane): the t it finds as tmax,
      // and the next float up.
      for (float tmax : {INFINITY, std::nextafter(h.t, INFINITY), h.t * (1.0f + 1e-6f)}) {
        LightHit again;
        if (!intersect_light(l, o, d, tmax, &again)) continue;
        ++tested;
        ASSERT_TRUE(contains(candidates(hittable, o, d, tmax, false), i))
            << "light " << i << " ray " << n << " tmax " << tmax;
      }
    }
  }
  EXPECT_GT(tested, 40000);
}

TEST(HittableLights, ListsOnlyTheLightsRaysOfTheKindSee) {
  std::vector<Light> lights = mixed_lights();
  // Camera rays see lights 1 and 3; BSDF rays all but light 5 (Multiple Importance off).
  lights[1].visibility.camera = lights[3].visibility.camera = true;
  lights[5].visibility.use_mis = false;
  const HittableLights hittable(lights);
  PCG32 rng(4, 4);
  bool saw_camera = false, saw_bsdf = false;
  for (int n = 0; n < 50000; ++n) {
    const Vec3 o(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    const Vec3 d = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    for (uint32_t i : candidates(hittable, o, d, INFINITY, true)) {
      ASSERT_TRUE(i == 1 || i == 3) << i;
      saw_camera = true;
    }
    for (uint32_t i : candidates(hittable, o, d, INFINITY, false)) {
      ASSERT_NE(i, 5u);
      saw_bsdf = true;
    }
  }
  EXPECT_TRUE(saw_camera);
  EXPECT_TRUE(saw_bsdf);
  EXPECT_TRUE(HittableLights({lights[0], lights[4]}).empty());  // a delta point light, a sun
}

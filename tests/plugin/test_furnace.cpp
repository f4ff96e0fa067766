// White furnaces: white Lambertian geometry inside a constant world of radiance 1 must render
// 1 everywhere (it neither adds nor removes energy). A single convex sphere needs only direct
// light; two nearly touching spheres see each other, so they need the indirect bounces, and
// any missing or doubled MIS weight shows up as a bias.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

struct FurnaceResult {
  double mean = 0, max_error = 0;
  RenderStats stats;
};

FurnaceResult furnace(const std::vector<Mesh>& meshes, int max_bounces, int spp) {
  Scene scene;
  ParamSet white;
  white.set("reflectance", RGBValue{1.0, 1.0, 1.0});
  scene.add_material(Material{{make("lambertian", white)}, RGB(0.0f)});
  for (const Mesh& m : meshes) scene.add_mesh(m.view());
  scene.set_world(RGB(1.0f));
  scene.commit();
  CameraSettings cam;
  cam.camera_to_world = look_at(Vec3(0, -4.5f, 0), Vec3(0, 0, 0), Vec3(0, 0, 1));
  RenderSettings s;
  s.width = s.height = 32;
  s.samples_per_pixel = spp;
  s.max_bounces = max_bounces;
  s.seed = 3;
  FurnaceResult r;
  const Film film = render_scene(scene, cam, s, {}, &r.stats);
  double sum = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      float px[4];
      film.pixel(x, y, px);
      for (int c = 0; c < 3; ++c) {
        sum += px[c];
        r.max_error = std::max(r.max_error, std::fabs(px[c] - 1.0));
      }
    }
  r.mean = sum / (32 * 32 * 3);
  return r;
}

}  // namespace

TEST(Furnace, ConvexWhiteSphereIsOneWithDirectLightOnly) {
  const FurnaceResult r = furnace({make_uv_sphere(Vec3(0, 0, 0), 1.2f, 48, 24, 0)}, 0, 64);
  EXPECT_NEAR(r.mean, 1.0, 0.01);
  EXPECT_LT(r.max_error, 0.15);  // per pixel: 64 samples of a bounded estimator
  EXPECT_EQ(r.stats.rejected_samples, 0u);
}

TEST(Furnace, TwoWhiteSpheresAreOneWithManyBounces) {
  const std::vector<Mesh> spheres = {make_uv_sphere(Vec3(-1.02f, 0, 0), 1.0f, 48, 24, 0),
                                     make_uv_sphere(Vec3(1.02f, 0, 0), 1.0f, 48, 24, 0)};
  const FurnaceResult many = furnace(spheres, 64, 64);
  EXPECT_NEAR(many.mean, 1.0, 0.01);
  EXPECT_LT(many.max_error, 0.25);
  // With direct light only, the light the spheres exchange is missing: visibly darker.
  const FurnaceResult direct = furnace(spheres, 0, 64);
  EXPECT_LT(direct.mean, many.mean - 0.01) << direct.mean << " " << many.mean;
}

// Paths traced in batches, vertex by vertex (PathBatch), give each sample the very result and
// the counts of tracing it alone, through transparent passes, refraction and node materials.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bxdf/registry.h"
#include "bxdf/render/camera.h"
#include "bxdf/render/filter.h"
#include "bxdf/render/material_graph_json.h"
#include "bxdf/render/shapes.h"
#include "path_batch.h"

using namespace bxdf;
using namespace bxdf::render;
using json = nlohmann::json;

namespace {

// `transparent_background`: camera rays that escape (finished at once by the batch) give no
// world radiance and alpha 0, those that passed the veil first give its share.
void expect_batches_trace_as_alone(bool transparent_background) {
  Scene scene;
  TextureStore textures;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  // Half transparent, half rough diffuse: camera rays pass through it (stream queries with the
  // camera's mask) and paths end at random.
  Material mixed;
  mixed.graph = read_material_graph(
      json{{"closures",
            {{{"model", "cycles_transparent"}, {"weight", 0.5}, {"params", {{"color", 0.9}}}},
             {{"model", "cycles_oren_nayar"}, {"weight", 0.5}, {"params", {{"color", 0.7}}}}}}},
      "graph", "", textures);
  scene.add_material(std::move(mixed));
  ParamSet sharp_glass;
  sharp_glass.set("roughness", 0.0);
  sharp_glass.set("ior", 1.5);
  scene.add_material(Material{{make("cycles_glass", sharp_glass)}, RGB(0.0f)});
  const Mesh floor = make_quad(Vec3(-4, -4, -1), Vec3(8, 0, 0), Vec3(0, 8, 0), 0);
  const Mesh veil = make_uv_sphere(Vec3(-0.7f, 0, 0), 0.6f, 24, 12, 1);
  const Mesh glass = make_uv_sphere(Vec3(0.8f, 0.3f, -0.3f), 0.6f, 24, 12, 2);
  for (const Mesh* m : {&floor, &veil, &glass}) scene.add_mesh(m->view());
  scene.add_light(point_light(Vec3(2, -2, 3), RGB(20.0f)));
  scene.set_world(RGB(0.2f));
  scene.commit();

  IntegratorSettings settings;
  settings.max_bounces = 6;
  settings.russian_roulette_depth = 1;
  settings.transparent_background = transparent_background;
  const PathTracer tracer(scene, settings);
  CameraSettings cs;
  cs.camera_to_world = look_at(Vec3(0, -5, 1), Vec3(0, 0, 0), Vec3(0, 0, 1));
  const Camera camera(cs, 20, 14);

  // More samples than one batch holds, and a last batch not full.
  PathBatch batch(scene, tracer);
  PathStats batched, alone;
  int compared = 0, escaped = 0;
  const auto check = [&] {
    batch.trace(batched);
    for (int k = 0; k < batch.size(); ++k) {
      const PathBatch::Sample& c = batch.sample(k);
      const PathSampler sampler(c.pixel_seed, c.index);
      const Point2 jitter = sampler.filter();
      const Ray ray = camera.generate_ray(float(c.x) + jitter.x, float(c.y) + jitter.y);
      CameraHit hit;
      scene.intersect_camera_rays(&ray, 1, &hit);
      const PathResult r = tracer.trace(ray, sampler, alone, &hit);
      escaped += !hit.found;
      const PathResult& b = batch.result(k);
      ASSERT_TRUE(r.radiance.r == b.radiance.r && r.radiance.g == b.radiance.g &&
                  r.radiance.b == b.radiance.b && r.alpha == b.alpha)
          << "pixel (" << c.x << ", " << c.y << ") sample " << c.index;
      ++compared;
    }
    batch.clear();
  };
  for (int y = 0; y < 14; ++y) {
    for (int x = 0; x < 20; ++x) {
      const uint32_t seed = PathSampler::pixel_seed(uint32_t(x), uint32_t(y), 7);
      for (uint32_t s = 0; s < 3; ++s) {
        const Point2 jitter = PathSampler(seed, s).filter();
        batch.add({x, y, seed, s}, camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y));
        if (batch.full()) check();
      }
    }
  }
  ASSERT_GT(batch.size(), 0);
  check();
  EXPECT_EQ(compared, 20 * 14 * 3);
  EXPECT_EQ(batched.rays, alone.rays);
  EXPECT_EQ(batched.shadow_rays, alone.shadow_rays);
  EXPECT_EQ(batched.rejected, alone.rejected);
  EXPECT_GT(batched.rays, uint64_t(2 * compared));  // paths went past their first hit
  EXPECT_GT(escaped, 20);                            // and camera rays saw the sky
}

}  // namespace

TEST(PathBatch, EverySampleIsWhatTracingItAloneGives) { expect_batches_trace_as_alone(false); }

TEST(PathBatch, EverySampleIsWhatTracingItAloneGivesOnATransparentFilm) {
  expect_batches_trace_as_alone(true);
}

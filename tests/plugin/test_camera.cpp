// The camera against Blender's rules (BKE_camera_params_compute_viewplane): sensor fit, lens,
// shift in units of the fitted side, clip planes at depths along the view axis.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/params.h"
#include "bxdf/render/camera.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

// Camera at the origin looking down -Z (Blender's default orientation), identity matrix.
// Returns the point where the ray through raster (x, y) meets the plane z = -1.
Point2 plane_point(const Camera& cam, float x, float y) {
  const Ray r = cam.generate_ray(x, y);
  return {r.dir.x / -r.dir.z, r.dir.y / -r.dir.z};
}

}  // namespace

TEST(Camera, AutoFitUsesSensorWidthForTheLargerSide) {
  CameraSettings s;
  s.lens_mm = 50.0f;
  s.sensor_width_mm = 36.0f;
  s.sensor_height_mm = 24.0f;
  // Landscape: the width spans 36/50 at unit distance.
  const Camera wide(s, 200, 100);
  EXPECT_NEAR(plane_point(wide, 200, 50).x, 0.36f, 1e-5f);
  EXPECT_NEAR(plane_point(wide, 100, 0).y, 0.18f, 1e-5f);
  // Portrait: AUTO puts the sensor *width* along the height.
  const Camera tall(s, 100, 200);
  EXPECT_NEAR(plane_point(tall, 50, 0).y, 0.36f, 1e-5f);
  EXPECT_NEAR(plane_point(tall, 100, 100).x, 0.18f, 1e-5f);
}

TEST(Camera, HorizontalAndVerticalFit) {
  CameraSettings s;
  s.lens_mm = 35.0f;
  s.sensor_width_mm = 36.0f;
  s.sensor_height_mm = 24.0f;
  s.sensor_fit = SensorFit::Horizontal;
  const Camera h(s, 100, 200);  // portrait but horizontal fit: width spans 36/35
  EXPECT_NEAR(plane_point(h, 100, 100).x, 0.5f * 36.0f / 35.0f, 1e-5f);
  EXPECT_NEAR(plane_point(h, 50, 0).y, 36.0f / 35.0f, 1e-5f);
  s.sensor_fit = SensorFit::Vertical;
  const Camera v(s, 200, 100);  // landscape, vertical fit: height spans 24/35
  EXPECT_NEAR(plane_point(v, 100, 0).y, 0.5f * 24.0f / 35.0f, 1e-5f);
  EXPECT_NEAR(plane_point(v, 200, 50).x, 24.0f / 35.0f, 1e-5f);
}

TEST(Camera, ShiftIsInUnitsOfTheFittedSide) {
  CameraSettings s;
  s.shift_x = 0.25f;
  s.shift_y = -0.1f;
  const Camera c(s, 100, 50);  // horizontal (AUTO), fitted side 36/50 = 0.72
  const Point2 centre = plane_point(c, 50, 25);
  EXPECT_NEAR(centre.x, 0.25f * 0.72f, 1e-5f);
  EXPECT_NEAR(centre.y, -0.1f * 0.72f, 1e-5f);
  s.sensor_fit = SensorFit::Vertical;
  const Camera v(s, 100, 50);  // fitted side is the height: 24/50
  EXPECT_NEAR(plane_point(v, 50, 25).x, 0.25f * 0.48f, 1e-5f);
}

TEST(Camera, ClipPlanesAreDepthsAlongTheViewAxis) {
  CameraSettings s;
  s.clip_start = 0.5f;
  s.clip_end = 10.0f;
  const Camera c(s, 64, 64);
  for (float x : {0.0f, 32.0f, 64.0f}) {
    const Ray r = c.generate_ray(x, 5.0f);
    EXPECT_NEAR(-r.at(r.tmin).z, 0.5f, 1e-5f);
    EXPECT_NEAR(-r.at(r.tmax).z, 10.0f, 1e-4f);
  }
}

TEST(Camera, MatrixPlacesAndOrientsTheCamera) {
  CameraSettings s;
  s.camera_to_world = look_at(Vec3(1, -5, 2), Vec3(1, 0, 2), Vec3(0, 0, 1));
  const Camera c(s, 32, 32);
  const Ray centre = c.generate_ray(16, 16);
  EXPECT_NEAR(centre.dir.y, 1.0f, 1e-6f);
  EXPECT_NEAR(centre.origin.x, 1.0f, 1e-6f);
  // Right of the image is +X, top is +Z.
  EXPECT_GT(c.generate_ray(32, 16).dir.x, 0.0f);
  EXPECT_GT(c.generate_ray(16, 0).dir.z, 0.0f);
}

TEST(Camera, RefusesBadSettingsByName) {
  CameraSettings s;
  s.lens_mm = 0.0f;
  try {
    Camera(s, 8, 8);
    FAIL() << "lens 0 accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("lens_mm"), std::string::npos);
  }
  s = CameraSettings();
  s.clip_end = s.clip_start;
  EXPECT_THROW(Camera(s, 8, 8), ParameterError);
}

TEST(Camera, OrthographicRaysAreParallelAndSpanTheOrthoScale) {
  CameraSettings s;
  s.projection = Projection::Orthographic;
  s.ortho_scale = 4.0f;
  s.clip_start = 0.5f;
  s.clip_end = 20.0f;
  s.camera_to_world = look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  const Camera c(s, 200, 100);  // AUTO fit, landscape: the width spans 4, the height 2
  EXPECT_TRUE(c.orthographic());
  const Ray corner = c.generate_ray(200, 0);
  const Ray centre = c.generate_ray(100, 50);
  EXPECT_NEAR(corner.origin.x, 2.0f, 1e-5f);
  EXPECT_NEAR(corner.origin.y, 1.0f, 1e-5f);
  EXPECT_NEAR(corner.origin.z, 5.0f, 1e-5f);
  for (const Ray& r : {corner, centre}) {
    EXPECT_NEAR(r.dir.z, -1.0f, 1e-6f);
    EXPECT_NEAR(r.tmin, 0.5f, 1e-6f);  // unit direction: t is the depth
    EXPECT_NEAR(r.tmax, 20.0f, 1e-6f);
  }
  // Portrait with AUTO fit: the ortho scale goes along the height.
  const Camera tall(s, 100, 200);
  EXPECT_NEAR(tall.generate_ray(50, 0).origin.y, 2.0f, 1e-5f);
  EXPECT_NEAR(tall.generate_ray(100, 100).origin.x, 1.0f, 1e-5f);
}

TEST(Camera, OrthographicShiftIsInUnitsOfTheOrthoScale) {
  CameraSettings s;
  s.projection = Projection::Orthographic;
  s.ortho_scale = 3.0f;
  s.shift_x = 0.5f;
  s.shift_y = -0.25f;
  const Camera c(s, 100, 50);
  const Ray r = c.generate_ray(50, 25);
  EXPECT_NEAR(r.origin.x, 1.5f, 1e-5f);
  EXPECT_NEAR(r.origin.y, -0.75f, 1e-5f);
}

TEST(Camera, RefusesANonPositiveOrthoScale) {
  CameraSettings s;
  s.projection = Projection::Orthographic;
  for (float bad : {0.0f, -1.0f, NAN, INFINITY}) {
    s.ortho_scale = bad;
    try {
      Camera c(s, 10, 10);
      FAIL() << "ortho_scale " << bad << " was accepted";
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find("ortho_scale"), std::string::npos) << e.what();
    }
  }
}

TEST(Camera, RaysMadeTogetherAreTheRaysMadeOneByOne) {
  // Perspective (shifted, tilted, clipped) and orthographic; 150 positions cross the batch's
  // blocks of 64 and include the image's corners and points past its edges.
  for (const Projection projection : {Projection::Perspective, Projection::Orthographic}) {
    CameraSettings s;
    s.projection = projection;
    s.lens_mm = 35.0f;
    s.shift_x = 0.1f;
    s.shift_y = -0.05f;
    s.clip_start = 0.3f;
    s.clip_end = 40.0f;
    s.camera_to_world = look_at(Vec3(1, -5, 2), Vec3(0.2f, 0, 0.7f), Vec3(0, 0, 1));
    const Camera c(s, 96, 64);
    constexpr int kN = 150;
    float x[kN], y[kN];
    for (int i = 0; i < kN; ++i) {
      x[i] = -1.0f + 98.0f * static_cast<float>((i * 37) % kN) / kN;
      y[i] = -1.0f + 66.0f * static_cast<float>((i * 61) % kN) / kN;
    }
    x[0] = 0.0f, y[0] = 0.0f, x[1] = 96.0f, y[1] = 64.0f;
    Ray together[kN];
    c.generate_rays(x, y, kN, together);
    for (int i = 0; i < kN; ++i) {
      const Ray one = c.generate_ray(x[i], y[i]);
      SCOPED_TRACE(testing::Message() << "projection " << int(projection) << " i " << i);
      EXPECT_EQ(together[i].origin.x, one.origin.x);
      EXPECT_EQ(together[i].origin.y, one.origin.y);
      EXPECT_EQ(together[i].origin.z, one.origin.z);
      EXPECT_EQ(together[i].dir.x, one.dir.x);
      EXPECT_EQ(together[i].dir.y, one.dir.y);
      EXPECT_EQ(together[i].dir.z, one.dir.z);
      EXPECT_EQ(together[i].tmin, one.tmin);
      EXPECT_EQ(together[i].tmax, one.tmax);
    }
  }
}

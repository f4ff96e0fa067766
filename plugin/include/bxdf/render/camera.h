// A camera that matches Blender's perspective camera (a pinhole: focal length in mm, sensor
// width/height with fit AUTO/HORIZONTAL/VERTICAL) and its orthographic one (parallel rays over
// ortho_scale, fitted the same way): lens shift, clip start/end (planes at a depth along the view
// axis, as Cycles clips), looking down its local -Z with +Y up.
#pragma once

#include <array>

#include "bxdf/math.h"
#include "bxdf/render/ray.h"

namespace bxdf::render {

enum class SensorFit { Auto, Horizontal, Vertical };
enum class Projection { Perspective, Orthographic };

struct CameraSettings {
  Projection projection = Projection::Perspective;
  float ortho_scale = 6.0f;  // orthographic: the fitted side's width in scene units, as Blender's
  float lens_mm = 50.0f;
  float sensor_width_mm = 36.0f;
  float sensor_height_mm = 24.0f;
  SensorFit sensor_fit = SensorFit::Auto;
  float shift_x = 0.0f;  // in units of the fitted sensor dimension, as Blender's shift
  float shift_y = 0.0f;
  float clip_start = 0.1f;
  float clip_end = 100.0f;
  // Camera-to-world (Blender's matrix_world), row-major 4×4. Its scale is ignored.
  std::array<float, 16> camera_to_world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

// Camera-to-world matrix of a camera at `eye` looking at `target` with `up` roughly up.
std::array<float, 16> look_at(const Vec3& eye, const Vec3& target, const Vec3& up);

class Camera {
 public:
  Camera() = default;
  // Throws ParameterError naming the bad setting (non-positive lens or sensor, clip range...).
  Camera(const CameraSettings& settings, int width, int height);

  // The ray through raster position (x, y): x right in [0, width], y down in [0, height].
  Ray generate_ray(float x, float y) const {
    const float px = (x * inv_width_ - 0.5f) * plane_width_ + shift_x_;
    const float py = (0.5f - y * inv_height_) * plane_height_ + shift_y_;
    if (orthographic_) {  // parallel rays from the plane through the eye; clip depths from it
      Ray r;
      r.origin = eye_ + right_ * px + up_ * py;
      r.dir = forward_;
      r.tmin = clip_start_;
      r.tmax = clip_end_;
      return r;
    }
    const Vec3 d = right_ * px + up_ * py - back_;
    const float len = length(d);
    Ray r;
    r.origin = eye_;
    r.dir = d / len;
    // Clip planes are depths along the view axis: t = depth · |d| for d with unit depth.
    r.tmin = clip_start_ * len;
    r.tmax = clip_end_ * len;
    return r;
  }

  // generate_ray for n raster positions at once, bit for bit: the perspective directions are
  // made and normalised in a loop over arrays, which the compiler turns into vector square
  // roots and divisions (one at a time, their latency was most of a camera sample's setup).
  void generate_rays(const float* x, const float* y, int n, Ray* out) const;

  const Vec3& position() const { return eye_; }
  const Vec3& forward() const { return forward_; }
  bool orthographic() const { return orthographic_; }
  // Size of the image plane at unit distance (tan of the half angles, doubled); orthographic:
  // the size of the view in scene units.
  float plane_width() const { return plane_width_; }
  float plane_height() const { return plane_height_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Vec3 eye_, right_{1, 0, 0}, up_{0, 1, 0}, back_{0, 0, 1}, forward_{0, 0, -1};
  float plane_width_ = 1.0f, plane_height_ = 1.0f, shift_x_ = 0.0f, shift_y_ = 0.0f;
  float inv_width_ = 1.0f, inv_height_ = 1.0f;
  float clip_start_ = 0.0f, clip_end_ = 1e30f;
  int width_ = 1, height_ = 1;
  bool orthographic_ = false;
};

}  // namespace bxdf::render

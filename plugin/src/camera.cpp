#include "bxdf/render/camera.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bxdf/params.h"

namespace bxdf::render {

namespace {

void require_positive(const char* name, float v) {
  if (!(v > 0.0f) || !std::isfinite(v))
    throw ParameterError(std::string("camera ") + name + " " + std::to_string(v) +
                         " must be in (0, inf)");
}

Vec3 column(const std::array<float, 16>& m, int c) { return {m[c], m[4 + c], m[8 + c]}; }

}  // namespace

std::array<float, 16> look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
  Vec3 back = eye - target;
  if (!normalize_direction(back)) throw ParameterError("look_at: eye and target coincide");
  Vec3 right = cross(up, back);
  if (!normalize_direction(right)) throw ParameterError("look_at: up is parallel to the view");
  const Vec3 true_up = cross(back, right);
  return {right.x, true_up.x, back.x, eye.x,  //
          right.y, true_up.y, back.y, eye.y,  //
          right.z, true_up.z, back.z, eye.z,  //
          0, 0, 0, 1};
}

Camera::Camera(const CameraSettings& s, int width, int height) {
  const bool orthographic = s.projection == Projection::Orthographic;
  if (orthographic) require_positive("ortho_scale", s.ortho_scale);
  require_positive("lens_mm", s.lens_mm);
  require_positive("sensor_width_mm", s.sensor_width_mm);
  require_positive("sensor_height_mm", s.sensor_height_mm);
  if (width < 1 || height < 1)
    throw ParameterError("camera image size " + std::to_string(width) + "x" +
                         std::to_string(height) + " must be at least 1x1");
  if (!(s.clip_start >= 0.0f) || !(s.clip_end > s.clip_start) || !std::isfinite(s.clip_end))
    throw ParameterError("camera clip_start " + std::to_string(s.clip_start) + " / clip_end " +
                         std::to_string(s.clip_end) + " must satisfy 0 <= start < end < inf");
  if (!std::isfinite(s.shift_x) || !std::isfinite(s.shift_y))
    throw ParameterError("camera shift must be finite");
  for (size_t i = 0; i < s.camera_to_world.size(); ++i)
    if (!(std::fabs(s.camera_to_world[i]) <= kMaxSceneCoordinate))  // NaN and Inf fail too
      throw ParameterError("camera matrix[" + std::to_string(i / 4) + "][" + std::to_string(i % 4) +
                           "] = " + std::to_string(s.camera_to_world[i]) +
                           " is outside [-1e9, 1e9] (the renderer's coordinate range, metres)");

  width_ = width;
  height_ = height;
  inv_width_ = 1.0f / static_cast<float>(width);
  inv_height_ = 1.0f / static_cast<float>(height);

  // Blender (BKE_camera_params_compute_viewplane): AUTO fits the sensor width to the larger
  // image side; VERTICAL uses the sensor height. The shift is in units of the fitted side.
  // Orthographic: ortho_scale is the fitted side, whichever sensor size (only the fit counts).
  bool horizontal = s.sensor_fit == SensorFit::Horizontal ||
                    (s.sensor_fit == SensorFit::Auto && width >= height);
  const float sensor = s.sensor_fit == SensorFit::Vertical ? s.sensor_height_mm : s.sensor_width_mm;
  // size of the fitted side at unit distance (perspective) or anywhere (orthographic)
  const float fitted = orthographic ? s.ortho_scale : sensor / s.lens_mm;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  if (horizontal) {
    plane_width_ = fitted;
    plane_height_ = fitted / aspect;
  } else {
    plane_height_ = fitted;
    plane_width_ = fitted * aspect;
  }
  shift_x_ = s.shift_x * fitted;
  shift_y_ = s.shift_y * fitted;
  clip_start_ = s.clip_start;
  clip_end_ = s.clip_end;
  orthographic_ = orthographic;

  right_ = column(s.camera_to_world, 0);
  up_ = column(s.camera_to_world, 1);
  back_ = column(s.camera_to_world, 2);
  eye_ = column(s.camera_to_world, 3);
  if (!normalize_direction(right_) || !normalize_direction(up_) || !normalize_direction(back_))
    throw ParameterError("camera matrix has a zero axis (one of its first three columns is 0)");
  forward_ = -back_;
}

void Camera::generate_rays(const float* x, const float* y, int n, Ray* out) const {
  if (orthographic_) {
    for (int i = 0; i < n; ++i) out[i] = generate_ray(x[i], y[i]);
    return;
  }
  constexpr int kBlock = 64;
  float dx[kBlock], dy[kBlock], dz[kBlock], len[kBlock];
  for (int first = 0; first < n; first += kBlock) {
    const int m = std::min(kBlock, n - first);
    // The operations of generate_ray in its order: d = right·px + up·py − back, |d|, d·(1/|d|).
    for (int i = 0; i < m; ++i) {
      const float px = (x[first + i] * inv_width_ - 0.5f) * plane_width_ + shift_x_;
      const float py = (0.5f - y[first + i] * inv_height_) * plane_height_ + shift_y_;
      dx[i] = right_.x * px + up_.x * py - back_.x;
      dy[i] = right_.y * px + up_.y * py - back_.y;
      dz[i] = right_.z * px + up_.z * py - back_.z;
      len[i] = std::sqrt(dx[i] * dx[i] + dy[i] * dy[i] + dz[i] * dz[i]);
    }
    for (int i = 0; i < m; ++i) {
      const float inv = 1.0f / len[i];
      Ray& r = out[first + i];
      r.origin = eye_;
      r.dir = Vec3(dx[i] * inv, dy[i] * inv, dz[i] * inv);
      r.tmin = clip_start_ * len[i];
      r.tmax = clip_end_ * len[i];
    }
  }
}

}  // namespace bxdf::render

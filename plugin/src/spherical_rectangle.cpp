#include "bxdf/render/spherical_rectangle.h"

#include <cmath>

namespace bxdf::render {

namespace {

// The four angles of a rectangle were a sixth of an area light's sample through the library's
// acosf; the polynomial is inline and as accurate.
float safe_acosf(float x) { return acos_poly(clamp(x, -1.0f, 1.0f)); }

}  // namespace

SphericalRectangle::SphericalRectangle(const Vec3& centre, const Vec3& axis_u, const Vec3& axis_v)
    : corner_(centre - axis_u * 0.5f - axis_v * 0.5f),
      len_u_(length(axis_u)),
      len_v_(length(axis_v)) {
  x_ = axis_u / len_u_;
  y_ = axis_v / len_v_;
  z_ = cross(x_, y_);
}

// The rectangle in a frame at p: x along axis_u, y along axis_v, z towards p's side flipped so
// that the rectangle lies at z0 <= 0; corners (x0..x1, y0..y1).
struct SphericalRectangle::Frame {
  Vec3 z;
  float x0, x1, y0, y1, z0;
  float b0, b1, k, solid_angle;
};

SphericalRectangle::Frame SphericalRectangle::frame(const Vec3& p) const {
  Frame f;
  f.z = z_;
  const Vec3 dir = corner_ - p;
  f.z0 = dot(dir, f.z);
  if (f.z0 > 0.0f) {
    f.z = -f.z;
    f.z0 = -f.z0;
  }
  f.x0 = dot(dir, x_);
  f.y0 = dot(dir, y_);
  f.x1 = f.x0 + len_u_;
  f.y1 = f.y0 + len_v_;
  // Normals of the four edge planes through p, and the spherical rectangle's internal angles.
  const float diff[4] = {f.x0 - f.x1, f.y1 - f.y0, f.x1 - f.x0, f.y0 - f.y1};
  const float base[4] = {f.y0, f.x1, f.y1, f.x0};
  float nz[4];
  for (int i = 0; i < 4; ++i) {
    const float n = base[i] * diff[i];
    nz[i] = n / std::sqrt(f.z0 * f.z0 * diff[i] * diff[i] + n * n);
  }
  const float g0 = safe_acosf(-nz[0] * nz[1]);
  const float g1 = safe_acosf(-nz[1] * nz[2]);
  const float g2 = safe_acosf(-nz[2] * nz[3]);
  const float g3 = safe_acosf(-nz[3] * nz[0]);
  f.b0 = nz[0];
  f.b1 = nz[2];
  f.k = 2.0f * kPi - g2 - g3;
  f.solid_angle = g0 + g1 - f.k;
  return f;
}

float SphericalRectangle::sample(const Vec3& p, Point2 u, Vec3* q) const {
  const Frame f = frame(p);
  if (!(f.solid_angle > 0.0f) || f.z0 == 0.0f) return 0.0f;
  // u.x picks the x coordinate by solid angle, u.y the y coordinate on that column.
  const float au = u.x * f.solid_angle + f.k;
  const float fu = (std::cos(au) * f.b0 - f.b1) / std::sin(au);
  float cu = std::copysign(1.0f, fu) / std::sqrt(fu * fu + f.b0 * f.b0);
  cu = clamp(cu, -1.0f, 1.0f);
  float xu = -(cu * f.z0) / std::max(std::sqrt(1.0f - cu * cu), 1e-7f);
  xu = clamp(xu, f.x0, f.x1);
  const float d2 = xu * xu + f.z0 * f.z0;
  const float h0 = f.y0 / std::sqrt(d2 + f.y0 * f.y0);
  const float h1 = f.y1 / std::sqrt(d2 + f.y1 * f.y1);
  const float hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
  const float yv = hv2 < 1.0f - 1e-6f ? hv * std::sqrt(d2) / std::sqrt(1.0f - hv2) : f.y1;
  *q = p + x_ * xu + y_ * yv + f.z * f.z0;
  return 1.0f / f.solid_angle;
}

float SphericalRectangle::pdf(const Vec3& p) const {
  const Frame f = frame(p);
  return f.solid_angle > 0.0f && f.z0 != 0.0f ? 1.0f / f.solid_angle : 0.0f;
}

}  // namespace bxdf::render

// Independent reference geometry for the renderer's tests: Blender's camera rays written out
// from Blender's rules, and brute-force ray/mesh intersection in double precision, so that the
// truth does not come from the code under test (Embree, Camera, Scene::surface_point).
#pragma once

#include <array>
#include <cmath>
#include <optional>

#include "bxdf/render/mesh.h"

namespace bxdf::test {

struct D3 {
  double x = 0, y = 0, z = 0;
  D3() = default;
  D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  D3 operator+(const D3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  D3 operator-(const D3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  D3 operator*(double s) const { return {x * s, y * s, z * s}; }
  D3 operator-() const { return {-x, -y, -z}; }
};
inline double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const D3& a) { return std::sqrt(dot(a, a)); }
inline D3 unit(const D3& a) { return a * (1.0 / norm(a)); }

// A camera at `eye` looking at `target`, world up +Z, Blender's horizontal sensor fit with a
// square image: the image plane at unit distance is sensor/lens wide. Ray through the centre of
// pixel (px, py), row 0 at the top.
struct ReferenceCamera {
  D3 eye, target;
  double lens_mm = 50, sensor_mm = 36;
  int width = 32, height = 32;
  D3 ray(int px, int py) const {
    const D3 forward = unit(target - eye);
    const D3 right = unit(cross(forward, D3(0, 0, 1)));
    const D3 up = cross(right, forward);
    const double plane_w = sensor_mm / lens_mm;
    const double plane_h = plane_w * height / width;
    const double sx = ((px + 0.5) / width - 0.5) * plane_w;
    const double sy = (0.5 - (py + 0.5) / height) * plane_h;
    return unit(forward + right * sx + up * sy);
  }
};

struct MeshHit {
  double t;
  D3 p, ng, ns;  // ng from the winding, ns interpolated and normalised
  size_t triangle;
};

inline D3 vertex(const std::vector<float>& a, uint32_t i) {
  return {a[3 * size_t(i)], a[3 * size_t(i) + 1], a[3 * size_t(i) + 2]};
}

// Closest hit of origin + t dir (t > tmin) with the mesh (Möller–Trumbore).
inline std::optional<MeshHit> intersect(const render::Mesh& m, const D3& o, const D3& d,
                                        double tmin = 1e-9) {
  std::optional<MeshHit> best;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const uint32_t i0 = m.indices[3 * t], i1 = m.indices[3 * t + 1], i2 = m.indices[3 * t + 2];
    const D3 p0 = vertex(m.positions, i0), e1 = vertex(m.positions, i1) - p0,
             e2 = vertex(m.positions, i2) - p0;
    const D3 pv = cross(d, e2);
    const double det = dot(e1, pv);
    if (std::fabs(det) < 1e-300) continue;
    const D3 tv = o - p0;
    const double b1 = dot(tv, pv) / det;
    if (b1 < 0 || b1 > 1) continue;
    const D3 qv = cross(tv, e1);
    const double b2 = dot(d, qv) / det;
    if (b2 < 0 || b1 + b2 > 1) continue;
    const double dist = dot(e2, qv) / det;
    if (dist <= tmin || (best && dist >= best->t)) continue;
    MeshHit h;
    h.t = dist;
    h.p = o + d * dist;
    h.ng = unit(cross(e1, e2));
    h.ns = h.ng;
    if (!m.normals.empty())
      h.ns = unit(vertex(m.normals, i0) * (1 - b1 - b2) + vertex(m.normals, i1) * b1 +
                  vertex(m.normals, i2) * b2);
    h.triangle = t;
    best = h;
  }
  return best;
}

}  // namespace bxdf::test

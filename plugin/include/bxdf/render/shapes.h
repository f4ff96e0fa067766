// Mesh generators for tests, benchmarks and JSON scenes: a UV sphere with smooth normals, a
// quad, and an axis-aligned box.
#pragma once

#include "bxdf/math.h"
#include "bxdf/render/mesh.h"

namespace bxdf::render {

// Latitude/longitude sphere: `rings` bands from pole to pole, `segments` around; normals are the
// exact sphere normals at the vertices, u = longitude / 2π, v = colatitude / π.
Mesh make_uv_sphere(const Vec3& center, float radius, int segments, int rings, uint32_t material);

// Parallelogram corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v; its front
// faces along cross(edge_u, edge_v). Two triangles, flat normal, UVs over [0, 1]².
Mesh make_quad(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, uint32_t material);

// Box between lo and hi, faces pointing outwards, flat shaded.
Mesh make_box(const Vec3& lo, const Vec3& hi, uint32_t material);

// Appends b's triangles to a (materials kept per triangle).
void append_mesh(Mesh& a, const Mesh& b);

}  // namespace bxdf::render

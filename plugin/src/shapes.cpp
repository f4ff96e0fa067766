#include "bxdf/render/shapes.h"

#include <string>

#include "bxdf/params.h"

namespace bxdf::render {

Mesh make_uv_sphere(const Vec3& center, float radius, int segments, int rings, uint32_t material) {
  if (!(radius > 0.0f) || !std::isfinite(radius))
    throw ParameterError("sphere radius " + std::to_string(radius) + " must be in (0, inf)");
  if (segments < 3 || rings < 2)
    throw ParameterError("sphere needs segments >= 3 and rings >= 2, got " +
                         std::to_string(segments) + " and " + std::to_string(rings));
  Mesh m;
  m.material = material;
  // (rings + 1) rows of (segments + 1) vertices: the seam column is duplicated for the UVs.
  for (int j = 0; j <= rings; ++j) {
    const float v = static_cast<float>(j) / static_cast<float>(rings);
    const float theta = v * kPi;
    for (int i = 0; i <= segments; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(segments);
      const float phi = u * 2.0f * kPi;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      const Vec3 p = center + n * radius;
      m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
      m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
      m.uvs.insert(m.uvs.end(), {u, 1.0f - v});
    }
  }
  const auto vid = [segments](int i, int j) {
    return static_cast<uint32_t>(j * (segments + 1) + i);
  };
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const uint32_t a = vid(i, j), b = vid(i + 1, j), c = vid(i + 1, j + 1), d = vid(i, j + 1);
      // Outward facing: from the north pole (z = +r) down, counter-clockwise seen from outside.
      if (j != 0) m.indices.insert(m.indices.end(), {a, d, b});
      if (j != rings - 1) m.indices.insert(m.indices.end(), {b, d, c});
    }
  }
  return m;
}

Mesh make_quad(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, uint32_t material) {
  Mesh m;
  m.material = material;
  const Vec3 p[4] = {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v};
  const float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  for (int i = 0; i < 4; ++i) {
    m.positions.insert(m.positions.end(), {p[i].x, p[i].y, p[i].z});
    m.uvs.insert(m.uvs.end(), {uv[2 * i], uv[2 * i + 1]});
  }
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Mesh make_box(const Vec3& lo, const Vec3& hi, uint32_t material) {
  const Vec3 d = hi - lo;
  const Vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  Mesh box;
  box.material = material;
  // Each face: corner and two edges ordered so that cross(edge_u, edge_v) points outwards.
  append_mesh(box, make_quad(lo, ey, ex, material));                  // -z
  append_mesh(box, make_quad(lo + ez, ex, ey, material));             // +z
  append_mesh(box, make_quad(lo, ex, ez, material));                  // -y
  append_mesh(box, make_quad(lo + ey, ez, ex, material));             // +y
  append_mesh(box, make_quad(lo, ez, ey, material));                  // -x
  append_mesh(box, make_quad(lo + ex, ey, ez, material));             // +x
  return box;
}

void append_mesh(Mesh& a, const Mesh& b) {
  const uint32_t base = static_cast<uint32_t>(a.num_vertices());
  const bool a_empty = a.indices.empty();
  // Per-triangle materials once the two parts may differ.
  if (!a_empty && a.material_indices.empty())
    a.material_indices.assign(a.num_triangles(), a.material);
  // Normals and UVs survive only if both parts have them.
  const bool keep_normals = (a_empty || !a.normals.empty()) && !b.normals.empty();
  const bool keep_uvs = (a_empty || !a.uvs.empty()) && !b.uvs.empty();
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  if (keep_normals) a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  else a.normals.clear();
  if (keep_uvs) a.uvs.insert(a.uvs.end(), b.uvs.begin(), b.uvs.end());
  else a.uvs.clear();
  for (uint32_t idx : b.indices) a.indices.push_back(base + idx);
  if (a_empty) {
    a.material = b.material;
    a.material_indices = b.material_indices;
  } else if (b.material_indices.empty()) {
    a.material_indices.insert(a.material_indices.end(), b.num_triangles(), b.material);
  } else {
    a.material_indices.insert(a.material_indices.end(), b.material_indices.begin(),
                              b.material_indices.end());
  }
}

}  // namespace bxdf::render

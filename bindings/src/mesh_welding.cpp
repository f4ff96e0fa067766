#include "mesh_welding.h"

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "bxdf/render/recycled_buffers.h"

namespace bxdf::python {

namespace {

// Rows a and b of a width-column array hold the same numbers (bitwise, so -0 and NaN do not merge).
bool same_values(const float* rows, int32_t a, int32_t b, int width) {
  return a >= 0 && b >= 0 &&
         std::memcmp(rows + size_t(width) * size_t(a), rows + size_t(width) * size_t(b), sizeof(float) * size_t(width)) == 0;
}

// Whether an attribute's corners index it exactly as they index the positions (or it is absent).
bool indexed_like_positions(const int32_t* attribute_indices, const int32_t* triangles, size_t corners) {
  return !attribute_indices || attribute_indices == triangles ||
         std::memcmp(attribute_indices, triangles, corners * sizeof(int32_t)) == 0;
}

// Whether some corner uses each position (welding leaves out the ones none uses).
bool uses_every_position(const IndexedMeshArrays& in) {
  std::vector<uint8_t> used(in.num_positions, 0);
  size_t count = 0;
  for (size_t c = 0; c < 3 * in.num_triangles; ++c) {
    uint8_t& u = used[size_t(in.triangles[c])];
    count += u ^ 1u;
    u = 1;
  }
  return count == in.num_positions;
}

// The mesh as given, each array copied once: what welding makes of a mesh with nothing to split,
// but for the order of the vertices (no image depends on it).
render::Mesh copied_as_is(const IndexedMeshArrays& in) {
  render::Mesh out;
  const size_t nv = in.num_positions, corners = 3 * in.num_triangles;
  // Into the buffers of the last scene where they fit (recycled_buffers.h).
  using render::recycled::copied;
  out.positions = copied<float>(in.positions, 3 * nv, 3 * nv + 1);  // + the padding float
  if (in.normals && in.normal_indices) out.normals = copied<float>(in.normals, 3 * nv, 3 * nv);
  if (in.uvs && in.uv_indices) out.uvs = copied<float>(in.uvs, 2 * nv, 2 * nv);
  out.indices = copied<uint32_t>(in.triangles, corners, corners);  // validated: all >= 0
  if (in.material_indices)
    out.material_indices =
        copied<uint32_t>(in.material_indices, in.num_triangles, in.num_triangles);
  return out;
}

}  // namespace

render::Mesh weld_corners(const IndexedMeshArrays& in) {
  // Blender's smooth meshes without UVs (most of a scene's triangles, often) have their normals
  // indexed by position: nothing to split, and the per-corner search and its bookkeeping arrays
  // (fresh memory to fault in) are skipped.
  const size_t corners = 3 * in.num_triangles;
  if (indexed_like_positions(in.normals ? in.normal_indices : nullptr, in.triangles, corners) &&
      indexed_like_positions(in.uvs ? in.uv_indices : nullptr, in.triangles, corners) && uses_every_position(in))
    return copied_as_is(in);
  render::Mesh out;
  const bool has_normals = in.normals && in.normal_indices;
  const bool has_uvs = in.uvs && in.uv_indices;
  out.indices = render::recycled::indices(corners);
  out.indices.resize(corners);
  if (in.material_indices)
    out.material_indices =
        render::recycled::copied<uint32_t>(in.material_indices, in.num_triangles, in.num_triangles);

  // Output vertex → (position, normal, uv) indices; per position, the head of its split list.
  // 32-bit, as the input indices are: fewer bytes to allocate and touch per corner.
  std::vector<int32_t> head(in.num_positions, -1), next, src_p, src_n, src_uv;
  next.reserve(in.num_positions);
  src_p.reserve(in.num_positions);
  for (size_t c = 0; c < corners; ++c) {
    const int32_t p = in.triangles[c];
    const int32_t n = has_normals ? in.normal_indices[c] : -1;
    const int32_t t = has_uvs ? in.uv_indices[c] : -1;
    int32_t found = -1;
    int depth = 0;
    for (int32_t o = head[size_t(p)]; o >= 0 && depth < kMaxSplitSearch; o = next[size_t(o)], ++depth) {
      // Equal values count as equal attributes: Blender gives every corner its own UV and
      // split-normal index even where the values agree, and those corners should share a vertex.
      const bool same_normal = src_n[size_t(o)] == n || same_values(in.normals, src_n[size_t(o)], n, 3);
      const bool same_uv = src_uv[size_t(o)] == t || same_values(in.uvs, src_uv[size_t(o)], t, 2);
      if (same_normal && same_uv) {
        found = o;
        break;
      }
    }
    if (found < 0) {
      found = static_cast<int32_t>(src_p.size());
      src_p.push_back(p);
      src_n.push_back(n);
      src_uv.push_back(t);
      next.push_back(head[size_t(p)]);
      head[size_t(p)] = found;
    }
    out.indices[c] = static_cast<uint32_t>(found);
  }

  const size_t nv = src_p.size();
  out.positions = render::recycled::floats(3 * nv + 1);  // + the renderer's padding float
  out.positions.resize(3 * nv);
  if (has_normals) {
    out.normals = render::recycled::floats(3 * nv);
    out.normals.resize(3 * nv);
  }
  if (has_uvs) {
    out.uvs = render::recycled::floats(2 * nv);
    out.uvs.resize(2 * nv);
  }
  for (size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) out.positions[3 * v + k] = in.positions[3 * size_t(src_p[v]) + k];
    if (has_normals)
      for (int k = 0; k < 3; ++k) out.normals[3 * v + k] = in.normals[3 * size_t(src_n[v]) + k];
    if (has_uvs)
      for (int k = 0; k < 2; ++k) out.uvs[2 * v + k] = in.uvs[2 * size_t(src_uv[v]) + k];
  }
  return out;
}

render::Mesh transformed(render::Mesh mesh, const std::array<double, 16>& m) {
  // In place: a mesh placed once (the usual case) is moved in, so its arrays are neither copied
  // nor allocated twice (fresh memory costs a page fault per 4 KB, which dominated the
  // conversion of the harness scenes inside Blender).
  mesh.object_to_world.resize(12);
  for (int i = 0; i < 12; ++i) mesh.object_to_world[size_t(i)] = static_cast<float>(m[size_t(i)]);

  const size_t nv = mesh.num_vertices();
  mesh.positions.reserve(3 * nv + 1);  // room for the renderer's padding float
  for (size_t v = 0; v < nv; ++v) {
    const double x = mesh.positions[3 * v], y = mesh.positions[3 * v + 1], z = mesh.positions[3 * v + 2];
    for (int r = 0; r < 3; ++r)
      mesh.positions[3 * v + r] = static_cast<float>(m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]);
  }

  // Cofactor matrix of the 3×3 part = det · (A⁻¹)ᵀ: the normal transform up to scale.
  auto a = [&](int r, int c) { return m[4 * r + c]; };
  double cof[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      cof[r][c] = a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1);
    }
  const double det = a(0, 0) * cof[0][0] + a(0, 1) * cof[0][1] + a(0, 2) * cof[0][2];

  if (det < 0.0) {
    // A mirror turns counter-clockwise into clockwise; swapping two corners restores the front.
    for (size_t t = 0; t < mesh.num_triangles(); ++t) std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
    // Per-corner attributes follow their corners.
    auto swap_corners = [&](std::vector<float>& a, size_t width) {
      for (size_t t = 0; t < mesh.num_triangles(); ++t)
        for (size_t c = 0; c < width; ++c) std::swap(a[(3 * t + 1) * width + c], a[(3 * t + 2) * width + c]);
    };
    for (auto& uv : mesh.uv_maps) swap_corners(uv, 2);
    for (auto& t : mesh.tangents)
      if (!t.empty()) swap_corners(t, 4);
  }
  // Tangents are directions on the surface: moved by the linear part. A mirror flips the
  // bitangent (cross(A n, A t) = −A (n × t) for an orthogonal A with det < 0).
  for (auto& t : mesh.tangents)
    for (size_t c = 0; c < t.size() / 4; ++c) {
      const double x = t[4 * c], y = t[4 * c + 1], z = t[4 * c + 2];
      for (int r = 0; r < 3; ++r)
        t[4 * c + size_t(r)] = static_cast<float>(a(r, 0) * x + a(r, 1) * y + a(r, 2) * z);
      if (det < 0.0) t[4 * c + 3] = -t[4 * c + 3];
    }
  if (det == 0.0) {
    mesh.normals.clear();  // no normal transform: shading falls back to the face normals
  } else if (!mesh.normals.empty()) {
    const double sign = det > 0.0 ? 1.0 : -1.0;
    for (size_t v = 0; v < nv; ++v) {
      const double x = mesh.normals[3 * v], y = mesh.normals[3 * v + 1], z = mesh.normals[3 * v + 2];
      double n[3];
      for (int r = 0; r < 3; ++r) n[r] = sign * (cof[r][0] * x + cof[r][1] * y + cof[r][2] * z);
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double inv = len > 0.0 ? 1.0 / len : 0.0;
      for (int r = 0; r < 3; ++r) mesh.normals[3 * v + r] = static_cast<float>(n[r] * inv);
    }
  }
  return mesh;
}

}  // namespace bxdf::python

// Triangle meshes as the renderer takes them: flat arrays, so that a caller (the JSON reader,
// the shape generators, a numpy binding) can hand over its buffers without conversion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bxdf::render {

// Ray visibility of a mesh (Blender's object ray visibility; shadow = visible_shadow).
struct MeshVisibility {
  bool camera = true;
  bool shadow = true;
};

// Cycles' shadow terminator settings of the mesh's object (Blender: object.cycles).
struct TerminatorOffsets {
  float geometry = 0.1f;  // shadow_terminator_geometry_offset, [0, 1]
  float shading = 0.0f;   // shadow_terminator_offset, [0, 1)
};

// Non-owning view of one mesh. Scene::add_mesh copies what it needs, so the arrays only have to
// live for the duration of that call (a binding can pass numpy buffers with the GIL held).
struct MeshView {
  const float* positions = nullptr;  // (num_vertices, 3), world space
  size_t num_vertices = 0;
  const float* normals = nullptr;    // (num_vertices, 3) smooth normals, or null (flat shading)
  const float* uvs = nullptr;        // (num_vertices, 2), or null
  const uint32_t* indices = nullptr; // (num_triangles, 3), counter-clockwise = front
  size_t num_triangles = 0;
  const uint32_t* material_indices = nullptr;  // (num_triangles,) or null: all use `material`
  uint32_t material = 0;
  MeshVisibility visibility;
  TerminatorOffsets terminator;
};

// An owning mesh, for meshes the renderer builds or loads itself.
struct Mesh {
  std::vector<float> positions, normals, uvs;
  std::vector<uint32_t> indices, material_indices;
  uint32_t material = 0;
  MeshVisibility visibility;
  TerminatorOffsets terminator;

  size_t num_vertices() const { return positions.size() / 3; }
  size_t num_triangles() const { return indices.size() / 3; }
  MeshView view() const {
    MeshView v;
    v.positions = positions.data();
    v.num_vertices = num_vertices();
    v.normals = normals.empty() ? nullptr : normals.data();
    v.uvs = uvs.empty() ? nullptr : uvs.data();
    v.indices = indices.data();
    v.num_triangles = num_triangles();
    v.material_indices = material_indices.empty() ? nullptr : material_indices.data();
    v.material = material;
    v.visibility = visibility;
    v.terminator = terminator;
    return v;
  }
};

}  // namespace bxdf::render

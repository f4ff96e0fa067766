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

  // Attributes material graphs read (all optional). UV maps per triangle corner, each
  // (num_triangles * 3, 2); map 0 is the active render map (without uv_maps, `uvs` is map 0).
  const float* const* uv_maps = nullptr;
  size_t num_uv_maps = 0;
  // Per UV map (num_uv_maps entries, each may be null): per-corner tangents (x, y, z, sign),
  // (num_triangles * 3, 4), world space (Blender's MikkTSpace calc_tangents, transformed).
  const float* const* tangents = nullptr;
  // Object → world, 3×4 row-major; null: identity. Object coordinates are world positions
  // taken back through it.
  const float* object_to_world = nullptr;
  // Texture space (location, size: 6 floats, object space) for Generated coordinates; null:
  // the object-space bounding box (Blender's automatic texture space).
  const float* texture_space = nullptr;
  MeshVisibility visibility;
  TerminatorOffsets terminator;
};

// An owning mesh, for meshes the renderer builds or loads itself.
struct Mesh {
  std::vector<float> positions, normals, uvs;
  std::vector<uint32_t> indices, material_indices;
  uint32_t material = 0;
  std::vector<std::vector<float>> uv_maps, tangents;  // as in MeshView (a tangent entry may be empty)
  std::vector<float> object_to_world, texture_space;  // empty: as null in MeshView
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
    uv_map_pointers_.clear();
    tangent_pointers_.clear();
    for (const auto& m : uv_maps) uv_map_pointers_.push_back(m.data());
    for (const auto& t : tangents) tangent_pointers_.push_back(t.empty() ? nullptr : t.data());
    v.uv_maps = uv_map_pointers_.empty() ? nullptr : uv_map_pointers_.data();
    v.num_uv_maps = uv_maps.size();
    v.tangents = tangent_pointers_.empty() ? nullptr : tangent_pointers_.data();
    v.object_to_world = object_to_world.empty() ? nullptr : object_to_world.data();
    v.texture_space = texture_space.empty() ? nullptr : texture_space.data();
    v.visibility = visibility;
    v.terminator = terminator;
    return v;
  }

 private:
  mutable std::vector<const float*> uv_map_pointers_, tangent_pointers_;
};

}  // namespace bxdf::render

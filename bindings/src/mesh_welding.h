// Meshes whose normals and UVs are indexed separately from the positions (as OBJ and Blender's
// export keep them) turned into the renderer's shared-index meshes, and instances flattened into
// world space. Pure C++ (no Python), so the binding can run it with the GIL released.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "bxdf/render/mesh.h"

namespace bxdf::python {

// Borrowed arrays of one separately-indexed mesh, all validated by the caller (indices in range).
struct IndexedMeshArrays {
  const float* positions = nullptr;  // (V, 3)
  size_t num_positions = 0;
  const int32_t* triangles = nullptr;  // (T, 3) into positions
  size_t num_triangles = 0;
  const float* normals = nullptr;        // (N, 3) or null
  const int32_t* normal_indices = nullptr;  // (T, 3) into normals, or null
  const float* uvs = nullptr;            // (U, 2) or null
  const int32_t* uv_indices = nullptr;   // (T, 3) into uvs, or null
  const uint32_t* material_indices = nullptr;  // (T,) scene material per triangle
};

// One renderer vertex per distinct (position, normal, uv) that the corners use (attributes
// compared by index, then by value), so a smooth mesh keeps its vertex count and only seams and
// flat faces split vertices. Linear time:
// each position keeps a short list of the splits made from it (searched at most
// kMaxSplitSearch deep, beyond which a corner gets its own vertex: still correct, just larger).
render::Mesh weld_corners(const IndexedMeshArrays& in);
inline constexpr int kMaxSplitSearch = 16;

// The mesh moved to world space by the affine object→world matrix (row-major 4×4, last row
// 0 0 0 1): positions by the matrix, normals by its inverse transpose (renormalised). A mirroring
// matrix (negative determinant) reverses the winding so that the front stays the front; a
// singular one drops the normals (the flattened object is shaded flat). Taken by value: a mesh
// moved in is transformed in place.
render::Mesh transformed(render::Mesh mesh, const std::array<double, 16>& object_to_world);

}  // namespace bxdf::python

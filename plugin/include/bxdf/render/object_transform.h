// An object's affine placement (object → world and back), and how points, directions and normals
// move between the two spaces. Shared by meshes drawn where they are declared (whose object
// transform only serves object-space texture coordinates) and by instances of a mesh.
#pragma once

#include <array>

#include "bxdf/math.h"

namespace bxdf::render {

struct ObjectTransform {
  // 3×4 row-major affine matrices; identity by default.
  std::array<float, 12> to_world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::array<float, 12> to_object{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  // Negative determinant: the winding of object-space triangles is reversed in world space.
  bool mirrors = false;

  // From a 3×4 object → world matrix; false (and left unchanged) when it is singular.
  bool set(const float* object_to_world);

  Vec3 point_to_world(const Vec3& p) const { return affine(to_world, p); }
  Vec3 point_to_object(const Vec3& p) const { return affine(to_object, p); }
  Vec3 vector_to_world(const Vec3& v) const { return linear(to_world, v); }
  Vec3 vector_to_object(const Vec3& v) const { return linear(to_object, v); }
  // Normals move by the inverse transpose: (A⁻¹)ᵀ n to world, Aᵀ n to object (not normalised).
  Vec3 normal_to_world(const Vec3& n) const { return transposed(to_object, n); }
  Vec3 normal_to_object(const Vec3& n) const { return transposed(to_world, n); }

 private:
  static Vec3 affine(const std::array<float, 12>& m, const Vec3& p) {
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
            m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
  }
  static Vec3 linear(const std::array<float, 12>& m, const Vec3& v) {
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
            m[8] * v.x + m[9] * v.y + m[10] * v.z};
  }
  static Vec3 transposed(const std::array<float, 12>& m, const Vec3& n) {
    return {m[0] * n.x + m[4] * n.y + m[8] * n.z, m[1] * n.x + m[5] * n.y + m[9] * n.z,
            m[2] * n.x + m[6] * n.y + m[10] * n.z};
  }
};

}  // namespace bxdf::render

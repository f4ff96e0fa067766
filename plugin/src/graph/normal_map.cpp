// Normal Map in tangent space, as Cycles 3.4's svm_node_normal_map (svm/tex_coord.h).
#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

Vec3 normal_map_direction(const Vec3& color, const Vec3& tangent, float sign, const Vec3& normal) {
  const Vec3 c = (color - Vec3(0.5f, 0.5f, 0.5f)) * 2.0f;
  const Vec3 b = cross(normal, tangent) * sign;
  return tangent * c.x + b * c.y + normal * c.z;
}

Vec3 normal_map_finish(Vec3 n, float strength, const Vec3& shading_normal, bool backfacing) {
  // Cycles uses the normal before it is turned towards the viewer, then turns the result.
  if (backfacing) n = -n;
  if (strength != 1.0f) {
    const float s = std::max(strength, 0.0f);
    n = safe_normalize(shading_normal + (n - shading_normal) * s);
  }
  if (n == Vec3(0.0f, 0.0f, 0.0f)) n = shading_normal;
  return n;
}

Vec3 normal_map_tangent(const Vec3& color, float strength, const Vec3& tangent, float sign,
                        const Vec3& smooth_normal, const Vec3& shading_normal, bool backfacing) {
  const Vec3 n = safe_normalize(normal_map_direction(color, tangent, sign, smooth_normal));
  return normal_map_finish(n, strength, shading_normal, backfacing);
}

}  // namespace bxdf::render

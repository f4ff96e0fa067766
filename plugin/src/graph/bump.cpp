// Bump: Cycles 3.4's svm_node_set_bump (svm/displace.h). Cycles evaluates the height at P and
// at P + dP.dx, P + dP.dy, its ray differentials about the geometric normal; we evaluate it at
// offsets of a fixed small length (MaterialGraph::evaluate), so the gradient is the height's
// own slope rather than its average over a pixel's footprint.
#include <cmath>

#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

Vec3 bump_normal(const BumpInputs& in, const Vec3& ng, const Vec3& incoming) {
  const Vec3& n = in.normal;
  const Vec3 rx = cross(in.dpdy, n), ry = cross(n, in.dpdx);
  const float det = dot(in.dpdx, rx);
  const Vec3 surface_gradient = rx * (in.height_x - in.height) + ry * (in.height_y - in.height);
  const float scale = in.invert ? -in.distance : in.distance;
  const float sign_det = det > 0.0f ? 1.0f : (det < 0.0f ? -1.0f : 0.0f);
  Vec3 out = safe_normalize(n * std::fabs(det) - surface_gradient * (scale * sign_det));
  if (out == Vec3(0.0f, 0.0f, 0.0f)) {
    out = n;
  } else {
    const float strength = std::max(in.strength, 0.0f);
    out = safe_normalize(out * strength + n * (1.0f - strength));
    if (out == Vec3(0.0f, 0.0f, 0.0f)) out = n;
  }
  return ensure_valid_reflection(ng, incoming, out);
}

}  // namespace bxdf::render

// Cycles 3.4's ensure_valid_reflection (closure/bsdf_util.h): a perturbed normal is tilted
// towards the geometric one just enough that the mirror direction of the incoming ray stays
// above the surface.
#include <cmath>

#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& incoming, const Vec3& n) {
  const Vec3 r = n * (2.0f * dot(n, incoming)) - incoming;
  // Reflected rays may always be at least as shallow as the incoming ray.
  const float threshold = std::min(0.9f * dot(ng, incoming), 0.01f);
  if (dot(ng, r) >= threshold) return n;

  // Ng is the Z axis, N lies in the X-Z plane; solve for the N' whose reflection meets the
  // threshold (two candidates, both in the upper hemisphere).
  Vec3 x = n - ng * dot(n, ng);
  const float lx = length(x);
  if (!(lx > 0.0f)) return ng;
  x = x / lx;
  const float ix = dot(incoming, x), iz = dot(incoming, ng);
  const float ix2 = ix * ix, iz2 = iz * iz;
  const float a = ix2 + iz2;
  if (!(a > 0.0f)) return ng;
  const float b = std::sqrt(std::max(ix2 * (a - threshold * threshold), 0.0f));
  const float c = iz * threshold + a;
  const float fac = 0.5f / a;
  const float n1_z2 = fac * (b + c), n2_z2 = fac * (-b + c);
  bool valid1 = n1_z2 > 1e-5f && n1_z2 <= 1.0f + 1e-5f;
  bool valid2 = n2_z2 > 1e-5f && n2_z2 <= 1.0f + 1e-5f;
  auto root = [](float v) { return std::sqrt(std::max(v, 0.0f)); };
  float nx, nz;
  if (valid1 && valid2) {
    const float n1x = root(1.0f - n1_z2), n1z = root(n1_z2);
    const float n2x = root(1.0f - n2_z2), n2z = root(n2_z2);
    const float r1 = 2.0f * (n1x * ix + n1z * iz) * n1z - iz;
    const float r2 = 2.0f * (n2x * ix + n2z * iz) * n2z - iz;
    valid1 = r1 >= 1e-5f;
    valid2 = r2 >= 1e-5f;
    // Both valid: the shallower reflection, closer to the input; else the positive one.
    const bool first = valid1 && valid2 ? r1 < r2 : r1 > r2;
    nx = first ? n1x : n2x;
    nz = first ? n1z : n2z;
  } else if (valid1 || valid2) {
    const float z2 = valid1 ? n1_z2 : n2_z2;
    nx = root(1.0f - z2);
    nz = root(z2);
  } else {
    return ng;
  }
  return x * nx + ng * nz;
}

}  // namespace bxdf::render

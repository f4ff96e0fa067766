#include "bxdf/render/object_transform.h"

#include <cmath>

namespace bxdf::render {

bool ObjectTransform::set(const float* m) {
  // Inverted in double: object coordinates of far-off points keep their precision.
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
               k = m[10];
  const double det = a * (e * k - f * h) - b * (d * k - f * g) + c * (d * h - e * g);
  if (!(std::fabs(det) > 1e-30)) return false;
  const double inv[9] = {(e * k - f * h) / det, (c * h - b * k) / det, (b * f - c * e) / det,
                         (f * g - d * k) / det, (a * k - c * g) / det, (c * d - a * f) / det,
                         (d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det};
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) to_object[size_t(4 * r + col)] = float(inv[3 * r + col]);
    to_object[size_t(4 * r + 3)] =
        float(-(inv[3 * r] * m[3] + inv[3 * r + 1] * m[7] + inv[3 * r + 2] * m[11]));
  }
  for (size_t i = 0; i < 12; ++i) to_world[i] = m[i];
  mirrors = det < 0.0;
  return true;
}

}  // namespace bxdf::render

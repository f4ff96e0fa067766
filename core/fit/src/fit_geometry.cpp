#include "fit_geometry.h"

#include <algorithm>
#include <cmath>

namespace bxdf::fit {

std::vector<FitSample> prepare_samples(const std::vector<MeasuredSample>& samples) {
  std::vector<FitSample> out;
  out.reserve(samples.size());
  for (const MeasuredSample& m : samples) {
    const Vec3& wo = m.wo;
    const Vec3& wi = m.wi;
    if (!(wo.z > 1e-4f && wi.z > 1e-4f) || !finite_nonnegative(m.value)) continue;
    FitSample s;
    for (int c = 0; c < 3; ++c) s.ref[c] = m.value[c];
    s.cos_i = wi.z;
    s.dot_xy = double(wo.x) * wi.x + double(wo.y) * wi.y;
    s.dot_z = double(wo.z) * wi.z;
    const double hx = double(wo.x) + wi.x, hy = double(wo.y) + wi.y, hz = double(wo.z) + wi.z;
    const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    const double h[3] = {hx / hl, hy / hl, hz / hl};
    s.cos_h = h[2];
    const double r2 = h[0] * h[0] + h[1] * h[1];
    s.cos2_phi_h = r2 > 0.0 ? h[0] * h[0] / r2 : 1.0;
    s.tan2_h = r2 / (h[2] * h[2]);
    s.cos_d = std::clamp(h[0] * wi.x + h[1] * wi.y + h[2] * wi.z, 0.0, 1.0);
    const double cos_o = wo.z, cos_i = wi.z;
    s.inv_4cc = 1.0 / (4.0 * cos_i * cos_o);
    const double wo_h = h[0] * wo.x + h[1] * wo.y + h[2] * wo.z;
    s.g_vgroove = std::min({1.0, 2.0 * h[2] * cos_o / wo_h, 2.0 * h[2] * cos_i / wo_h});
    s.tan2_o = (1.0 - cos_o * cos_o) / (cos_o * cos_o);
    s.tan2_i = (1.0 - cos_i * cos_i) / (cos_i * cos_i);
    out.push_back(s);
  }
  return out;
}

}  // namespace bxdf::fit

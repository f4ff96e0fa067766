// Per-sample quantities that do not depend on the fitted parameters, computed once so that the
// templated (automatically differentiated) residuals only do the parameter-dependent work.
#pragma once

#include <vector>

#include "bxdf/measured/measured_data.h"

namespace bxdf::fit {

struct FitSample {
  double ref[3];     // measured BRDF
  double cos_i;      // weight: cos θi
  // Lafortune: the two terms of the generalised cosine.
  double dot_xy;     // wo.x wi.x + wo.y wi.y
  double dot_z;      // wo.z wi.z
  // Half-vector models.
  double cos_h;      // n · h
  double cos2_phi_h; // azimuth of h (Ashikhmin–Shirley)
  double tan2_h;     // tan² θh
  double cos_d;      // wi · h (Fresnel)
  double inv_4cc;    // 1 / (4 cos θi cos θo)
  double g_vgroove;  // Torrance–Sparrow V-groove shadowing
  double tan2_o, tan2_i;  // for Smith Λ
};

std::vector<FitSample> prepare_samples(const std::vector<MeasuredSample>& samples);

}  // namespace bxdf::fit

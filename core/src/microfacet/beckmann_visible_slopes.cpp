// Slopes of the Beckmann normals visible from a direction, at unit roughness (Heitz and d'Eon
// 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution of Visible
// Normals"). The x slope inverts the CDF of the visible slopes numerically, in the erf domain,
// by Newton steps kept inside a bisection interval (Jakob's inversion in Mitsuba, which unlike
// the paper's fitted inverse is continuous in u: stratified points stay stratified). The y
// slope is a plain Gaussian, independent of x.
#include <algorithm>
#include <cmath>

#include "bxdf/microfacet/beckmann.h"

namespace bxdf {
namespace microfacet {

namespace {

// The inverse error function in single precision (Giles 2010, "Approximating the erfinv
// function"): relative error below 4e-7 on (−1, 1).
float erfinv(float x) {
  float w = -std::log((1.0f - x) * (1.0f + x));
  float p;
  if (w < 5.0f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

}  // namespace

void beckmann_visible_slopes(float cos_theta, float sin_theta, Point2 u, float* slope_x,
                             float* slope_y) {
  // Away from 0 and 1, where erfinv is infinite.
  const float u1 = std::clamp(u.x, 1e-6f, 1.0f - 1e-6f);
  const float u2 = std::clamp(u.y, 1e-6f, 1.0f - 1e-6f);
  const float theta = std::acos(std::clamp(cos_theta, -1.0f, 1.0f));
  if (theta < 1e-4f) {
    // Seen from the normal, every normal is visible: the slope's radius² is exponential.
    const float r = std::sqrt(-std::log(1.0f - u1));
    const float phi = 2.0f * kPi * u2;
    *slope_x = r * std::cos(phi);
    *slope_y = r * std::sin(phi);
    return;
  }
  const float tan_theta = sin_theta / cos_theta;
  const float cot_theta = cos_theta / sin_theta;
  // The search interval of b = erf(slope_x): slopes the direction can see lie below cot θ.
  float lo = -1.0f, hi = std::erf(cot_theta);
  // Initial guess: the inverse of a fit of the CDF (Jakob), then Newton steps.
  const float fit = 1.0f + theta * (-0.876f + theta * (0.4265f - 0.0594f * theta));
  float b = hi - (1.0f + hi) * std::pow(1.0f - u1, fit);
  const float normalization =
      1.0f / (1.0f + hi + kInvSqrtPi * tan_theta * std::exp(-cot_theta * cot_theta));
  for (int it = 0; it < 10; ++it) {
    if (!(b >= lo && b <= hi)) b = 0.5f * (lo + hi);  // also catches NaN
    const float x = erfinv(b);
    const float cdf = normalization * (1.0f + b + kInvSqrtPi * tan_theta * std::exp(-x * x)) - u1;
    if (std::fabs(cdf) < 1e-6f) break;
    if (cdf > 0.0f) hi = b;
    else lo = b;
    const float density = normalization * (1.0f - x * tan_theta);
    b -= cdf / density;
  }
  *slope_x = erfinv(std::clamp(b, -1.0f + 1e-7f, 1.0f - 1e-7f));
  *slope_y = erfinv(2.0f * u2 - 1.0f);
}

}  // namespace microfacet
}  // namespace bxdf

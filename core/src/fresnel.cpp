#include "bxdf/fresnel.h"

#include <cmath>

namespace bxdf {

float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
  if (!std::isfinite(cos_i)) return 0.0f;
  cos_i = clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0.0f) {  // arriving from the eta_t side
    std::swap(eta_i, eta_t);
    cos_i = -cos_i;
  }
  const float sin_i = safe_sqrt(1.0f - cos_i * cos_i);
  const float sin_t = eta_i / eta_t * sin_i;
  if (sin_t >= 1.0f) return 1.0f;  // total internal reflection
  const float cos_t = safe_sqrt(1.0f - sin_t * sin_t);
  const float r_par = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  const float r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const float f = 0.5f * (r_par * r_par + r_perp * r_perp);
  return std::isfinite(f) ? clamp(f, 0.0f, 1.0f) : 1.0f;  // 0/0 only at cos_i = 0: grazing
}

float fresnel_conductor_seed(float cos_i, float eta, float k) {
  if (!std::isfinite(cos_i)) return 0.0f;
  const float c = std::min(std::fabs(cos_i), 1.0f);
  const float c2 = c * c;
  const float ek = eta * eta + k * k;
  const float two_eta_c = 2.0f * eta * c;
  const float r_par2 = (ek * c2 - two_eta_c + 1.0f) / (ek * c2 + two_eta_c + 1.0f);
  const float r_perp2 = (ek - two_eta_c + c2) / (ek + two_eta_c + c2);
  return clamp(0.5f * (r_par2 + r_perp2), 0.0f, 1.0f);
}

RGB fresnel_conductor_seed(float cos_i, const RGB& eta, const RGB& k) {
  return {fresnel_conductor_seed(cos_i, eta.r, k.r), fresnel_conductor_seed(cos_i, eta.g, k.g),
          fresnel_conductor_seed(cos_i, eta.b, k.b)};
}

float fresnel_conductor_exact(float cos_i, float eta_i, float eta_in, float k_in) {
  if (!std::isfinite(cos_i)) return 0.0f;
  const float c = std::min(std::fabs(cos_i), 1.0f);
  const float eta = eta_in / eta_i, eta_k = k_in / eta_i;
  const float c2 = c * c;
  const float s2 = 1.0f - c2;
  const float eta2 = eta * eta, eta_k2 = eta_k * eta_k;
  const float t0 = eta2 - eta_k2 - s2;
  const float a2b2 = std::sqrt(t0 * t0 + 4.0f * eta2 * eta_k2);
  const float a = safe_sqrt(0.5f * (a2b2 + t0));
  const float t1 = a2b2 + c2;
  const float t2 = 2.0f * a * c;
  const float rs = (t1 - t2) / (t1 + t2);
  const float t3 = c2 * a2b2 + s2 * s2;
  const float t4 = t2 * s2;
  const float rp = rs * (t3 - t4) / (t3 + t4);
  const float f = 0.5f * (rs + rp);
  return std::isfinite(f) ? clamp(f, 0.0f, 1.0f) : 1.0f;
}

RGB fresnel_conductor_exact(float cos_i, float eta_i, const RGB& eta, const RGB& k) {
  return {fresnel_conductor_exact(cos_i, eta_i, eta.r, k.r),
          fresnel_conductor_exact(cos_i, eta_i, eta.g, k.g),
          fresnel_conductor_exact(cos_i, eta_i, eta.b, k.b)};
}

float eta_from_f0(float f0) {
  const float s = std::sqrt(clamp(f0, 0.0f, 0.999999f));
  return (1.0f + s) / (1.0f - s);
}

float k_from_f0(float f0) {
  const float f = clamp(f0, 0.0f, 0.999999f);
  return 2.0f * std::sqrt(f / (1.0f - f));
}

}  // namespace bxdf

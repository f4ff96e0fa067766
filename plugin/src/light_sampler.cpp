#include "bxdf/render/light_sampler.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "bxdf/render/cdf_search.h"

namespace bxdf::render {

namespace {

// A local light's bounding sphere (centre, radius), its emitting normal and whether it emits
// to that side only.
struct Bounds {
  Vec3 centre;
  float radius = 0.0f;
  Vec3 normal{0, 0, 1};
  bool one_sided = false;
};

Bounds bounds_of(const Light& light) {
  Bounds b;
  b.centre = light.position;
  switch (light.type) {
    case LightType::Point:
    case LightType::Spot: b.radius = light.radius; break;
    case LightType::Area:
      // Its corners (the rectangle's; the disk's and ellipse's bounding rectangle).
      b.radius = 0.5f * std::sqrt(length_squared(light.axis_u) + length_squared(light.axis_v));
      b.normal = light.direction;
      b.one_sided = true;
      break;
    case LightType::Mesh: {
      // The emissive triangles' bounding box; they emit to both sides.
      const float inf = std::numeric_limits<float>::infinity();
      Vec3 lo(inf, inf, inf), hi(-inf, -inf, -inf);
      for (const EmissiveTriangle& t : light.triangles)
        for (const Vec3& q : {t.p0, t.p0 + t.e1, t.p0 + t.e2}) {
          lo = Vec3(std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z));
          hi = Vec3(std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z));
        }
      if (!(hi.x >= lo.x)) break;
      b.centre = (lo + hi) * 0.5f;
      b.radius = 0.5f * length(hi - lo);
      break;
    }
    case LightType::Sun: break;
  }
  return b;
}

}  // namespace

LightSampler::LightSampler(const std::vector<Light>& lights, const Environment* world,
                           float scene_radius) {
  std::vector<float> power;
  for (const Light& l : lights) power.push_back(light_power(l, scene_radius));
  if (world && world->importance_sampled()) power.push_back(world->power(scene_radius));
  if (power.empty()) return;
  double total = 0.0;
  for (float& p : power) {
    if (!(p > 0.0f) || !std::isfinite(p)) p = 0.0f;
    total += p;
  }
  if (!(total > 0.0)) {
    std::fill(power.begin(), power.end(), 1.0f);
    total = static_cast<double>(power.size());
  }
  double running = 0.0;
  for (float p : power) {
    pmf_.push_back(static_cast<float>(p / total));
    running += p / total;
    cdf_.push_back(static_cast<float>(running));
  }
  cdf_.back() = 1.0f;

  // The local lights with a share to split, each with its bounds.
  std::vector<size_t> local;
  double local_share = 0.0;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].type == LightType::Sun || !(pmf_[i] > 0.0f)) continue;
    local.push_back(i);
    local_share += pmf_[i];
  }
  if (local.size() < 2 || local.size() > size_t(kMaxSpatialLights)) return;
  local_of_.assign(pmf_.size(), -1);
  for (size_t i : local) {
    const Bounds b = bounds_of(lights[i]);
    const int k = local_.count++;
    local_of_[i] = k;
    local_.cx[size_t(k)] = b.centre.x;
    local_.cy[size_t(k)] = b.centre.y;
    local_.cz[size_t(k)] = b.centre.z;
    local_.radius[size_t(k)] = b.radius;
    local_.nx[size_t(k)] = b.normal.x;
    local_.ny[size_t(k)] = b.normal.y;
    local_.nz[size_t(k)] = b.normal.z;
    local_.one_sided[size_t(k)] = b.one_sided ? 1.0f : 0.0f;
    local_.power[size_t(k)] = power[i];
  }
  local_share_ = static_cast<float>(local_share);
}

void LightSampler::evaluate4(const LocalLights& l, int k, const LightReceiver& r,
                             float* importance, float* reaching_power) {
  const auto load = [k](const std::array<float, kMaxSpatialLights>& a) {
    return _mm_load_ps(a.data() + k);
  };
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 tx = _mm_sub_ps(load(l.cx), _mm_set1_ps(r.p.x));
  const __m128 ty = _mm_sub_ps(load(l.cy), _mm_set1_ps(r.p.y));
  const __m128 tz = _mm_sub_ps(load(l.cz), _mm_set1_ps(r.p.z));
  const __m128 one_sided = load(l.one_sided), radius = load(l.radius), power = load(l.power);
  // > 0: r is behind the light's emitting side (what sample_light() gives nothing for).
  const __m128 facing =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(load(l.nx), tx), _mm_mul_ps(load(l.ny), ty)),
                 _mm_mul_ps(load(l.nz), tz));
  const __m128 behind = _mm_and_ps(_mm_cmpgt_ps(one_sided, zero), _mm_cmpgt_ps(facing, zero));
  // The cosines at either end, each raised by the sine of the half-angle θr the bounding
  // sphere subtends (cos θ + sin θr ≥ cos(θ − θr), the best cosine over the sphere, for the
  // angles that matter), over the squared distance; inside the sphere, as at its surface.
  const __m128 length2 =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(tx, tx), _mm_mul_ps(ty, ty)), _mm_mul_ps(tz, tz));
  const __m128 d2 =
      _mm_max_ps(_mm_max_ps(length2, _mm_mul_ps(radius, radius)), _mm_set1_ps(1e-12f));
  const __m128 inv_d = _mm_div_ps(one, _mm_sqrt_ps(d2));
  const __m128 sin_r = _mm_min_ps(_mm_mul_ps(radius, inv_d), one);
  __m128 c = _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(r.n.x), tx),
                                              _mm_mul_ps(_mm_set1_ps(r.n.y), ty)),
                                   _mm_mul_ps(_mm_set1_ps(r.n.z), tz)),
                        inv_d);
  if (r.two_sided) c = _mm_andnot_ps(_mm_set1_ps(-0.0f), c);
  const __m128 receiver = _mm_min_ps(_mm_max_ps(_mm_add_ps(c, sin_r), zero), one);
  const __m128 emitted =
      _mm_min_ps(_mm_max_ps(_mm_sub_ps(sin_r, _mm_mul_ps(facing, inv_d)), zero), one);
  const __m128 emitter = _mm_max_ps(emitted, _mm_sub_ps(one, one_sided));  // 1: two-sided
  const __m128 value = _mm_min_ps(
      _mm_mul_ps(_mm_mul_ps(_mm_mul_ps(power, receiver), emitter), _mm_mul_ps(inv_d, inv_d)),
      _mm_set1_ps(1e30f));
  // Where it cannot reach r, or the value is not positive (a NaN normal), 0.
  const __m128 keep = _mm_andnot_ps(behind, _mm_cmpgt_ps(value, zero));
  _mm_store_ps(importance, _mm_and_ps(keep, value));
  _mm_store_ps(reaching_power, _mm_andnot_ps(behind, power));
}

void LightSampler::normalise(LightReceiver& r, float* importance, float* reaching_power) const {
  for (int k = 0; k < local_.count; k += 4)
    evaluate4(local_, k, r, importance + k, reaching_power + k);
  float importance_sum = 0.0f, power_sum = 0.0f;
  for (int k = 0; k < local_.count; ++k) {
    importance_sum += importance[k];
    power_sum += reaching_power[k];
  }
  r.normalised = true;
  r.scale = 1.0f;
  if (power_sum > 0.0f && std::isfinite(power_sum)) {
    const bool by_importance = importance_sum > 0.0f && std::isfinite(importance_sum);
    r.importance_factor = by_importance ? (1.0f - kPowerShare) / importance_sum : 0.0f;
    r.power_factor = (by_importance ? kPowerShare : 1.0f) / power_sum;
  } else {
    // No local light reaches r (each is one-sided, r behind it): the other entries share
    // everything, or nothing is picked.
    r.importance_factor = 0.0f;
    r.power_factor = 0.0f;
    r.scale = local_share_ < 1.0f ? 1.0f / (1.0f - local_share_) : 0.0f;
  }
}

size_t LightSampler::sample(float u, float* probability, float* remapped) const {
  if (pmf_.size() == 1 && pmf_[0] == 1.0f) {
    // One light (or the world alone): what the search below gives, (u − 0) / 1 being u.
    *probability = 1.0f;
    if (remapped) *remapped = into_unit_interval(u);
    return 0;
  }
  const size_t i = std::min(first_above(cdf_, u), pmf_.size() - 1);
  *probability = pmf_[i];
  if (remapped) {
    // A picked light has pmf > 0 (first_above passes over empty intervals).
    const float lo = i == 0 ? 0.0f : cdf_[i - 1];
    *remapped = into_unit_interval((u - lo) / pmf_[i]);
  }
  return i;
}

size_t LightSampler::sample(LightReceiver& r, float u, float* probability,
                            float* remapped) const {
  if (local_.count == 0) return sample(u, probability, remapped);
  alignas(16) std::array<float, kMaxSpatialLights> importance, reaching_power;
  normalise(r, importance.data(), reaching_power.data());
  // The first entry whose interval holds u; past the (rounded) last interval, the last entry
  // with a positive probability.
  size_t picked = pmf_.size();
  float lo = 0.0f, p = 0.0f;
  for (size_t i = 0; i < pmf_.size(); ++i) {
    const int k = local_of_[i];
    const float q =
        (k < 0 ? pmf_[i] : local_probability(r, importance[size_t(k)], reaching_power[size_t(k)])) *
        r.scale;
    if (!(q > 0.0f)) continue;
    if (picked != pmf_.size()) lo += p;  // past the previous positive entry
    picked = i;
    p = q;
    if (u < lo + q) break;
  }
  if (picked == pmf_.size()) {  // nothing to pick
    *probability = 0.0f;
    if (remapped) *remapped = 0.0f;
    return picked;
  }
  *probability = p;
  if (remapped) *remapped = into_unit_interval((u - lo) / p);
  return picked;
}

float LightSampler::probability(const LightReceiver& r, size_t index) const {
  if (index >= pmf_.size()) return 0.0f;
  if (local_.count == 0) return pmf_[index];
  LightReceiver at = r;
  const int k = local_of_[index];
  if (!at.normalised) {
    alignas(16) std::array<float, kMaxSpatialLights> importance, reaching_power;
    normalise(at, importance.data(), reaching_power.data());
    if (k < 0) return pmf_[index] * at.scale;
    return local_probability(at, importance[size_t(k)], reaching_power[size_t(k)]) * at.scale;
  }
  if (k < 0) return pmf_[index] * at.scale;
  alignas(16) float importance[4], reaching_power[4];
  evaluate4(local_, k & ~3, at, importance, reaching_power);
  return local_probability(at, importance[k & 3], reaching_power[k & 3]) * at.scale;
}

}  // namespace bxdf::render

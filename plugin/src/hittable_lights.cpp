#include "bxdf/render/hittable_lights.h"

#include <immintrin.h>

namespace bxdf::render {

HittableLights::HittableLights(const std::vector<Light>& lights) {
  size_t n = 0;  // hittable lights so far
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    if (!light.is_hittable()) continue;
    const size_t k = n++ % 4;
    if (k == 0) groups_.emplace_back();
    Group& g = groups_.back();
    const unsigned bit = 1u << k;
    g.index[k] = static_cast<uint32_t>(i);
    if (light.visibility.camera) g.camera_mask |= bit;
    if (light.visibility.use_mis) g.mis_mask |= bit;
    if (light.type != LightType::Area) {
      g.untested_mask |= bit;
      continue;
    }
    g.cx[k] = light.position.x;
    g.cy[k] = light.position.y;
    g.cz[k] = light.position.z;
    g.nx[k] = light.direction.x;
    g.ny[k] = light.direction.y;
    g.nz[k] = light.direction.z;
    // intersect_light()'s coordinates across the light, 2 (q·axis) / |axis|², as one product.
    const Vec3 u = light.axis_u * (2.0f / length_squared(light.axis_u));
    const Vec3 v = light.axis_v * (2.0f / length_squared(light.axis_v));
    g.ux[k] = u.x;
    g.uy[k] = u.y;
    g.uz[k] = u.z;
    g.vx[k] = v.x;
    g.vy[k] = v.y;
    g.vz[k] = v.z;
  }
}

unsigned HittableLights::crossing_mask(const Group& g, const Vec3& origin, const Vec3& dir,
                                       float tmax) {
  const auto dot4 = [](__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
  };
  const __m128 dx = _mm_set1_ps(dir.x), dy = _mm_set1_ps(dir.y), dz = _mm_set1_ps(dir.z);
  const __m128 nx = _mm_load_ps(g.nx), ny = _mm_load_ps(g.ny), nz = _mm_load_ps(g.nz);
  // From the light's centre to the origin.
  const __m128 ox = _mm_sub_ps(_mm_set1_ps(origin.x), _mm_load_ps(g.cx));
  const __m128 oy = _mm_sub_ps(_mm_set1_ps(origin.y), _mm_load_ps(g.cy));
  const __m128 oz = _mm_sub_ps(_mm_set1_ps(origin.z), _mm_load_ps(g.cz));
  // The ray meets the plane at t = h / c, with c = dir·n and h = (centre − origin)·n. Without
  // the division (whose latency the test waited on): a one-sided light is met in front when
  // c < 0, at t > 0 when h < 0, and before tmax when h > tmax·c, taken a little wider than
  // intersect_light()'s rounded t < tmax (also when tmax is infinite). Unused entries (a zero
  // normal) give c = 0.
  const __m128 zero = _mm_setzero_ps();
  const __m128 c = dot4(dx, dy, dz, nx, ny, nz);
  const __m128 h = _mm_sub_ps(zero, dot4(ox, oy, oz, nx, ny, nz));
  const __m128 before_tmax = _mm_cmpgt_ps(h, _mm_mul_ps(_mm_set1_ps(tmax * (1.0f + 1e-5f)), c));
  const __m128 ahead =
      _mm_and_ps(_mm_and_ps(_mm_cmplt_ps(c, zero), _mm_cmplt_ps(h, zero)), before_tmax);
  // The crossing's coordinates across the light times c: (origin − centre)·a c + h (dir·a)
  // for a = u, v, within ±c by a margin that the rounding of either form cannot cross.
  const __m128 ux = _mm_load_ps(g.ux), uy = _mm_load_ps(g.uy), uz = _mm_load_ps(g.uz);
  const __m128 vx = _mm_load_ps(g.vx), vy = _mm_load_ps(g.vy), vz = _mm_load_ps(g.vz);
  const __m128 xc = _mm_add_ps(_mm_mul_ps(dot4(ox, oy, oz, ux, uy, uz), c),
                               _mm_mul_ps(h, dot4(dx, dy, dz, ux, uy, uz)));
  const __m128 yc = _mm_add_ps(_mm_mul_ps(dot4(ox, oy, oz, vx, vy, vz), c),
                               _mm_mul_ps(h, dot4(dx, dy, dz, vx, vy, vz)));
  const __m128 sign = _mm_set1_ps(-0.0f);
  const __m128 bound = _mm_mul_ps(_mm_andnot_ps(sign, c), _mm_set1_ps(1.0f + 1e-3f));
  const __m128 inside = _mm_and_ps(_mm_cmple_ps(_mm_andnot_ps(sign, xc), bound),
                                   _mm_cmple_ps(_mm_andnot_ps(sign, yc), bound));
  return static_cast<unsigned>(_mm_movemask_ps(_mm_and_ps(ahead, inside)));
}

}  // namespace bxdf::render

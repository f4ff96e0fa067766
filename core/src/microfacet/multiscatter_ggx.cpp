#include "bxdf/microfacet/multiscatter_ggx.h"

#include <cmath>
#include <cstring>

#include "bxdf/microfacet/walk_numbers.h"
#include "bxdf/sampling.h"

namespace bxdf {
namespace microfacet {

float cycles_fresnel_dielectric_cos(float cos_i, float eta) {
  const float c = std::fabs(cos_i);
  float g = eta * eta - 1.0f + c * c;
  if (!(g > 0.0f)) return 1.0f;  // total internal reflection
  g = std::sqrt(g);
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

RGB cycles_interpolate_fresnel(float cos_lh, float eta, const RGB& cspec0) {
  const float f0 = cycles_fresnel_dielectric_cos(1.0f, eta);
  return cycles_interpolate_fresnel_of(cycles_fresnel_dielectric_cos(cos_lh, eta), f0, cspec0);
}

RGB cycles_interpolate_fresnel_of(float fresnel, float f0, const RGB& cspec0) {
  const float fh = (fresnel - f0) / (1.0f - f0);
  return cspec0 * (1.0f - fh) + RGB(fh);
}

float cycles_ggx_albedo(float r) {
  float albedo = 0.806495f * std::exp(-1.98712f * r * r) + 0.199531f;
  albedo -= ((((((1.76741f * r - 8.43891f) * r + 15.784f) * r - 14.398f) * r + 6.45221f) * r -
              1.19722f) * r + 0.027803f) * r + 0.00568739f;
  return clamp(albedo, 0.0f, 1.0f);
}

float cycles_ggx_transmission_albedo(float a, float ior) {
  if (ior < 1.0f) ior = 1.0f / ior;
  a = clamp(a, 0.0f, 1.0f);
  ior = clamp(ior, 1.0f, 3.0f);
  const float i1 = 0.0476898f * std::exp(-0.978352f * (ior - 0.65657f) * (ior - 0.65657f)) -
                   0.033756f * ior + 0.993261f;
  const float r1 = (((0.116991f * a - 0.270369f) * a + 0.0501366f) * a - 0.00411511f) * a + 1.00008f;
  const float i2 = (((-2.08704f * ior + 26.3298f) * ior - 127.906f) * ior + 292.958f) * ior -
                   287.946f + 199.803f / (ior * ior) - 101.668f / (ior * ior * ior);
  const float r2 = ((((5.3725f * a - 24.9307f) * a + 22.7437f) * a - 3.40751f) * a + 0.0986325f) * a +
                   0.00493504f;
  return clamp(1.0f + i2 * r2 * 0.0019127f - (1.0f - i1) * (1.0f - r1) * 9.3205f, 0.0f, 1.0f);
}

namespace {

// ---- Cycles' walk, transcribed from bsdf_microfacet_multi.h / _impl.h (names kept). ----

float d_ggx(Vec3 wm, float alpha) {
  wm.z *= wm.z;
  alpha *= alpha;
  const float tmp = (1.0f - wm.z) + alpha * wm.z;
  return alpha / std::max(kPi * tmp * tmp, 1e-7f);
}

float d_ggx_aniso(const Vec3& wm, float ax, float ay) {
  const float sx = -wm.x / ax, sy = -wm.y / ay;
  const float tmp = wm.z * wm.z + sx * sx + sy * sy;
  return 1.0f / std::max(kPi * tmp * tmp * ax * ay, 1e-7f);
}

float d_walk(const Vec3& wm, float ax, float ay) {
  return ax == ay ? d_ggx(wm, ax) : d_ggx_aniso(wm, ax, ay);
}

Vec3 normalize_unchecked(const Vec3& v) { return v / std::sqrt(dot(v, v)); }

// mf_sampleP22_11: a slope of the unit-roughness distribution visible from cos θ = cos_i.
void sample_p22_11(float cos_i, float randx, float randy, float* sx, float* sy) {
  if (cos_i > 0.9999f || std::fabs(cos_i) < 1e-6f) {
    const float r = std::sqrt(randx / std::max(1.0f - randx, 1e-7f));
    const float phi = 2.0f * kPi * randy;
    *sx = r * std::cos(phi);
    *sy = r * std::sin(phi);
    return;
  }
  const float sin_i = safe_sqrt(1.0f - cos_i * cos_i);
  const float tan_i = sin_i / cos_i;
  const float proj_a = 0.5f * (cos_i + 1.0f);
  *sx = *sy = 0.0f;
  if (proj_a < 0.0001f) return;
  const float a = 2.0f * randx * proj_a / cos_i - 1.0f;
  float tmp = a * a - 1.0f;
  if (std::fabs(tmp) < 1e-7f) return;
  tmp = 1.0f / tmp;
  const float d = safe_sqrt(tan_i * tan_i * tmp * tmp - (a * a - tan_i * tan_i) * tmp);
  const float slope_x2 = tan_i * tmp + d;
  const float slope_x = (a < 0.0f || slope_x2 > 1.0f / tan_i) ? (tan_i * tmp - d) : slope_x2;
  const float u2 = randy >= 0.5f ? 2.0f * (randy - 0.5f) : 2.0f * (0.5f - randy);
  const float z = (u2 * (u2 * (u2 * 0.27385f - 0.73369f) + 0.46341f)) /
                  (u2 * (u2 * (u2 * 0.093073f + 0.309420f) - 1.0f) + 0.597999f);
  const float slope_y = z * std::sqrt(1.0f + slope_x * slope_x);
  *sx = slope_x;
  *sy = randy >= 0.5f ? slope_y : -slope_y;
}

// mf_sample_vndf
Vec3 sample_vndf(const Vec3& wi, float ax, float ay, float randx, float randy) {
  const Vec3 wi_11 = normalize_unchecked(Vec3(ax * wi.x, ay * wi.y, wi.z));
  float s11x, s11y;
  sample_p22_11(wi_11.z, randx, randy, &s11x, &s11y);
  Vec3 cs(wi_11.x, wi_11.y, 0.0f);
  const float len = std::sqrt(dot(cs, cs));
  if (len != 0.0f) cs = cs * (1.0f / len);  // safe_normalize keeps a zero vector
  const float slope_x = ax * (cs.x * s11x - cs.y * s11y);
  const float slope_y = ay * (cs.y * s11x + cs.x * s11y);
  return normalize_unchecked(Vec3(-slope_x, -slope_y, 1.0f));
}

float eval_phase_glossy(const Vec3& w, float lambda, const Vec3& wo, float ax, float ay) {
  if (w.z > 0.9999f) return 0.0f;
  const Vec3 wh = normalize_unchecked(wo - w);
  if (wh.z < 0.0f) return 0.0f;
  const float p_area = w.z < -0.9999f ? 1.0f : lambda * w.z;
  const float dot_w_wh = dot(-w, wh);
  if (dot_w_wh < 0.0f) return 0.0f;
  const float phase = std::max(0.0f, dot_w_wh) * 0.25f / std::max(p_area * dot_w_wh, 1e-7f);
  return phase * d_walk(wh, ax, ay);
}

Vec3 sample_phase_glass(const Vec3& wi, float eta, const Vec3& wm, float rand_v, bool* outside) {
  const float cos_i = dot(wi, wm);
  const float f = cycles_fresnel_dielectric_cos(cos_i, eta);
  if (rand_v < f) {
    *outside = true;
    return -wi + wm * (2.0f * cos_i);
  }
  *outside = false;
  const float inv_eta = 1.0f / eta;
  const float cos_t = -safe_sqrt(1.0f - (1.0f - cos_i * cos_i) * inv_eta * inv_eta);
  return normalize_unchecked(wm * (cos_i * inv_eta + cos_t) - wi * inv_eta);
}

float eval_phase_glass(const Vec3& w, float lambda, const Vec3& wo, bool wo_outside, float alpha,
                       float eta) {
  if (w.z > 0.9999f) return 0.0f;
  const float p_area = w.z < -0.9999f ? 1.0f : lambda * w.z;
  if (wo_outside) {
    const Vec3 wh = normalize_unchecked(wo - w);
    if (wh.z < 0.0f) return 0.0f;
    const float dot_w_wh = dot(-w, wh);
    return cycles_fresnel_dielectric_cos(dot_w_wh, eta) * std::max(0.0f, dot_w_wh) *
           d_ggx(wh, alpha) * 0.25f / (p_area * dot_w_wh);
  }
  Vec3 wh = normalize_unchecked(wo * eta - w);
  if (wh.z < 0.0f) wh = -wh;
  const float dot_w_wh = dot(-w, wh), dot_wo_wh = dot(wo, wh);
  if (dot_w_wh < 0.0f) return 0.0f;
  const float temp = dot_w_wh + eta * dot_wo_wh;
  return (1.0f - cycles_fresnel_dielectric_cos(dot_w_wh, eta)) * std::max(0.0f, dot_w_wh) *
         std::max(0.0f, -dot_wo_wh) * d_ggx(wh, alpha) / (p_area * temp * temp);
}

float mf_lambda(const Vec3& w, float ax, float ay) {
  if (w.z > 0.9999f) return 0.0f;
  if (w.z < -0.9999f) return -0.9999f;
  const float inv_wz2 = 1.0f / std::max(w.z * w.z, 1e-7f);
  const float wax = w.x * ax, way = w.y * ay;
  float v = std::sqrt(1.0f + (wax * wax + way * way) * inv_wz2);
  if (w.z <= 0.0f) v = -v;
  return 0.5f * (v - 1.0f);
}

float mf_inv_c1(float h) { return 2.0f * clamp(h, 0.0f, 1.0f) - 1.0f; }
float mf_c1(float h) { return clamp(0.5f * (h + 1.0f), 0.0f, 1.0f); }

float mf_g1(const Vec3& w, float c1, float lambda) {
  if (w.z > 0.9999f) return 1.0f;
  if (w.z < 1e-5f) return 0.0f;
  return std::pow(c1, lambda);
}

bool mf_sample_height(const Vec3& w, float* h, float* c1, float* g1, float* lambda, float u) {
  if (w.z > 0.9999f) return false;
  if (w.z < -0.9999f) {
    *c1 *= u;
    *h = mf_inv_c1(*c1);
    *g1 = mf_g1(w, *c1, *lambda);
  } else if (std::fabs(w.z) >= 0.0001f) {
    if (u > 1.0f - *g1) return false;
    if (*lambda >= 0.0f) {
      *c1 = 1.0f;
    } else {
      *c1 *= std::pow(1.0f - u, -1.0f / *lambda);
    }
    *h = mf_inv_c1(*c1);
    *g1 = mf_g1(w, *c1, *lambda);
  }
  return true;
}

float beta_function(float x, float y) {
  int sign = 0;  // the reentrant lgamma: the plain one writes the global signgam
  return std::exp(lgammaf_r(x, &sign) + lgammaf_r(y, &sign) - lgammaf_r(x + y, &sign));
}

struct Walk {
  float ax, ay, eta;
  RGB color, cspec0;
  bool use_fresnel;
};

constexpr int kMaxOrder = 10;

// The body of Cycles' mf_eval after its swap: wi (Cycles' incoming = the walk's start, z > 0),
// wo (the direction scattered to). Returns f·|cos θ(wo)| of the pair as Cycles computes it
// before the swap rescaling.
template <bool kGlass, class Rng>
RGB walk_eval(const Walk& p, const Vec3& wi, const Vec3& wo, bool wo_outside, Rng& rng) {
  if (wi.z < 1e-5f || (wo.z < 1e-5f && wo_outside) || (wo.z > -1e-5f && !wo_outside))
    return RGB(0.0f);
  float lambda_r = mf_lambda(-wi, p.ax, p.ay);
  const float shadowing_lambda = mf_lambda(wo_outside ? wo : -wo, p.ax, p.ay);

  RGB eval;
  RGB throughput(1.0f);
  const Vec3 wh = normalize_unchecked(wi + wo);
  if constexpr (kGlass) {
    float e = eval_phase_glass(-wi, lambda_r, wo, wo_outside, p.ax, p.eta);
    if (wo_outside)
      e *= -lambda_r / (shadowing_lambda - lambda_r);
    else
      e *= -lambda_r * beta_function(-lambda_r, shadowing_lambda + 1.0f);
    eval = RGB(e);
  } else {
    const float g2 = 1.0f / (1.0f - (lambda_r + 1.0f) + shadowing_lambda);
    eval = RGB(g2 * 0.25f / wi.z * d_walk(wh, p.ax, p.ay));
  }
  if (p.use_fresnel) {
    throughput = cycles_interpolate_fresnel(dot(wi, wh), p.eta, p.cspec0);
    eval *= throughput;
  }

  Vec3 wr = -wi;
  float hr = 1.0f, c1_r = 1.0f, g1_r = 0.0f;
  bool outside = true;
  for (int order = 0; order < kMaxOrder; ++order) {
    const float height_rand = rng.uniform();
    if (!mf_sample_height(wr, &hr, &c1_r, &g1_r, &lambda_r, height_rand)) break;
    const float vndf_rand_y = rng.uniform();
    const float vndf_rand_x = rng.uniform();
    const Vec3 wm = sample_vndf(-wr, p.ax, p.ay, vndf_rand_x, vndf_rand_y);

    const auto phase_here = [&]() -> RGB {
      if constexpr (kGlass) {
        return RGB(outside ? eval_phase_glass(wr, lambda_r, wo, wo_outside, p.ax, p.eta)
                           : eval_phase_glass(wr, lambda_r, -wo, !wo_outside, p.ax, 1.0f / p.eta));
      } else {
        return RGB(eval_phase_glossy(wr, lambda_r, wo, p.ax, p.ay)) * throughput;
      }
    };
    const auto g1_wo = [&] {
      return mf_g1(wo_outside ? wo : -wo, mf_c1(outside == wo_outside ? hr : -hr),
                   shadowing_lambda);
    };
    if constexpr (kGlass) {
      // Cycles replaces the analytic first order of the Fresnel glass by this one-sample one.
      if (order == 0 && p.use_fresnel) eval = throughput * phase_here() * g1_wo();
    }
    // (For glossy, phase_here() already carries the throughput: Cycles applies it twice.)
    if (order > 0) eval += throughput * phase_here() * g1_wo();

    if (order + 1 < kMaxOrder) {
      if constexpr (kGlass) {
        bool next_outside;
        const Vec3 wi_prev = -wr;
        const float phase_rand = rng.uniform();
        wr = sample_phase_glass(-wr, outside ? p.eta : 1.0f / p.eta, wm, phase_rand, &next_outside);
        if (!next_outside) {
          outside = !outside;
          wr = -wr;
          hr = -hr;
        }
        if (p.use_fresnel && !next_outside)
          throughput *= p.color;
        else if (p.use_fresnel && order > 0)
          throughput *= cycles_interpolate_fresnel(dot(wi_prev, wm), p.eta, p.cspec0);
      } else {
        if (p.use_fresnel && order > 0)
          throughput *= cycles_interpolate_fresnel(dot(-wr, wm), p.eta, p.cspec0);
        wr = wr + wm * (2.0f * dot(-wr, wm));  // mf_sample_phase_glossy(-wr, wm)
      }
      lambda_r = mf_lambda(wr, p.ax, p.ay);
      if (!p.use_fresnel) throughput *= p.color;
      c1_r = mf_c1(hr);
      g1_r = mf_g1(wr, c1_r, lambda_r);
    }
  }
  return eval;
}

// The numbers of a sampling walk outside a MultiscatterWalkNumbers scope: a seeded generator,
// and the caller's first facet where it gives one (else the generator's two numbers).
struct SeededWalkNumbers {
  PCG32& rng;
  const Point2* facet;
  float uniform() { return rng.uniform(); }
  Point2 first_facet() {
    if (facet != nullptr) return *facet;
    const float y = rng.uniform();
    return Point2(rng.uniform(), y);
  }
};

// The numbers of a sampling walk inside a scope: the path vertex's WalkNumbers, whose first
// facet is u at the path's first sampling walk (walk_numbers.h).
struct VertexWalkNumbers {
  WalkNumbers& numbers;
  Point2 u;
  float uniform() { return numbers.uniform(); }
  Point2 first_facet() { return numbers.first_facet(u); }
};

// Cycles' mf_sample: returns the throughput f cos/p and the exit direction, drawing from
// `numbers` (SeededWalkNumbers or VertexWalkNumbers) in Cycles' order.
template <bool kGlass, class Numbers>
RGB walk_sample_impl(const Walk& p, const Vec3& wi, Numbers&& numbers, Vec3* wo) {
  RGB throughput(1.0f);
  Vec3 wr = -wi;
  float lambda_r = mf_lambda(wr, p.ax, p.ay);
  float hr = 1.0f, c1_r = 1.0f, g1_r = 0.0f;
  bool outside = true;
  for (int order = 0; order < kMaxOrder; ++order) {
    const float height_rand = numbers.uniform();
    if (!mf_sample_height(wr, &hr, &c1_r, &g1_r, &lambda_r, height_rand)) {
      *wo = outside ? wr : -wr;
      return throughput;
    }
    float vndf_rand_y, vndf_rand_x;
    if (order == 0) {
      const Point2 facet = numbers.first_facet();
      vndf_rand_x = facet.x;
      vndf_rand_y = facet.y;
    } else {
      vndf_rand_y = numbers.uniform();
      vndf_rand_x = numbers.uniform();
    }
    const Vec3 wm = sample_vndf(-wr, p.ax, p.ay, vndf_rand_x, vndf_rand_y);
    if (!p.use_fresnel && order > 0) throughput *= p.color;
    if constexpr (kGlass) {
      bool next_outside;
      const Vec3 wi_prev = -wr;
      const float phase_rand = numbers.uniform();
      wr = sample_phase_glass(-wr, outside ? p.eta : 1.0f / p.eta, wm, phase_rand, &next_outside);
      if (!next_outside) {
        hr = -hr;
        wr = -wr;
        outside = !outside;
      }
      if (p.use_fresnel) {
        if (!next_outside) {
          throughput *= p.color;
        } else {
          const RGB t = cycles_interpolate_fresnel(dot(wi_prev, wm), p.eta, p.cspec0);
          throughput = order == 0 ? t : throughput * t;
        }
      }
    } else {
      if (p.use_fresnel) {
        const RGB t = cycles_interpolate_fresnel(dot(-wr, wm), p.eta, p.cspec0);
        throughput = order == 0 ? t : throughput * t;
      }
      wr = wr + wm * (2.0f * dot(-wr, wm));  // -wi' + 2 wm (wi'·wm) with wi' = -wr
    }
    lambda_r = mf_lambda(wr, p.ax, p.ay);
    g1_r = mf_g1(wr, c1_r, lambda_r);
  }
  *wo = Vec3(0.0f, 0.0f, 1.0f);
  return RGB(0.0f);
}

uint64_t mix64(uint64_t h) {  // splitmix64's finaliser
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

uint64_t hash_pair(const Vec3& a, const Vec3& b) {
  const float v[6] = {a.x, a.y, a.z, b.x, b.y, b.z};
  uint64_t h = 0x6a09e667f3bcc909ULL;
  for (float x : v) {
    uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    h = mix64(h ^ bits);
  }
  return h;
}

thread_local uint64_t walk_salt = 0;

// The average of kMultiscatterWalks walks of the pair (start, end), seeded from the pair, or,
// when a MultiscatterWalkSalt scope is open, of kSaltedMultiscatterWalks seeded from the pair
// and the thread's salt.
template <bool kGlass>
RGB averaged_walks(const Walk& p, const Vec3& start, const Vec3& end, bool end_outside) {
  const uint64_t pair = hash_pair(start, end);
  const uint64_t seed = walk_salt == 0 ? pair : mix64(pair ^ mix64(walk_salt));
  const int walks = walk_salt == 0 ? kMultiscatterWalks : kSaltedMultiscatterWalks;
  // In the renderer the first walk draws from the vertex's walk numbers, as Cycles' one eval
  // walk draws from the shading point's LCG: the vertex's sampling walk then starts where
  // Cycles' does (walk_numbers.h).
  WalkNumbers* numbers = MultiscatterWalkNumbers::current();
  RGB sum(0.0f);
  for (int k = 0; k < walks; ++k) {
    if (k == 0 && numbers != nullptr) {
      sum += walk_eval<kGlass>(p, start, end, end_outside, *numbers);
      continue;
    }
    PCG32 rng(static_cast<uint64_t>(k), seed);
    sum += walk_eval<kGlass>(p, start, end, end_outside, rng);
  }
  return sum * (1.0f / static_cast<float>(walks));
}

// The generator of one sampling walk: seeded by the bits of wo and u and the thread's salt.
PCG32 sampling_walk_rng(const Vec3& wo, Point2 u) {
  const uint64_t h = hash_pair(wo, Vec3(u.x, u.y, 0.0f));
  return PCG32(0x5a17u, walk_salt == 0 ? h : mix64(h ^ mix64(walk_salt)));
}

// Cycles' sampling walk from wo with its first facet stratified by u: drawing from this
// thread's WalkNumbers where the renderer opened a scope, else from a generator seeded by the
// bits of wo and u (and the thread's salt).
template <bool kGlass>
RGB sampling_walk(const Walk& p, const Vec3& wo, Point2 u, Vec3* wi) {
  if (WalkNumbers* numbers = MultiscatterWalkNumbers::current())
    return walk_sample_impl<kGlass>(p, wo, VertexWalkNumbers{*numbers, u}, wi);
  PCG32 rng = sampling_walk_rng(wo, u);
  return walk_sample_impl<kGlass>(p, wo, SeededWalkNumbers{rng, &u}, wi);
}

// A walk's exit as a sample: snapped, and refused when it did not leave or lies in the plane.
WalkSample walk_exit(Vec3 wi, const RGB& weight, bool below) {
  WalkSample s;
  if (weight.is_black() || wi.z == 0.0f) return s;
  if (below) wi.z = -wi.z;
  if (!snap_to_unit(wi) || wi.z == 0.0f) return s;
  s.wi = wi;
  s.weight = weight;
  s.flags = ((wi.z > 0.0f) == !below ? kReflection : kTransmission) | kGlossy;
  s.ok = true;
  return s;
}

// True when a is the direction Cycles starts the walk from (the shallower one); ties are
// broken by the bits, so that (a, b) and (b, a) always walk the same pair.
bool starts_from(const Vec3& a, const Vec3& b, float za, float zb) {
  if (za != zb) return za < zb;
  if (a.x != b.x) return a.x < b.x;
  return a.y < b.y;
}

constexpr float kOneBelowOne = 0x1.fffffep-1f;
float rescale(float u, float lo, float width) { return std::min((u - lo) / width, kOneBelowOne); }

Walk walk_of(const MultiscatterSetup& s, bool glass) {
  Walk w;
  w.ax = clamp(s.alpha_x, 1e-4f, 1.0f);
  w.ay = glass ? w.ax : clamp(s.alpha_y, 1e-4f, 1.0f);
  w.eta = s.eta;
  const auto sat = [](const RGB& c) {
    return RGB(clamp(c.r, 0.0f, 1.0f), clamp(c.g, 0.0f, 1.0f), clamp(c.b, 0.0f, 1.0f));
  };
  w.color = sat(s.color);
  w.cspec0 = sat(s.cspec0);
  w.use_fresnel = s.fresnel == MultiscatterFresnel::kInterpolated;
  return w;
}

MultiscatterSetup clamped(const MultiscatterSetup& s, bool glass) {
  const Walk w = walk_of(s, glass);
  MultiscatterSetup out = s;
  out.alpha_x = w.ax;
  out.alpha_y = w.ay;
  out.color = w.color;
  out.cspec0 = w.cspec0;
  return out;
}

}  // namespace

MultiscatterWalkSalt::MultiscatterWalkSalt(uint64_t salt) : previous_(walk_salt) {
  walk_salt = salt;
}
MultiscatterWalkSalt::~MultiscatterWalkSalt() { walk_salt = previous_; }
uint64_t MultiscatterWalkSalt::current() { return walk_salt; }
uint64_t* MultiscatterWalkSalt::thread_slot() { return &walk_salt; }

// ---- Reflection ----

MultiscatterGGXReflection::MultiscatterGGXReflection(const MultiscatterSetup& setup)
    : setup_(clamped(setup, false)),
      ggx_(setup_.alpha_x, setup_.alpha_y),
      single_probability_(cycles_ggx_albedo(std::sqrt(setup_.alpha_x * setup_.alpha_y))) {}

namespace {

// The pair Cycles' glossy eval walks: from the shallower direction (wo mirrored up first).
bool reflection_walk(Vec3 wo, Vec3 wi, Vec3* start, Vec3* end) {
  if (!same_hemisphere(wo, wi)) return false;
  if (wo.z < 0.0f) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  const bool from_wo = starts_from(wo, wi, wo.z, wi.z);
  *start = from_wo ? wo : wi;
  *end = from_wo ? wi : wo;
  return true;
}

}  // namespace

// f(wo, wi) = W(start, end)/cos θ(end), W the walk's estimate of f·cos θ(end).
RGB MultiscatterGGXReflection::eval(Vec3 wo, Vec3 wi) const {
  Vec3 start, end;
  if (!reflection_walk(wo, wi, &start, &end)) return RGB(0.0f);
  return averaged_walks<false>(walk_of(setup_, false), start, end, true) / end.z;
}

RGB MultiscatterGGXReflection::walk_f(Vec3 wo, Vec3 wi, PCG32& rng) const {
  Vec3 start, end;
  if (!reflection_walk(wo, wi, &start, &end)) return RGB(0.0f);
  return walk_eval<false>(walk_of(setup_, false), start, end, true, rng) / end.z;
}

RGB MultiscatterGGXReflection::walk_sample(Vec3 wo, PCG32& rng, Vec3* wi) const {
  const bool below = wo.z < 0.0f;
  if (below) wo.z = -wo.z;
  const RGB t =
      walk_sample_impl<false>(walk_of(setup_, false), wo, SeededWalkNumbers{rng, nullptr}, wi);
  if (below) wi->z = -wi->z;
  return t;
}

WalkSample MultiscatterGGXReflection::sample_walk(Vec3 wo, Point2 u) const {
  if (wo.z == 0.0f) return WalkSample();
  const bool below = wo.z < 0.0f;
  if (below) wo.z = -wo.z;
  Vec3 wi;
  const RGB t = sampling_walk<false>(walk_of(setup_, false), wo, u, &wi);
  if (!(wi.z > 0.0f)) return WalkSample();
  return walk_exit(wi, t, below);
}

DirectionSample MultiscatterGGXReflection::sample_direction(Vec3 wo, Point2 u) const {
  DirectionSample d;
  if (wo.z == 0.0f) return d;
  const bool below = wo.z < 0.0f;
  if (below) wo.z = -wo.z;
  const float a = single_probability_;
  Vec3 wi;
  if (u.x < a) {
    const Vec3 wh = ggx_.sample_wh(wo, Point2(rescale(u.x, 0.0f, a), u.y));
    wi = reflect(wo, wh);
  } else {
    wi = sample_cosine_hemisphere(Point2(rescale(u.x, a, 1.0f - a), u.y));
  }
  if (!(wi.z > 0.0f)) return d;
  if (below) wi.z = -wi.z;
  if (!snap_to_unit(wi)) return d;
  d.wi = wi;
  d.flags = kReflection | kGlossy;
  d.ok = true;
  return d;
}

float MultiscatterGGXReflection::density(Vec3 wo, Vec3 wi) const {
  if (!same_hemisphere(wo, wi)) return 0.0f;
  if (wo.z < 0.0f) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  Vec3 wh = wo + wi;
  if (!normalize_direction(wh)) return 0.0f;
  const float wo_h = dot(wo, wh);
  const float single = wo_h > 0.0f ? ggx_.pdf_wh(wo, wh) / (4.0f * wo_h) : 0.0f;
  const float a = single_probability_;
  return a * single + (1.0f - a) * wi.z * kInvPi;
}

// ---- Glass ----

MultiscatterGGXGlass::MultiscatterGGXGlass(const MultiscatterSetup& setup)
    : setup_(clamped(setup, true)),
      ggx_(setup_.alpha_x, setup_.alpha_x),
      single_probability_(cycles_ggx_albedo(setup_.alpha_x)) {}

namespace {

// The pair seen from above: wo.z > 0, and the index ratio on that side.
struct GlassSide {
  Vec3 wo, wi;
  float eta;
};
bool glass_side(Vec3 wo, Vec3 wi, float eta, GlassSide* s) {
  if (wo.z == 0.0f || wi.z == 0.0f) return false;
  if (wo.z < 0.0f) {
    wo.z = -wo.z;
    wi.z = -wi.z;
    eta = 1.0f / eta;
  }
  *s = {wo, wi, eta};
  return true;
}

// The generalised half vector of a refraction from wo (above) to wi (below), facing up, or
// false when no facet seen from wo refracts wo into wi.
bool refraction_half(const GlassSide& s, Vec3* wh) {
  Vec3 h = s.wo + s.wi * s.eta;
  if (!normalize_direction(h)) return false;
  if (h.z < 0.0f) h = -h;
  if (!(dot(s.wo, h) > 0.0f) || !(dot(s.wi, h) < 0.0f)) return false;
  *wh = h;
  return true;
}

float uniform_from_bits(Point2 u) {  // a third number for a choice, hashed from u's bits
  uint32_t bx, by;
  std::memcpy(&bx, &u.x, sizeof bx);
  std::memcpy(&by, &u.y, sizeof by);
  const uint64_t h = mix64((static_cast<uint64_t>(bx) << 32) | by);
  return static_cast<float>(h >> 40) * 0x1p-24f;
}

// The walk Cycles' glass eval runs for (wo, wi): its parameters, start and end.
struct GlassWalk {
  Walk p;
  Vec3 start, end;
  bool end_outside;
};
bool glass_walk(const MultiscatterSetup& setup, Vec3 wo, Vec3 wi, GlassWalk* w) {
  GlassSide s;
  if (!glass_side(wo, wi, setup.eta, &s)) return false;
  w->p = walk_of(setup, true);
  w->p.eta = s.eta;
  const bool transmission = s.wi.z < 0.0f;
  // Cycles' glass eval: a transmitted pair walks with the colour rule even for the Fresnel
  // closure (its first order then carries no colour).
  if (transmission) w->p.use_fresnel = false;
  w->end_outside = !transmission;
  w->start = s.wo;
  w->end = s.wi;
  if (transmission) {
    if (-s.wi.z < s.wo.z) {  // Cycles' swap for transmission: start from -wi, end at -wo
      w->start = -s.wi;
      w->end = -s.wo;
    }
  } else if (!starts_from(s.wo, s.wi, s.wo.z, s.wi.z)) {
    w->start = s.wi;
    w->end = s.wo;
  }
  return true;
}

}  // namespace

RGB MultiscatterGGXGlass::eval(Vec3 wo, Vec3 wi) const {
  GlassWalk w;
  if (!glass_walk(setup_, wo, wi, &w)) return RGB(0.0f);
  return averaged_walks<true>(w.p, w.start, w.end, w.end_outside) / std::fabs(w.end.z);
}

RGB MultiscatterGGXGlass::walk_f(Vec3 wo, Vec3 wi, PCG32& rng) const {
  GlassWalk w;
  if (!glass_walk(setup_, wo, wi, &w)) return RGB(0.0f);
  return walk_eval<true>(w.p, w.start, w.end, w.end_outside, rng) / std::fabs(w.end.z);
}

RGB MultiscatterGGXGlass::walk_sample(Vec3 wo, PCG32& rng, Vec3* wi) const {
  if (wo.z == 0.0f) return RGB(0.0f);
  Walk p = walk_of(setup_, true);
  const bool below = wo.z < 0.0f;
  if (below) {
    wo.z = -wo.z;
    p.eta = 1.0f / p.eta;
  }
  const RGB t = walk_sample_impl<true>(p, wo, SeededWalkNumbers{rng, nullptr}, wi);
  if (below) wi->z = -wi->z;
  return t;
}

WalkSample MultiscatterGGXGlass::sample_walk(Vec3 wo, Point2 u) const {
  if (wo.z == 0.0f) return WalkSample();
  Walk p = walk_of(setup_, true);
  const bool below = wo.z < 0.0f;
  if (below) {
    wo.z = -wo.z;
    p.eta = 1.0f / p.eta;
  }
  Vec3 wi;
  const RGB t = sampling_walk<true>(p, wo, u, &wi);
  return walk_exit(wi, t, below);
}

DirectionSample MultiscatterGGXGlass::sample_direction(Vec3 wo, Point2 u) const {
  DirectionSample d;
  GlassSide s;
  if (!glass_side(wo, Vec3(0.0f, 0.0f, 1.0f), setup_.eta, &s)) return d;
  const bool below = wo.z < 0.0f;
  const float a = single_probability_;
  Vec3 wi;
  if (u.x < a) {
    const Vec3 wh = ggx_.sample_wh(s.wo, Point2(rescale(u.x, 0.0f, a), u.y));
    const float wo_h = dot(s.wo, wh);
    if (!(wo_h > 0.0f)) return d;
    const float f = cycles_fresnel_dielectric_cos(wo_h, s.eta);
    if (uniform_from_bits(u) < f) {
      wi = reflect(s.wo, wh);
      if (!(wi.z > 0.0f)) return d;
    } else if (!refract(s.wo, wh, 1.0f / s.eta, &wi) || !(wi.z < 0.0f)) {
      return d;
    }
  } else {
    const float v = rescale(u.x, a, 1.0f - a);
    const float p_reflect = cycles_fresnel_dielectric_cos(s.wo.z, s.eta);
    if (v < p_reflect) {
      wi = sample_cosine_hemisphere(Point2(rescale(v, 0.0f, p_reflect), u.y));
    } else {
      wi = sample_cosine_hemisphere(Point2(rescale(v, p_reflect, 1.0f - p_reflect), u.y));
      wi.z = -wi.z;
    }
    if (wi.z == 0.0f) return d;
  }
  d.flags = (wi.z > 0.0f ? kReflection : kTransmission) | kGlossy;
  if (below) wi.z = -wi.z;
  if (!snap_to_unit(wi) || wi.z == 0.0f) return d;
  d.wi = wi;
  d.ok = true;
  return d;
}

float MultiscatterGGXGlass::density(Vec3 wo, Vec3 wi) const {
  GlassSide s;
  if (!glass_side(wo, wi, setup_.eta, &s)) return 0.0f;
  const float a = single_probability_;
  const float p_reflect = cycles_fresnel_dielectric_cos(s.wo.z, s.eta);
  float single = 0.0f, multi;
  if (s.wi.z > 0.0f) {
    Vec3 wh = s.wo + s.wi;
    if (normalize_direction(wh)) {
      const float wo_h = dot(s.wo, wh);
      if (wo_h > 0.0f)
        single = ggx_.pdf_wh(s.wo, wh) * cycles_fresnel_dielectric_cos(wo_h, s.eta) / (4.0f * wo_h);
    }
    multi = p_reflect * s.wi.z * kInvPi;
  } else {
    Vec3 wh;
    if (refraction_half(s, &wh)) {
      const float wo_h = dot(s.wo, wh), wi_h = dot(s.wi, wh);
      const float denom = wo_h + s.eta * wi_h;
      single = ggx_.pdf_wh(s.wo, wh) * (1.0f - cycles_fresnel_dielectric_cos(wo_h, s.eta)) *
               s.eta * s.eta * std::fabs(wi_h) / (denom * denom);
    }
    multi = (1.0f - p_reflect) * -s.wi.z * kInvPi;
  }
  return a * single + (1.0f - a) * multi;
}

MultiscatterGGXRefraction::MultiscatterGGXRefraction(const MultiscatterSetup& setup)
    : glass_(setup),
      ggx_(glass_.setup().alpha_x, glass_.setup().alpha_x),
      single_probability_(cycles_ggx_albedo(glass_.setup().alpha_x)) {}

RGB MultiscatterGGXRefraction::eval(Vec3 wo, Vec3 wi) const {
  if (!(wo.z * wi.z < 0.0f)) return RGB(0.0f);
  return glass_.eval(wo, wi);
}

DirectionSample MultiscatterGGXRefraction::sample_direction(Vec3 wo, Point2 u) const {
  DirectionSample d;
  GlassSide s;
  if (!glass_side(wo, Vec3(0.0f, 0.0f, 1.0f), glass_.setup().eta, &s)) return d;
  const float a = single_probability_;
  Vec3 wi;
  if (u.x < a) {
    const Vec3 wh = ggx_.sample_wh(s.wo, Point2(rescale(u.x, 0.0f, a), u.y));
    if (!(dot(s.wo, wh) > 0.0f)) return d;
    if (!refract(s.wo, wh, 1.0f / s.eta, &wi) || !(wi.z < 0.0f)) return d;
  } else {
    wi = sample_cosine_hemisphere(Point2(rescale(u.x, a, 1.0f - a), u.y));
    wi.z = -wi.z;
  }
  if (wo.z < 0.0f) wi.z = -wi.z;
  if (!snap_to_unit(wi) || wi.z == 0.0f) return d;
  d.wi = wi;
  d.flags = kTransmission | kGlossy;
  d.ok = true;
  return d;
}

float MultiscatterGGXRefraction::density(Vec3 wo, Vec3 wi) const {
  GlassSide s;
  if (!glass_side(wo, wi, glass_.setup().eta, &s) || !(s.wi.z < 0.0f)) return 0.0f;
  float single = 0.0f;
  Vec3 wh;
  if (refraction_half(s, &wh)) {
    const float wo_h = dot(s.wo, wh), wi_h = dot(s.wi, wh);
    const float denom = wo_h + s.eta * wi_h;
    single = ggx_.pdf_wh(s.wo, wh) * s.eta * s.eta * std::fabs(wi_h) / (denom * denom);
  }
  const float a = single_probability_;
  return a * single + (1.0f - a) * -s.wi.z * kInvPi;
}

}  // namespace microfacet
}  // namespace bxdf

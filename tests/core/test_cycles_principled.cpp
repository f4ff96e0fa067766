// cycles_principled against Blender 3.4's Principled BSDF written out here in double precision
// the way Cycles builds and evaluates it: svm/closure.h (PRINCIPLED case: weights, cut-offs,
// subsurface on diffuse-ancestor paths, back-face IOR) and closure/bsdf_principled_diffuse.h,
// bsdf_principled_sheen.h, bsdf_microfacet.h (GGX with interpolated Fresnel, clearcoat, GGX
// refraction). Cycles' eval returns f·|cos θi| summed over closures × weights. Also: the
// singular (delta) closures' sample weights, the multi_ggx switch thresholds, and the mapping
// from registry parameters to the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bxdf/models/cycles_principled.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;

struct D3 {
  double x = 0, y = 0, z = 0;
};
D3 d3(const Vec3& v) { return {v.x, v.y, v.z}; }
double dotd(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 normd(const D3& a) {
  const double l = std::sqrt(dotd(a, a));
  return {a.x / l, a.y / l, a.z / l};
}
struct C3 {
  double r = 0, g = 0, b = 0;
};
C3 c3(double v) { return {v, v, v}; }
C3 operator*(const C3& a, double s) { return {a.r * s, a.g * s, a.b * s}; }
C3 operator*(const C3& a, const C3& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
C3 operator+(const C3& a, const C3& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
double avg(const C3& c) { return (c.r + c.g + c.b) / 3; }

double sat(double x) { return std::min(1.0, std::max(0.0, x)); }

double fresnel_dielectric_cos(double cosi, double eta) {
  const double c = std::fabs(cosi);
  double g = eta * eta - 1 + c * c;
  if (g > 0) {
    g = std::sqrt(g);
    const double A = (g - c) / (g + c);
    const double B = (c * (g + c) - 1) / (c * (g - c) + 1);
    return 0.5 * A * A * (1 + B * B);
  }
  return 1.0;
}
double schlick(double u) {
  const double m = sat(1 - u);
  return m * m * m * m * m;
}
C3 interpolate_fresnel(double cos_lh, double ior, const C3& cspec0) {
  const double f0 = fresnel_dielectric_cos(1.0, ior);
  const double fh = (fresnel_dielectric_cos(cos_lh, ior) - f0) / (1 - f0);
  return cspec0 * (1 - fh) + c3(fh);
}

struct Params {
  C3 base{0.8, 0.8, 0.8};
  double subsurface = 0;
  C3 subsurface_color{0.8, 0.8, 0.8};
  double metallic = 0, specular = 0.5, specular_tint = 0, roughness = 0.5, anisotropic = 0,
         anisotropic_rotation = 0, sheen = 0, sheen_tint = 0.5, clearcoat = 0,
         clearcoat_roughness = 0.03, ior = 1.45, transmission = 0, transmission_roughness = 0;

  ParamSet to_params() const {
    ParamSet p;
    p.set("base_color", RGBValue{base.r, base.g, base.b});
    p.set("subsurface", subsurface);
    p.set("subsurface_color", RGBValue{subsurface_color.r, subsurface_color.g, subsurface_color.b});
    p.set("metallic", metallic);
    p.set("specular", specular);
    p.set("specular_tint", specular_tint);
    p.set("roughness", roughness);
    p.set("anisotropic", anisotropic);
    p.set("anisotropic_rotation", anisotropic_rotation);
    p.set("sheen", sheen);
    p.set("sheen_tint", sheen_tint);
    p.set("clearcoat", clearcoat);
    p.set("clearcoat_roughness", clearcoat_roughness);
    p.set("ior", ior);
    p.set("transmission", transmission);
    p.set("transmission_roughness", transmission_roughness);
    p.set("distribution", "ggx");
    return p;
  }
};

// bsdf_microfacet.h's isotropic terms: Smith's G1 for α² at cos θ, GGX's D for α² at cos θm
// (in Cycles' tan² form), and GTR1's D for α at cos θm (uniform at α ≥ 1).
double smith_g1(double cos_n, double a2) {
  return 2 / (1 + std::sqrt(1 + a2 * (1 - cos_n * cos_n) / (cos_n * cos_n)));
}
double d_ggx(double cos_m, double a2) {
  const double c2 = cos_m * cos_m, tan2 = (1 - c2) / c2;
  return a2 / (kPiD * c2 * c2 * (a2 + tan2) * (a2 + tan2));
}
double d_gtr1(double cos_m, double a) {
  if (a >= 1) return 1 / kPiD;
  const double aa = a * a;
  return (aa - 1) / (kPiD * std::log(aa) * (1 + (aa - 1) * cos_m * cos_m));
}

// One microfacet closure of bsdf_microfacet.h, evaluated for the local frame (N = z, T = the
// rotated tangent), returning eval = f·|cos θL|.
struct Microfacet {
  enum Type { kFresnel, kClearcoat, kRefraction } type;
  double alpha_x, alpha_y, ior;
  C3 cspec0;
  double clearcoat = 0;
  D3 T{1, 0, 0};

  C3 eval(const D3& I, const D3& L) const {
    const double cos_no = I.z, cos_ni = L.z;
    if (alpha_x * alpha_y <= 1e-7) return {};
    if (type == kRefraction) {
      if (cos_no <= 0 || cos_ni >= 0) return {};
      const double eta = ior;
      const D3 ht{-(eta * L.x + I.x), -(eta * L.y + I.y), -(eta * L.z + I.z)};
      const D3 Ht = normd(ht);
      const double cos_ho = dotd(Ht, I), cos_hi = dotd(Ht, L);
      const double a2 = alpha_x * alpha_y;
      const double D = d_ggx(Ht.z, a2);
      const double G1o = smith_g1(cos_no, a2), G1i = smith_g1(cos_ni, a2);
      const double common = D * eta * eta / (cos_no * dotd(ht, ht));
      return c3(G1o * G1i * std::fabs(cos_hi * cos_ho) * common);
    }
    if (!(cos_ni > 0 && cos_no > 0)) return {};
    const D3 m = normd({L.x + I.x, L.y + I.y, L.z + I.z});
    double D, G1o, G1i;
    if (alpha_x == alpha_y) {
      double a2 = alpha_x * alpha_y;
      if (type == kClearcoat) {
        D = d_gtr1(m.z, alpha_x);
        a2 = 0.0625;
      } else {
        D = d_ggx(m.z, a2);
      }
      G1o = smith_g1(cos_no, a2);
      G1i = smith_g1(cos_ni, a2);
    } else {
      // make_orthonormals_tangent(Z, T): Y = normalize(Z × T), X = Y × Z.
      const D3 Y = normd({-T.y, T.x, 0});
      const D3 X{Y.y, -Y.x, 0};
      const D3 lm{dotd(X, m), dotd(Y, m), m.z};
      const double sx = -lm.x / (lm.z * alpha_x), sy = -lm.y / (lm.z * alpha_y);
      const double sl = 1 + sx * sx + sy * sy;
      D = 1 / (sl * sl * kPiD * alpha_x * alpha_y * lm.z * lm.z * lm.z * lm.z);
      const auto g1 = [&](const D3& w) {
        const double c = w.z, t2 = (1 - c * c) / (c * c);
        const double cp = dotd(w, X), sp = dotd(w, Y);
        const double a2w = (cp * cp * alpha_x * alpha_x + sp * sp * alpha_y * alpha_y) / (cp * cp + sp * sp);
        return 2 / (1 + std::sqrt(1 + a2w * t2));
      };
      G1o = g1(I);
      G1i = g1(L);
    }
    C3 F = interpolate_fresnel(dotd(L, m), ior, cspec0);
    if (type == kClearcoat) F = F * (0.25 * clearcoat);
    return F * (G1o * G1i * D * 0.25 / cos_no);
  }
};

// svm_node_closure_bsdf's PRINCIPLED case on a diffuse-ancestor path, distribution GGX; I (the
// viewer) and L in the local frame. Returns Σ weight × eval / |cos θL| (= our f).
C3 cycles_principled_f(const Params& p, D3 I, D3 L) {
  constexpr double kCut = 1e-5;
  const bool backfacing = I.z < 0;
  if (backfacing) {  // Cycles flips N (and Ng) towards the viewer on a back face
    I.z = -I.z;
    L.z = -L.z;
  }
  const double eta = std::max(p.ior, 1e-5);
  const double ior = backfacing ? 1 / eta : eta;
  const double fresnel = fresnel_dielectric_cos(I.z, ior);
  const double diffuse_weight = (1 - sat(p.metallic)) * (1 - sat(p.transmission));
  const double final_transmission = sat(p.transmission) * (1 - sat(p.metallic));
  const double specular_weight = 1 - final_transmission;
  C3 base = p.subsurface_color * p.subsurface + p.base * (1 - p.subsurface);  // diffuse ancestor
  const double rough = p.roughness;
  C3 sum;
  const auto alloc_ok = [&](const C3& w) { return std::fabs(avg(w)) >= kCut; };

  if (std::fabs(avg(base)) > kCut && diffuse_weight > kCut && alloc_ok(base * diffuse_weight)) {
    if (L.z > 0) {
      const double FV = schlick(I.z), FL = schlick(L.z);
      const double RR = rough * (dotd(L, I) + 1);
      const double f = (1 - 0.5 * FV) * (1 - 0.5 * FL) + RR * (FL + FV + FL * FV * (RR - 1));
      sum = sum + base * (diffuse_weight * f / kPiD * L.z);
    }
  }
  if (diffuse_weight > kCut && p.sheen > kCut) {
    const double lum = 0.2126 * base.r + 0.7152 * base.g + 0.0722 * base.b;
    const C3 tint = lum > 0 ? base * (1 / lum) : c3(1);
    const C3 sheen_color = c3(1 - p.sheen_tint) + tint * p.sheen_tint;
    const C3 w = sheen_color * (p.sheen * diffuse_weight);
    if (alloc_ok(w) && L.z > 0 && I.z >= 0) {
      const D3 H = normd({L.x + I.x, L.y + I.y, L.z + I.z});
      sum = sum + w * (schlick(dotd(L, H)) * L.z);
    }
  }
  if (specular_weight > kCut && (p.specular > kCut || p.metallic > kCut)) {
    const double aspect = std::sqrt(std::max(0.0, 1 - p.anisotropic * 0.9));
    const double r2 = rough * rough;
    const double cdlum = 0.3 * base.r + 0.6 * base.g + 0.1 * base.b;
    const C3 tint = cdlum > 0 ? base * (1 / cdlum) : c3(1);
    const C3 tmp = c3(1 - p.specular_tint) + tint * p.specular_tint;
    C3 cspec0 = (tmp * (p.specular * 0.08)) * (1 - p.metallic) + base * p.metallic;
    cspec0 = {sat(cspec0.r), sat(cspec0.g), sat(cspec0.b)};
    const double angle = p.anisotropic_rotation * 2 * kPiD;
    Microfacet m{Microfacet::kFresnel, sat(r2 / aspect), sat(r2 * aspect),
                 2 / (1 - std::sqrt(0.08 * p.specular)) - 1, cspec0};
    m.T = {std::cos(angle), std::sin(angle), 0};
    sum = sum + m.eval(I, L) * specular_weight;
  }
  if (final_transmission > kCut) {
    const C3 cspec0 = base * p.specular_tint + c3(1 - p.specular_tint);
    const C3 gw = c3(final_transmission);
    const double ra = rough * rough;
    if (alloc_ok(gw * fresnel)) {
      Microfacet r{Microfacet::kFresnel, sat(ra), sat(ra), ior,
                   {sat(cspec0.r), sat(cspec0.g), sat(cspec0.b)}};
      sum = sum + r.eval(I, L) * (final_transmission * fresnel);
    }
    const C3 rw = base * (final_transmission * std::max(1e-4, 1 - fresnel));
    if (alloc_ok(rw)) {
      const double tr = 1 - (1 - rough) * (1 - p.transmission_roughness);
      Microfacet t{Microfacet::kRefraction, sat(tr * tr), sat(tr * tr), ior, {}};
      if (!(std::fabs(ior - 1) < 1e-4)) sum = sum + t.eval(I, L) * rw;
    }
  }
  if (p.clearcoat > kCut) {
    const double a = sat(p.clearcoat_roughness * p.clearcoat_roughness);
    Microfacet c{Microfacet::kClearcoat, a, a, 1.5, c3(0.04)};
    c.clearcoat = p.clearcoat;
    sum = sum + c.eval(I, L);
  }
  return sum * (1 / std::fabs(L.z));
}

std::vector<Params> parameter_sets() {
  std::vector<Params> out;
  Params a;
  out.push_back(a);  // Blender's defaults
  Params all;
  all.base = {0.8, 0.3, 0.2};
  all.metallic = 0.2;
  all.specular = 0.6;
  all.specular_tint = 0.5;
  all.roughness = 0.45;
  all.sheen = 1;
  all.sheen_tint = 0.7;
  all.clearcoat = 1;
  all.clearcoat_roughness = 0.35;
  all.transmission = 0.5;
  all.transmission_roughness = 0.2;
  out.push_back(all);
  Params aniso;
  aniso.base = {0.9, 0.6, 0.3};
  aniso.metallic = 1;
  aniso.roughness = 0.6;
  aniso.anisotropic = 0.8;
  aniso.anisotropic_rotation = 0.2;
  out.push_back(aniso);
  Params glass;
  glass.base = {1, 0.9, 0.7};
  glass.transmission = 1;
  glass.roughness = 0.3;
  glass.ior = 1.33;
  glass.specular_tint = 0.4;
  out.push_back(glass);
  Params sss;
  sss.subsurface = 0.6;
  sss.subsurface_color = {0.9, 0.2, 0.1};
  sss.sheen = 0.5;
  sss.roughness = 0.9;
  sss.specular = 0.2;
  sss.clearcoat = 0.5;
  sss.clearcoat_roughness = 1.0;  // GTR1 at α = 1 is uniform
  out.push_back(sss);
  // Random sets over the whole parameter box (roughness kept off the singular case).
  PCG32 rng(77);
  for (int i = 0; i < 12; ++i) {
    Params r;
    r.base = {rng.uniform(), rng.uniform(), rng.uniform()};
    r.subsurface = rng.uniform() < 0.3 ? rng.uniform() : 0.0;
    r.subsurface_color = {rng.uniform(), rng.uniform(), rng.uniform()};
    r.metallic = rng.uniform();
    r.specular = rng.uniform();
    r.specular_tint = rng.uniform();
    r.roughness = 0.05 + 0.95 * rng.uniform();
    r.anisotropic = rng.uniform();
    r.anisotropic_rotation = rng.uniform();
    r.sheen = rng.uniform();
    r.sheen_tint = rng.uniform();
    r.clearcoat = rng.uniform();
    r.clearcoat_roughness = 0.05 + 0.95 * rng.uniform();
    r.ior = 1.0 + 1.5 * rng.uniform();
    r.transmission = rng.uniform() < 0.5 ? rng.uniform() : 0.0;
    r.transmission_roughness = rng.uniform();
    out.push_back(r);
  }
  return out;
}

}  // namespace

TEST(CyclesPrincipled, MatchesKernelTranscription) {
  PCG32 rng(1234);
  int compared = 0, nonzero = 0;
  for (const Params& p : parameter_sets()) {
    const BxDFPtr m = make("cycles_principled", p.to_params());
    for (int i = 0; i < 400; ++i) {
      const Vec3 wo = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
      const Vec3 wi = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
      if (std::fabs(wo.z) < 0.02f || std::fabs(wi.z) < 0.02f) continue;
      const RGB got = m->f(wo, wi);
      const C3 want = cycles_principled_f(p, d3(wo), d3(wi));
      for (int c = 0; c < 3; ++c) {
        const double w = c == 0 ? want.r : (c == 1 ? want.g : want.b);
        EXPECT_NEAR(got[c], w, 2e-3 * std::fabs(w) + 1e-5)
            << "wo (" << wo.x << ", " << wo.y << ", " << wo.z << ") wi (" << wi.x << ", " << wi.y
            << ", " << wi.z << ") channel " << c << " roughness " << p.roughness << " ior "
            << p.ior << " transmission " << p.transmission;
      }
      ++compared;
      nonzero += got.max_component() > 0.0f;
    }
  }
  EXPECT_GT(compared, 4000);
  EXPECT_GT(nonzero, compared / 2);
}

// Roughness 0 makes the specular, glass and (clearcoat roughness 0) clearcoat closures
// Cycles' singular case: each sample of one is a delta whose path weight is the closure
// weight × the Fresnel colour at the normal (refraction: the weight alone).
TEST(CyclesPrincipled, SingularClosuresCarryCyclesWeights) {
  Params p;
  p.base = {0.9, 0.7, 0.5};
  p.metallic = 0.3;
  p.roughness = 0.0;
  p.transmission = 0.6;
  p.clearcoat = 0.8;
  p.clearcoat_roughness = 0.0;
  p.ior = 1.5;
  const BxDFPtr m = make("cycles_principled", p.to_params());
  EXPECT_TRUE(m->flags() & kSpecular);
  EXPECT_TRUE(m->flags() & kDiffuse);
  for (const Vec3& wo : {normalize(Vec3(0.3f, 0.1f, 0.9f)), normalize(Vec3(-0.7f, 0.2f, 0.3f)),
                         normalize(Vec3(0.2f, 0.4f, -0.8f))}) {
    // The expected weights of the delta closures, from the transcription's formulas.
    const bool back = wo.z < 0;
    const double cos_o = std::fabs(wo.z), ior = back ? 1 / p.ior : p.ior;
    const double fresnel = fresnel_dielectric_cos(cos_o, ior);
    const double ft = p.transmission * (1 - p.metallic);
    const C3 base = p.base;
    const double cdlum = 0.3 * base.r + 0.6 * base.g + 0.1 * base.b;
    (void)cdlum;
    const C3 cspec0 = (c3(1) * (p.specular * 0.08)) * (1 - p.metallic) + base * p.metallic;
    const C3 spec = interpolate_fresnel(cos_o, 2 / (1 - std::sqrt(0.08 * p.specular)) - 1, cspec0) *
                    (1 - ft);
    const C3 glass_refl = interpolate_fresnel(cos_o, ior, c3(1)) * (ft * fresnel);
    const C3 refr = base * (ft * std::max(1e-4, 1 - fresnel));
    const C3 coat = c3(0.25 * p.clearcoat * fresnel_dielectric_cos(cos_o, 1.5));
    const C3 reflect_total = spec + glass_refl + coat;

    PCG32 rng(5);
    constexpr int kN = 200000;
    double refl[3] = {0, 0, 0}, trans[3] = {0, 0, 0};
    for (int i = 0; i < kN; ++i) {
      const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
      if (!s.valid() || !(s.flags & kSpecular)) continue;
      EXPECT_EQ(s.pdf, 1.0f);
      double* acc = s.flags & kReflection ? refl : trans;
      if (s.flags & kReflection) {
        EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
        EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
      } else {
        EXPECT_LT(s.wi.z * wo.z, 0.0f);
      }
      for (int c = 0; c < 3; ++c) acc[c] += s.f[c] * std::fabs(s.wi.z);
    }
    const double want_r[3] = {reflect_total.r, reflect_total.g, reflect_total.b};
    const double want_t[3] = {refr.r, refr.g, refr.b};
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(refl[c] / kN, want_r[c], 0.01 * want_r[c] + 2e-3) << "reflection channel " << c;
      EXPECT_NEAR(trans[c] / kN, want_t[c], 0.01 * want_t[c] + 2e-3) << "refraction channel " << c;
    }
    // f and pdf ignore the delta closures: the diffuse alone at the mirror direction.
    const Vec3 mirror(-wo.x, -wo.y, wo.z);
    const C3 want = cycles_principled_f(p, d3(wo), d3(mirror));
    EXPECT_NEAR(m->f(wo, mirror).r, want.r, 1e-3 * want.r + 1e-6);
  }
}

// Cycles switches to multiple scattering only above roughness 0.075 (specular) and 0.05
// (glass): below, multi_ggx is the single-scattering model (to float rounding: GGX computes
// the refraction roughness as 1 − (1 − r)(1 − 0), the fallback takes r).
TEST(CyclesPrincipled, MultiGGXSwitchesAtCyclesThresholds) {
  Params p;
  p.metallic = 0.5;
  p.transmission = 0.5;
  p.roughness = 0.05f;
  ParamSet single = p.to_params(), multi = p.to_params();
  multi.set("distribution", "multi_ggx");
  // transmission_roughness 0: single-scatter GGX uses it, the multi_ggx fallback does not, so
  // they agree when it is 0.
  const BxDFPtr a = make("cycles_principled", single), b = make("cycles_principled", multi);
  PCG32 rng(3);
  for (int i = 0; i < 500; ++i) {
    const Vec3 wo = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const Vec3 wi = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const RGB fa = a->f(wo, wi), fb = b->f(wo, wi);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(fa[ch], fb[ch], 1e-4f * fa[ch] + 1e-7f) << i;
  }
  p.roughness = 0.3;
  multi = p.to_params();
  multi.set("distribution", "multi_ggx");
  const BxDFPtr c = make("cycles_principled", p.to_params()), d = make("cycles_principled", multi);
  int differ = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 wo = sample_cosine_hemisphere(Point2(rng.uniform(), rng.uniform()));
    const Vec3 wi = sample_cosine_hemisphere(Point2(rng.uniform(), rng.uniform()));
    differ += !(c->f(wo, wi) == d->f(wo, wi));
  }
  EXPECT_GT(differ, 150);
}

// Cycles draws the clearcoat from GGX's visible normals (bsdf_microfacet_ggx_sample) and
// weights the sample by eval over its mixture pdf, in which the clearcoat reports
// G1(wo, α² 0.0625) D_GTR1 / (4 cos θo), not the density of that draw. Its BSDF-sampled
// estimate therefore converges to ∫ eval p_drawn / p_reported, not to ∫ eval, and sample_f
// (Cycles' sampler) must converge there too. Both integrals by quadrature, with GGX's visible
// normal density and Cycles' reported pdf written out here.
TEST(CyclesPrincipled, ClearcoatSamplesConvergeWhereCyclesDo) {
  Params p;
  p.base = {0.05, 0.05, 0.05};
  p.roughness = 0.6;
  p.clearcoat = 1.0;
  p.clearcoat_roughness = 0.6;
  const BxDFPtr m = make("cycles_principled", p.to_params());
  const CyclesPrincipled direct(cycles_principled_inputs(m->params()));
  EXPECT_FALSE(m->sample_f_is_exact());
  const double alpha = p.clearcoat_roughness * p.clearcoat_roughness, a2 = alpha * alpha;
  for (const double cos_o : {0.9, 0.45}) {
    const Vec3 wo(static_cast<float>(std::sqrt(1 - cos_o * cos_o)), 0.0f, static_cast<float>(cos_o));
    const CyclesPrincipled::Closures c = direct.closures(wo, false);
    const double share = c.sample_weight[CyclesPrincipled::kClearcoatClosure] / c.sample_total;
    ASSERT_GT(share, 0.1);
    // Quadrature over the hemisphere in (cos θi, φ).
    constexpr int kU = 600, kPhi = 1200;
    double cycles = 0, exact = 0;
    for (int i = 0; i < kU; ++i) {
      const double u = (i + 0.5) / kU, sin_i = std::sqrt(1 - u * u);
      for (int j = 0; j < kPhi; ++j) {
        const double phi = 2 * kPiD * (j + 0.5) / kPhi;
        const Vec3 wi(static_cast<float>(sin_i * std::cos(phi)), static_cast<float>(sin_i * std::sin(phi)),
                      static_cast<float>(u));
        const D3 h = normd({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
        const RGB f = m->f(wo, wi);
        const double eval = avg(C3{f.r, f.g, f.b}) * u;
        const double mixture = m->pdf(wo, wi);
        const double gtr1 = d_gtr1(h.z, alpha) * h.z / (4 * dotd(d3(wo), h));
        const double drawn = smith_g1(cos_o, a2) * d_ggx(h.z, a2) / (4 * cos_o);
        const double reported = smith_g1(cos_o, 0.0625) * d_gtr1(h.z, alpha) / (4 * cos_o);
        const double weight = (2 * kPiD / kPhi) / kU;
        exact += eval * weight;
        cycles += eval * (mixture + share * (drawn - gtr1)) / (mixture + share * (reported - gtr1)) *
                  weight;
      }
    }
    PCG32 rng(31);
    constexpr int kN = 400000;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < kN; ++k) {
      const BxDFSample s = m->sample_f(wo, Point2(rng.uniform(), rng.uniform()));
      const double w = s.valid() ? (s.f.r + s.f.g + s.f.b) / 3 * std::fabs(s.wi.z) / s.pdf : 0.0;
      sum += w;
      sum2 += w * w;
    }
    const double mean = sum / kN, sigma = std::sqrt((sum2 / kN - mean * mean) / kN);
    EXPECT_NEAR(mean, cycles, 4 * sigma) << "cos θo " << cos_o << ": exact " << exact;
    EXPECT_GT(std::fabs(cycles - exact), 10 * sigma) << "cos θo " << cos_o;  // the test can tell
  }
}

// The model class is built from plain values; make() maps the registry's parameters onto them.
TEST(CyclesPrincipled, PlainValueConstructorMatchesRegistry) {
  Params p = parameter_sets()[1];
  const BxDFPtr from_registry = make("cycles_principled", p.to_params());
  const CyclesPrincipledInputs in = cycles_principled_inputs(from_registry->params());
  const CyclesPrincipled direct(in);
  EXPECT_FLOAT_EQ(in.sheen, 1.0f);
  EXPECT_FLOAT_EQ(in.transmission_roughness, 0.2f);
  EXPECT_FALSE(in.multiscatter);
  PCG32 rng(8);
  for (int i = 0; i < 200; ++i) {
    const Vec3 wo = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const Vec3 wi = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    EXPECT_TRUE(direct.f(wo, wi) == from_registry->f(wo, wi));
    EXPECT_EQ(direct.pdf(wo, wi), from_registry->pdf(wo, wi));
  }
}

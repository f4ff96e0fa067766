#include "bxdf/models/cycles_principled.h"

#include <cmath>

#include "bxdf/model_support.h"
#include "bxdf/registry.h"
#include "bxdf/sampling.h"

namespace bxdf {

namespace {

// Cycles' CLOSURE_WEIGHT_CUTOFF (kernel/types.h) and singular thresholds (bsdf_microfacet.h).
constexpr float kWeightCutoff = 1e-5f;
constexpr float kSingularAlpha2 = 1e-7f;
constexpr float kSingularEta = 1e-4f;
constexpr float kOneBelowOne = 0x1.fffffep-1f;

float saturate(float x) { return clamp(x, 0.0f, 1.0f); }
RGB saturate(const RGB& c) { return {saturate(c.r), saturate(c.g), saturate(c.b)}; }

microfacet::MultiscatterSetup glass_ms_setup(float alpha, float eta, const RGB& color,
                                             const RGB& cspec0) {
  microfacet::MultiscatterSetup s;
  s.alpha_x = s.alpha_y = alpha;
  s.eta = eta;
  s.color = color;
  s.cspec0 = cspec0;
  s.fresnel = microfacet::MultiscatterFresnel::kInterpolated;
  return s;
}

}  // namespace

CyclesPrincipled::State CyclesPrincipled::make_state(const CyclesPrincipledInputs& in) {
  State st;
  // Without subsurface scattering: Cycles' diffuse-ancestor rule (see the header).
  st.base = in.subsurface_color * in.subsurface + in.base_color * (1.0f - in.subsurface);
  st.roughness = in.roughness;
  const float metallic = in.metallic;
  st.diffuse_weight = (1.0f - saturate(metallic)) * (1.0f - saturate(in.transmission));
  st.final_transmission = saturate(in.transmission) * (1.0f - saturate(metallic));
  st.specular_weight = 1.0f - st.final_transmission;
  st.ior = std::max(in.ior, 1e-5f);

  st.has_diffuse = std::fabs(st.base.average()) > kWeightCutoff && st.diffuse_weight > kWeightCutoff &&
                 std::fabs((st.base * st.diffuse_weight).average()) >= kWeightCutoff;

  // Sheen tint: the hue of the base colour at the film's (Rec.709) luminance.
  const float lum = st.base.luminance();
  const RGB sheen_tint = lum > 0.0f ? st.base / lum : RGB(1.0f);
  st.sheen_color = RGB(1.0f - in.sheen_tint) + sheen_tint * in.sheen_tint;
  st.sheen = in.sheen;
  st.has_sheen = st.diffuse_weight > kWeightCutoff && in.sheen > kWeightCutoff &&
               std::fabs((st.sheen_color * (in.sheen * st.diffuse_weight)).average()) >= kWeightCutoff;

  // Specular: Cycles' own luminance approximation for the tint.
  st.has_specular = st.specular_weight > kWeightCutoff &&
                  (in.specular > kWeightCutoff || metallic > kWeightCutoff);
  const float spec_eta = 2.0f / (1.0f - safe_sqrt(0.08f * in.specular)) - 1.0f;
  const float aspect = safe_sqrt(1.0f - in.anisotropic * 0.9f);
  const float r2 = in.roughness * in.roughness;
  const float ax = r2 / aspect, ay = r2 * aspect;
  const float cdlum = 0.3f * st.base.r + 0.6f * st.base.g + 0.1f * st.base.b;
  const RGB ctint = cdlum > 0.0f ? st.base / cdlum : RGB(1.0f);
  const RGB tint = RGB(1.0f - in.specular_tint) + ctint * in.specular_tint;
  const RGB cspec0 = tint * (in.specular * 0.08f) * (1.0f - metallic) + st.base * metallic;
  st.specular_multi = in.multiscatter && in.roughness > 0.075f;
  if (in.anisotropic_rotation != 0.0f) {
    const float angle = in.anisotropic_rotation * 2.0f * kPi;
    st.rot_cos = std::cos(angle);
    st.rot_sin = std::sin(angle);
  }
  if (st.specular_multi) {
    microfacet::MultiscatterSetup s;
    s.alpha_x = ax;
    s.alpha_y = ay;
    s.eta = spec_eta;
    s.color = st.base;
    s.cspec0 = cspec0;
    s.fresnel = microfacet::MultiscatterFresnel::kInterpolated;
    st.specular_ms = microfacet::MultiscatterGGXReflection(s);
    st.specular_singular = false;
  } else {
    const float sx = saturate(ax), sy = saturate(ay);
    st.specular_singular = sx * sy <= kSingularAlpha2;
    st.specular = {microfacet::GGX(sx, sy), spec_eta, saturate(cspec0)};
  }

  // Glass.
  st.has_glass = st.final_transmission > kWeightCutoff;
  const RGB glass_cspec0 = st.base * in.specular_tint + RGB(1.0f - in.specular_tint);
  st.glass_multi = in.multiscatter && in.roughness > 5e-2f;
  if (st.glass_multi) {
    st.glass_ms = microfacet::MultiscatterGGXGlass(glass_ms_setup(r2, st.ior, st.base, glass_cspec0));
    st.glass_ms_back =
        microfacet::MultiscatterGGXGlass(glass_ms_setup(r2, 1.0f / st.ior, st.base, glass_cspec0));
    st.glass_reflection_singular = st.glass_refraction_singular = false;
  } else {
    const float refl_alpha = saturate(r2);
    const float t_rough = in.multiscatter ? in.roughness
                                          : 1.0f - (1.0f - in.roughness) *
                                                       (1.0f - in.transmission_roughness);
    const float refr_alpha = saturate(t_rough * t_rough);
    st.glass_reflection = {microfacet::GGX(refl_alpha, refl_alpha), st.ior, saturate(glass_cspec0)};
    st.glass_refraction = {microfacet::GGX(refr_alpha, refr_alpha), st.ior};
    st.glass_reflection_singular = refl_alpha * refl_alpha <= kSingularAlpha2;
    // The |η − 1| test is per side, but |1/η − 1| < 1e-4 exactly when |η − 1| is (to 1e-8).
    st.glass_refraction_singular =
        refr_alpha * refr_alpha <= kSingularAlpha2 || std::fabs(st.ior - 1.0f) < kSingularEta;
  }

  st.clearcoat = in.clearcoat;
  st.has_clearcoat = in.clearcoat > kWeightCutoff;
  const float cc_alpha = saturate(in.clearcoat_roughness * in.clearcoat_roughness);
  st.clearcoat_lobe = {cc_alpha};
  st.clearcoat_singular = cc_alpha * cc_alpha <= kSingularAlpha2;

  // Flags from the closures that can exist.
  uint32_t flags = kReflection;
  bool glossy = false, delta = false;
  for (int k = 0; k < kClosureCount; ++k) {
    const bool built = (k == kDiffuseClosure && st.has_diffuse) || (k == kSheenClosure && st.has_sheen) ||
                       (k == kSpecularClosure && st.has_specular) ||
                       ((k == kGlassReflectionClosure || k == kGlassRefractionClosure) && st.has_glass &&
                        !(st.glass_multi && k == kGlassRefractionClosure)) ||
                       (k == kClearcoatClosure && st.has_clearcoat);
    if (!built) continue;
    if (k == kDiffuseClosure || k == kSheenClosure)
      flags |= kDiffuse;
    else if (st.singular(k))
      delta = true;
    else
      glossy = true;
  }
  if (glossy) flags |= kGlossy;
  if (delta) flags |= kSpecular;
  if (st.has_glass) flags |= kTransmission;
  st.flags = flags;

  // The branch-free f of the single-scattering configuration (singular closures weigh 0 and
  // get harmless α's, so that no 0 × NaN appears).
  st.single_scatter = !st.specular_multi && !st.glass_multi;
  cycles::PrincipledEvalKernel& k = st.kernel;
  k.diffuse_weight = st.has_diffuse ? st.base * st.diffuse_weight : RGB(0.0f);
  k.sheen_weight = st.has_sheen ? st.sheen_color * (st.sheen * st.diffuse_weight) : RGB(0.0f);
  k.roughness = st.roughness;
  const bool spec_on = st.has_specular && !st.specular_singular && !st.specular_multi;
  k.specular_weight = spec_on ? st.specular_weight : 0.0f;
  k.spec_ax = spec_on ? st.specular.ggx.alpha_x : 1.0f;
  k.spec_ay = spec_on ? st.specular.ggx.alpha_y : 1.0f;
  k.rot_cos = st.rot_cos;
  k.rot_sin = st.rot_sin;
  k.spec_fresnel = cycles::InterpolatedFresnel(st.specular.eta, st.specular.cspec0);
  k.final_transmission = st.has_glass ? st.final_transmission : 0.0f;
  k.eta_front = st.ior;
  k.eta_back = 1.0f / st.ior;
  k.glass_fresnel_front = cycles::InterpolatedFresnel(st.ior, st.glass_reflection.cspec0);
  k.glass_fresnel_back = cycles::InterpolatedFresnel(1.0f / st.ior, st.glass_reflection.cspec0);
  k.glass_reflection_on = st.glass_reflection_singular ? 0.0f : 1.0f;
  k.glass_refraction_on = st.glass_refraction_singular ? 0.0f : 1.0f;
  k.refl_alpha = st.glass_reflection_singular ? 1.0f : st.glass_reflection.ggx.alpha_x;
  k.refr_alpha = st.glass_refraction_singular ? 1.0f : st.glass_refraction.ggx.alpha_x;
  k.base = st.base;
  const bool cc_on = st.has_clearcoat && !st.clearcoat_singular;
  const float a = cc_on ? st.clearcoat_lobe.alpha : 1.0f;
  k.clearcoat = cc_on ? st.clearcoat : 0.0f;
  k.cc_alpha2 = a >= 1.0f ? 1.0f : a * a;
  k.cc_norm = a >= 1.0f ? kInvPi : (a * a - 1.0f) / (kPi * std::log(a * a));
  return st;
}

bool CyclesPrincipled::State::singular(int k) const {
  switch (k) {
    case kSpecularClosure: return specular_singular;
    case kGlassReflectionClosure: return glass_reflection_singular;
    case kGlassRefractionClosure: return glass_refraction_singular;
    case kClearcoatClosure: return clearcoat_singular;
    default: return false;
  }
}

Vec3 CyclesPrincipled::to_tangent(const Vec3& w) const {
  return {s_.rot_cos * w.x + s_.rot_sin * w.y, -s_.rot_sin * w.x + s_.rot_cos * w.y, w.z};
}
Vec3 CyclesPrincipled::from_tangent(const Vec3& w) const {
  return {s_.rot_cos * w.x - s_.rot_sin * w.y, s_.rot_sin * w.x + s_.rot_cos * w.y, w.z};
}

CyclesPrincipled::Closures CyclesPrincipled::closures(const Vec3& wo, bool back_face,
                                                     ClosurePick pick) const {
  Closures c;
  c.eta = back_face ? 1.0f / s_.ior : s_.ior;
  const auto add = [&](int k, const RGB& weight, float sample_factor) {
    const float sw = std::fabs(weight.average());
    if (!(sw >= kWeightCutoff)) return;  // bsdf_alloc's cut-off
    c.weight[k] = weight;
    c.sample_weight[k] = sw * sample_factor;
    c.sample_total += c.sample_weight[k];
  };
  if (s_.has_diffuse) add(kDiffuseClosure, s_.base * s_.diffuse_weight, 1.0f);
  if (s_.has_sheen)
    add(kSheenClosure, s_.sheen_color * (s_.sheen * s_.diffuse_weight),
        cycles::principled_sheen_sample_factor(wo));
  if (s_.has_specular) {
    const RGB fresnel = s_.specular_multi
                            ? microfacet::cycles_interpolate_fresnel(
                                  wo.z, s_.specular_ms.setup().eta, s_.specular_ms.setup().cspec0)
                            : s_.specular.fresnel_at_normal(wo);
    add(kSpecularClosure, RGB(s_.specular_weight), fresnel.average());
  }
  if (s_.has_glass) {
    if (s_.glass_multi) {
      const auto& lobe = back_face ? s_.glass_ms_back : s_.glass_ms;
      add(kGlassReflectionClosure, RGB(s_.final_transmission),
          microfacet::cycles_interpolate_fresnel(wo.z, c.eta, lobe.setup().cspec0).average());
    } else {
      const float fresnel = microfacet::cycles_fresnel_dielectric_cos(wo.z, c.eta);
      // Its sample weight, the interpolated Fresnel at wo.z, from the Fresnel just computed
      // and the side's F0 (the kernel's), rather than evaluating F twice more.
      const float f0 = (back_face ? s_.kernel.glass_fresnel_back : s_.kernel.glass_fresnel_front).f0;
      add(kGlassReflectionClosure, RGB(s_.final_transmission * fresnel),
          microfacet::cycles_interpolate_fresnel_of(fresnel, f0, s_.glass_reflection.cspec0).average());
      add(kGlassRefractionClosure, s_.base * (s_.final_transmission * std::max(1e-4f, 1.0f - fresnel)),
          1.0f);
    }
  }
  if (s_.has_clearcoat)
    add(kClearcoatClosure, RGB(s_.clearcoat), s_.clearcoat_lobe.fresnel_at_normal(wo));
  if (pick == ClosurePick::kDefensive)
    c.sample_total = raise_to_defensive_floor(c.sample_weight, kClosureCount);
  return c;
}

RGB CyclesPrincipled::lobe_f(int k, const Vec3& wo, const Vec3& wi, float eta,
                             bool back_face) const {
  switch (k) {
    case kDiffuseClosure: return RGB(cycles::principled_diffuse_f(wo, wi, s_.roughness));
    case kSheenClosure: return RGB(cycles::principled_sheen_f(wo, wi));
    case kSpecularClosure:
      return s_.specular_multi ? s_.specular_ms.eval(to_tangent(wo), to_tangent(wi))
                             : s_.specular.f(to_tangent(wo), to_tangent(wi));
    case kGlassReflectionClosure: {
      if (s_.glass_multi) return (back_face ? s_.glass_ms_back : s_.glass_ms).eval(wo, wi);
      cycles::GGXFresnelReflection lobe = s_.glass_reflection;
      lobe.eta = eta;
      return lobe.f(wo, wi);
    }
    case kGlassRefractionClosure: {
      return RGB(refraction_lobe(eta).f(wo, wi));
    }
    case kClearcoatClosure: return RGB(s_.clearcoat_lobe.f(wo, wi));
    default: return RGB(0.0f);
  }
}

float CyclesPrincipled::lobe_density(int k, const Vec3& wo, const Vec3& wi, float eta,
                                     bool back_face) const {
  switch (k) {
    case kDiffuseClosure:
    case kSheenClosure: return wi.z > 0.0f ? wi.z * kInvPi : 0.0f;
    case kSpecularClosure:
      return s_.specular_multi ? s_.specular_ms.density(to_tangent(wo), to_tangent(wi))
                             : s_.specular.density(to_tangent(wo), to_tangent(wi));
    case kGlassReflectionClosure: {
      if (s_.glass_multi) return (back_face ? s_.glass_ms_back : s_.glass_ms).density(wo, wi);
      return s_.glass_reflection.density(wo, wi);  // the reflection density does not use η
    }
    case kGlassRefractionClosure: {
      return refraction_lobe(eta).density(wo, wi);
    }
    case kClearcoatClosure: return s_.clearcoat_lobe.density(wo, wi);
    default: return 0.0f;
  }
}

bool CyclesPrincipled::lobe_sample(int k, const Vec3& wo, Point2 u, float eta, bool back_face,
                                   bool as_cycles, Vec3* wi) const {
  switch (k) {
    case kDiffuseClosure:
    case kSheenClosure:
      *wi = sample_cosine_hemisphere(u);
      return wi->z > 0.0f;
    case kSpecularClosure: {
      Vec3 w;
      if (s_.specular_multi) {
        const DirectionSample d = s_.specular_ms.sample_direction(to_tangent(wo), u);
        if (!d.ok) return false;
        w = d.wi;
      } else if (!s_.specular.sample(to_tangent(wo), u, &w)) {
        return false;
      }
      *wi = from_tangent(w);
      return true;
    }
    case kGlassReflectionClosure: {
      if (s_.glass_multi) {
        const DirectionSample d = (back_face ? s_.glass_ms_back : s_.glass_ms).sample_direction(wo, u);
        *wi = d.wi;
        return d.ok;
      }
      return s_.glass_reflection.sample(wo, u, wi);
    }
    case kGlassRefractionClosure: {
      return refraction_lobe(eta).sample(wo, u, wi, !as_cycles);
    }
    case kClearcoatClosure:
      return as_cycles ? s_.clearcoat_lobe.cycles_sample(wo, u, wi)
                       : s_.clearcoat_lobe.sample(wo, u, wi);
    default: return false;
  }
}

RGB CyclesPrincipled::eval_upper(const Vec3& wo, const Vec3& wi, const Closures& c,
                                 bool back_face, int skip) const {
  RGB sum(0.0f);
  for (int k = 0; k < kClosureCount; ++k) {
    if (c.sample_weight[k] == 0.0f && c.weight[k].is_black()) continue;
    if (s_.singular(k) || k == skip) continue;
    sum += c.weight[k] * lobe_f(k, wo, wi, c.eta, back_face);
  }
  return sum;
}

float CyclesPrincipled::density_upper(const Vec3& wo, const Vec3& wi, const Closures& c,
                                      bool back_face, float* refraction_excess) const {
  if (refraction_excess) *refraction_excess = 0.0f;
  if (!(c.sample_total > 0.0f)) return 0.0f;
  float sum = 0.0f;
  for (int k = 0; k < kClosureCount; ++k) {
    if (c.sample_weight[k] == 0.0f || s_.singular(k)) continue;
    if (k == kGlassRefractionClosure && refraction_excess) {
      // lobe_density's refraction, with its facets' share kept (one evaluation for both).
      float facet;
      const float density = refraction_lobe(c.eta).density(wo, wi, &facet);
      *refraction_excess = density - facet;
      sum += c.sample_weight[k] * density;
      continue;
    }
    sum += c.sample_weight[k] * lobe_density(k, wo, wi, c.eta, back_face);
  }
  return sum / c.sample_total;
}

RGB CyclesPrincipled::diffuse_closure_f(const Vec3& wo_in, const Vec3& wi_in) const {
  Vec3 wo = wo_in, wi = wi_in;
  if (!normalize_direction(wo) || !normalize_direction(wi) || wo.z == 0.0f) return RGB(0.0f);
  if (wo.z < 0.0f) {  // the back face: the lobes about the flipped normal, as eval does
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  // The closure weights do not depend on wo (closures() adds the same ones, same cut-off).
  RGB sum(0.0f);
  if (s_.has_diffuse)
    sum += s_.base * (s_.diffuse_weight * cycles::principled_diffuse_f(wo, wi, s_.roughness));
  if (s_.has_sheen)
    sum += s_.sheen_color * (s_.sheen * s_.diffuse_weight * cycles::principled_sheen_f(wo, wi));
  return sanitize_nonnegative(sum);
}

RGB CyclesPrincipled::eval_general(Vec3 wo, Vec3 wi) const {
  if (wo.z == 0.0f) return RGB(0.0f);
  const bool back = wo.z < 0.0f;
  if (back) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  return eval_upper(wo, wi, closures(wo, back), back);
}

float CyclesPrincipled::density(Vec3 wo, Vec3 wi, ClosurePick pick) const {
  if (wo.z == 0.0f) return 0.0f;
  const bool back = wo.z < 0.0f;
  if (back) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  return density_upper(wo, wi, closures(wo, back, pick), back);
}

RGB CyclesPrincipled::eval_density(Vec3 wo, Vec3 wi, float* density_out,
                                   ClosurePick pick) const {
  // Term for term what eval() and density() compute; the single-scatter kernel takes the
  // directions as given (it turns them to the upper side itself).
  const RGB kernel_f = s_.single_scatter ? s_.kernel.eval_one(wo, wi) : RGB(0.0f);
  if (wo.z == 0.0f) {
    *density_out = 0.0f;
    return kernel_f;
  }
  const bool back = wo.z < 0.0f;
  if (back) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  const Closures c = closures(wo, back, pick);
  *density_out = density_upper(wo, wi, c, back);
  return s_.single_scatter ? kernel_f : eval_upper(wo, wi, c, back);
}

BxDFSample CyclesPrincipled::sample_closures(Vec3 wo, Point2 u, bool as_cycles,
                                             ClosurePick pick) const {
  BxDFSample s;
  if (wo.z == 0.0f) return s;
  const bool back = wo.z < 0.0f;
  if (back) wo.z = -wo.z;
  const Closures c = closures(wo, back, pick);
  if (!(c.sample_total > 0.0f)) return s;

  // Pick a closure in proportion to its sample weight and stretch u.x back to [0, 1).
  const float target = u.x * c.sample_total;
  float start = 0.0f;
  int k = -1;
  for (int i = 0; i < kClosureCount; ++i) {
    if (c.sample_weight[i] == 0.0f) continue;
    k = i;
    if (target < start + c.sample_weight[i]) break;
    start += c.sample_weight[i];
  }
  const float chance = c.sample_weight[k] / c.sample_total;
  const Point2 v(std::min((target - start) / c.sample_weight[k], kOneBelowOne), u.y);

  Vec3 wi;
  if (s_.singular(k)) {
    // Cycles' singular sample: eval = pdf = 1e6 × the Fresnel colour of the normal facet, so
    // the path weight is the closure weight × that colour (refraction: the weight alone).
    RGB weight = c.weight[k];
    if (k == kGlassRefractionClosure) {
      if (!refract(wo, Vec3(0.0f, 0.0f, 1.0f), 1.0f / c.eta, &wi) || !(wi.z < 0.0f)) return s;
      s.flags = kTransmission | kSpecular;
    } else {
      wi = Vec3(-wo.x, -wo.y, wo.z);
      if (k == kSpecularClosure) weight *= s_.specular.fresnel_at_normal(wo);
      if (k == kGlassReflectionClosure)
        weight *= microfacet::cycles_interpolate_fresnel(wo.z, c.eta, s_.glass_reflection.cspec0);
      if (k == kClearcoatClosure) weight *= s_.clearcoat_lobe.fresnel_at_normal(wo);
      s.flags = kReflection | kSpecular;
    }
    s.f = weight / (chance * std::fabs(wi.z));
    s.pdf = 1.0f;
  } else {
    // A multiscatter closure is sampled as Cycles does, with its walk: its eval is weight ×
    // walk throughput × its approximate pdf, plus the other closures' eval there
    // (shader_bsdf_sample_closure with _shader_bsdf_multi_eval), over the mixture's pdf.
    const bool by_walk = as_cycles && walks(k);
    microfacet::WalkSample w;
    if (by_walk) {
      const bool specular = k == kSpecularClosure;
      w = specular ? s_.specular_ms.sample_walk(to_tangent(wo), v)
                   : (back ? s_.glass_ms_back : s_.glass_ms).sample_walk(wo, v);
      if (!w.ok) return s;
      wi = specular ? from_tangent(w.wi) : w.wi;
    } else if (!lobe_sample(k, wo, v, c.eta, back, as_cycles, &wi)) {
      return s;
    }
    // f of the multiple-scattering lobes hashes the directions: use the bits f() will see.
    if (back) wi.z = -wi.z;
    if (!microfacet::snap_to_unit(wi)) return s;
    if (back) wi.z = -wi.z;
    // The refraction's cover excess is wanted where Cycles' draw left the cover out.
    const bool drawn_without_cover = !by_walk && as_cycles && has_rough_refraction() && wi.z < 0.0f;
    float cover_excess = 0.0f;
    s.pdf = density_upper(wo, wi, c, back, drawn_without_cover ? &cover_excess : nullptr);
    if (by_walk) {
      if (wi.z == 0.0f) return BxDFSample();
      const float own_pdf = lobe_density(k, wo, wi, c.eta, back);
      s.f = c.weight[k] * w.weight * (own_pdf / std::fabs(wi.z)) + eval_upper(wo, wi, c, back, k);
    } else {
      s.f = back ? eval(Vec3(wo.x, wo.y, -wo.z), Vec3(wi.x, wi.y, -wi.z)) : eval(wo, wi);
    }
    if (as_cycles) {
      // Cycles' weight is eval over its mixture pdf, which differs from density() where its
      // draw does: without the refraction's cover samples (the density of what was drawn)
      // and with the clearcoat's reported pdf (not the density of its GGX draw, so Cycles'
      // clearcoat weight is biased, and this reproduces it). pdf stays the mixture's (MIS).
      float cycles_pdf = s.pdf;
      if (drawn_without_cover)
        cycles_pdf -= c.sample_weight[kGlassRefractionClosure] / c.sample_total * cover_excess;
      if (c.sample_weight[kClearcoatClosure] != 0.0f && !s_.clearcoat_singular && wi.z > 0.0f)
        cycles_pdf += c.sample_weight[kClearcoatClosure] / c.sample_total *
                      s_.clearcoat_lobe.cycles_pdf_excess(wo, wi);
      if (cycles_pdf != s.pdf) {
        if (!(cycles_pdf > 0.0f)) return BxDFSample();
        s.f *= s.pdf / cycles_pdf;
      }
    }
    s.flags = (wi.z > 0.0f ? kReflection : kTransmission) |
              (k == kDiffuseClosure || k == kSheenClosure ? kDiffuse : kGlossy);
  }
  if (back) wi.z = -wi.z;
  s.wi = wi;
  return s;
}

namespace {

// The one mapping from the registry's parameters to the inputs, for a ParamSet (create) and
// for plain values (place): `num`, `rgb` and `choice` read a parameter by its name.
template <class Num, class Color, class Choice>
CyclesPrincipledInputs principled_inputs(Num&& num, Color&& rgb, Choice&& choice) {
  CyclesPrincipledInputs in;
  in.base_color = rgb("base_color");
  in.subsurface = num("subsurface");
  in.subsurface_color = rgb("subsurface_color");
  in.metallic = num("metallic");
  in.specular = num("specular");
  in.specular_tint = num("specular_tint");
  in.roughness = num("roughness");
  in.anisotropic = num("anisotropic");
  in.anisotropic_rotation = num("anisotropic_rotation");
  in.sheen = num("sheen");
  in.sheen_tint = num("sheen_tint");
  in.clearcoat = num("clearcoat");
  in.clearcoat_roughness = num("clearcoat_roughness");
  in.ior = num("ior");
  in.transmission = num("transmission");
  in.transmission_roughness = num("transmission_roughness");
  in.multiscatter = choice("distribution") == "multi_ggx";
  return in;
}

// The parameter indices principled_inputs reads, in the order it reads them (its reads are
// straight-line code, so the order is fixed): found by name once, when the model is declared,
// and replayed at every hit, where reading by name compared strings per parameter.
std::vector<size_t> principled_read_order(const std::vector<ParamSpec>& params) {
  std::vector<size_t> order;
  auto record = [&](const char* name) {
    order.push_back(param_index(params, name));
    return order.back();
  };
  principled_inputs([&](const char* name) { record(name); return 0.0f; },
                    [&](const char* name) { record(name); return RGB(0.0f); },
                    [&](const char* name) -> const std::string& {
                      return params[record(name)].choices.front();
                    });
  return order;
}

CyclesPrincipledInputs principled_inputs_in_order(const std::vector<ParamSpec>& params,
                                                  const std::vector<size_t>& order,
                                                  const PlainValue* values) {
  size_t next = 0;
  return principled_inputs(
      [&](const char*) { return values[order[next++]].x; },
      [&](const char*) { return plain_rgb(values[order[next++]]); },
      // An enum's plain value is the index of its choice in the declaration.
      [&](const char*) -> const std::string& {
        const size_t i = order[next++];
        return params[i].choices[static_cast<size_t>(values[i].x)];
      });
}

}  // namespace

CyclesPrincipledInputs cycles_principled_inputs(const ParamSet& p) {
  return principled_inputs(
      [&](const char* name) { return static_cast<float>(p.number(name)); },
      [&](const char* name) { return to_rgb(p.rgb(name)); },
      [&](const char* name) -> const std::string& { return p.string(name); });
}

CyclesPrincipledInputs cycles_principled_inputs(const std::vector<ParamSpec>& params,
                                                const PlainValue* values) {
  return principled_inputs_in_order(params, principled_read_order(params), values);
}

ModelInfo cycles_principled_model() {
  ModelInfo m;
  m.name = "cycles_principled";
  m.doc = "Blender 3.4's Principled BSDF as Cycles builds it: every closure, weight and cut-off";
  m.params = {
      rgb_param("base_color", {0.8, 0.8, 0.8}, 0.0, 1.0, "Base Color"),
      float_param("subsurface", 0.0, 0.0, 1.0, "",
                  "Subsurface: mixes subsurface_color into the base colour (no SSS here)"),
      rgb_param("subsurface_color", {0.8, 0.8, 0.8}, 0.0, 1.0, "Subsurface Color"),
      float_param("metallic", 0.0, 0.0, 1.0, "", "Metallic"),
      float_param("specular", 0.5, 0.0, 1.0, "", "Specular: F0 = 0.08 specular"),
      float_param("specular_tint", 0.0, 0.0, 1.0, "", "Specular Tint towards the base hue"),
      float_param("roughness", 0.5, 0.0, 1.0, "", "Roughness; alpha = roughness^2"),
      float_param("anisotropic", 0.0, 0.0, 1.0, "", "Anisotropic: aspect sqrt(1 - 0.9 a)"),
      float_param("anisotropic_rotation", 0.0, 0.0, 1.0, "",
                  "Anisotropic Rotation of the tangent, in turns"),
      float_param("sheen", 0.0, 0.0, 1.0, "", "Sheen"),
      float_param("sheen_tint", 0.5, 0.0, 1.0, "", "Sheen Tint towards the base hue"),
      float_param("clearcoat", 0.0, 0.0, 1.0, "", "Clearcoat (a GTR1 layer of weight 0.25 clearcoat)"),
      float_param("clearcoat_roughness", 0.03, 0.0, 1.0, "", "Clearcoat Roughness"),
      float_param("ior", 1.45, 0.0, 1000.0, "", "IOR of the transmission (inverted on back faces)"),
      float_param("transmission", 0.0, 0.0, 1.0, "", "Transmission"),
      float_param("transmission_roughness", 0.0, 0.0, 1.0, "",
                  "Transmission Roughness (GGX only): 1 - (1 - r)(1 - t)"),
      enum_param("distribution", "ggx", {"ggx", "multi_ggx"},
                 "GGX, or Multiscatter GGX (above roughness 0.075 / 0.05 for the glass)"),
  };
  m.create = [](const ParamSet& p) -> std::unique_ptr<BxDF> {
    return std::make_unique<CyclesPrincipled>(cycles_principled_inputs(p));
  };
  m.place = [params = m.params, order = principled_read_order(m.params)](
                const PlainValue* v, ClosureArena& arena) -> const BxDF* {
    return arena.make<CyclesPrincipled>(principled_inputs_in_order(params, order, v));
  };
  m.place_size = sizeof(CyclesPrincipled);
  return m;
}

}  // namespace bxdf

#include "bxdf/bsdf.h"

#include "bxdf/cosine_above_plane.h"

#include <string>

namespace bxdf {

namespace {

// A component contributes to a pair of directions only when its kind (reflection or
// transmission) agrees with what the geometric normal says the pair is.
bool agrees_with_geometry(uint32_t flags, bool reflect) {
  return reflect ? (flags & kReflection) != 0 : (flags & kTransmission) != 0;
}

// A sample of the cosine lobe above the triangle's plane (local horizon normal g); f is the
// model's own at that direction.
BxDFSample sample_clipped_lobe(const BxDF& b, const Vec3& wo, const Vec3& g, Point2 u) {
  BxDFSample s;
  const CosineAbovePlane lobe(g);
  s.wi = lobe.sample(u);
  s.pdf = lobe.pdf(s.wi);
  s.f = b.f(wo, s.wi);
  s.flags = kReflection | kDiffuse;
  return s;
}

// Cycles' bump_shadowing_term (closure/bsdf.h, after Chiang et al., "Taming the Shadow
// Terminator"): `ns` the shading normal, `n` the closure's perturbed one, `wi` the light.
float bump_shadowing_term(Vec3 ns, const Vec3& n, const Vec3& wi) {
  const float cos_ni = dot(n, wi);
  if (cos_ni < 0.0f) ns = -ns;
  const float denominator = cos_ni * dot(ns, n);
  const float g = denominator != 0.0f ? dot(ns, wi) / denominator : 0.0f;
  if (g >= 1.0f) return 1.0f;
  if (!(g >= 0.0f)) return 0.0f;
  const float g2 = g * g;
  return -g2 * g + g2 + g;  // smooth at the perpendicular angle
}

}  // namespace

void BSDF::add(const BxDF* component, const RGB& weight, const Frame* frame, bool bump_shadowed) {
  if (!component) throw ParameterError("BSDF::add: component is null");
  if (count_ >= kMaxComponents)
    throw ParameterError("BSDF::add: at most " + std::to_string(kMaxComponents) +
                         " components, got one more");
  if (!finite_nonnegative(weight))
    throw ParameterError("BSDF::add: weight must be in [0, inf) per channel");
  components_[count_] = component;
  weights_[count_] = weight;
  // Cycles' sample_weight: the average of the closure's whole weight, its Color included.
  sample_weights_[count_] = weight.average() * component->closure_sample_weight();
  frames_[count_] = frame ? *frame : frame_;
  const bool perturbed = frame && !(frame->n == frame_.n);
  bump_shadowing_[count_] = !perturbed    ? BumpShadowing::None
                            : bump_shadowed ? BumpShadowing::Whole
                            : component->has_diffuse_closure_lobes() ? BumpShadowing::DiffuseLobes
                                                                   : BumpShadowing::None;
  ++count_;
}

void BSDF::set_sampling_horizon(const Vec3& true_geometric_normal) {
  // A plane within float noise of the shading frame's clips nothing (flat shading keeps its
  // plain cosine samples, bit for bit).
  has_horizon_ = dot(true_geometric_normal, frame_.n) < 1.0f - 1e-7f;
  horizon_ = true_geometric_normal;
}

void BSDF::use_defensive_sampling() {
  if (defensive_) return;  // the raised weights are not raised again
  defensive_ = true;
  if (count_ == 1) {
    component_picks_defensively_ = true;
    return;
  }
  raise_to_defensive_floor(&sample_weights_[0], count_);
}

float BSDF::component_pdf(int i, const Vec3& wo, const Vec3& wi) const {
  Vec3 g;
  if (clipped_lobe(i, wo, &g)) return cosine_above_plane_pdf(wi, g);
  return model_pdf(*components_[i], wo, wi);
}

int BSDF::num_components(uint32_t mask) const {
  int n = 0;
  for (int i = 0; i < count_; ++i)
    if (components_[i]->matches(mask)) ++n;
  return n;
}

bool BSDF::has_non_delta() const {
  for (int i = 0; i < count_; ++i)
    if (!components_[i]->is_delta()) return true;
  return false;
}

bool BSDF::has_transmission() const {
  for (int i = 0; i < count_; ++i)
    if (components_[i]->flags() & kTransmission) return true;
  return false;
}

RGB BSDF::component_f(int i, const Vec3& wo, const Vec3& wi, const Vec3& wi_world) const {
  return bump_shadowed(i, components_[i]->f(wo, wi), wo, wi, wi_world);
}

RGB BSDF::component_f_pdf(int i, const Vec3& wo, const Vec3& wi, const Vec3& wi_world,
                          bool scatters, bool weighs, float* pdf) const {
  const BxDF& b = *components_[i];
  Vec3 g;
  if (clipped_lobe(i, wo, &g)) {  // component_pdf's clipped case
    if (weighs) *pdf = cosine_above_plane_pdf(wi, g);
    return scatters ? component_f(i, wo, wi, wi_world) : RGB(0.0f);
  }
  if (scatters && weighs) return bump_shadowed(i, model_f_pdf(b, wo, wi, pdf), wo, wi, wi_world);
  if (weighs) *pdf = model_pdf(b, wo, wi);
  return scatters ? component_f(i, wo, wi, wi_world) : RGB(0.0f);
}

RGB BSDF::apply_bump_shadowing(int i, RGB f, const Vec3& wo, const Vec3& wi,
                                const Vec3& wi_world) const {
  if (bump_shadowing_[i] == BumpShadowing::Whole) {
    f *= bump_shadowing_term(frame_.n, frames_[i].n, wi_world);
  } else if (bump_shadowing_[i] == BumpShadowing::DiffuseLobes) {
    // f − (1 − term) · diffuse part, so the other lobes keep their full value.
    const float term = bump_shadowing_term(frame_.n, frames_[i].n, wi_world);
    if (term < 1.0f)
      f = sanitize_nonnegative(f - components_[i]->diffuse_closure_f(wo, wi) * (1.0f - term));
  }
  return f;
}

template <class Term>
RGB BSDF::weighted_sum(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask,
                       Term term) const {
  const bool reflect = dot(wi_world, ng_) * dot(wo_world, ng_) > 0.0f;
  RGB sum(0.0f);
  for (int i = 0; i < count_; ++i) {
    const BxDF& b = *components_[i];
    if (!b.matches(mask) || !agrees_with_geometry(b.flags(), reflect)) continue;
    const Vec3 wo = frames_[i].to_local(wo_world);
    if (wo.z == 0.0f) continue;
    const Vec3 wi = frames_[i].to_local(wi_world);
    sum += weights_[i] * term(component_f(i, wo, wi, wi_world), wi);
  }
  return sum;
}

void BSDF::f_f_cos_pdf(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask, RGB* f_sum,
                       RGB* f_cos_sum, float* pdf_out, const SampledComponent* sampled) const {
  // f(), f_cos() and pdf() in one pass, term for term as they compute them.
  const bool reflect = dot(wi_world, ng_) * dot(wo_world, ng_) > 0.0f;
  RGB f_total(0.0f), f_cos_total(0.0f);
  float pdf_sum = 0.0f, total_weight = 0.0f;
  for (int i = 0; i < count_; ++i) {
    const BxDF& b = *components_[i];
    if (!b.matches(mask)) continue;
    total_weight += sample_weights_[i];
    const bool scatters = agrees_with_geometry(b.flags(), reflect);
    if (sampled && i == sampled->index) {
      // Its own sample's f and pdf: the same values (every model's sample agrees with its f
      // and pdf, test ModelSampling.SampleReturnsPdfAndF), as Cycles' bsdf_sample hands them
      // back and only the other closures are evaluated.
      const BxDFSample& s = sampled->sample;
      pdf_sum += sample_weights_[i] * s.pdf;
      if (!scatters) continue;
      const RGB f = bump_shadowed(i, s.f, sampled->wo, s.wi, wi_world);
      f_total += weights_[i] * f;
      f_cos_total += weights_[i] * (f * abs_cos_theta(s.wi));
      continue;
    }
    const bool weighs = sample_weights_[i] != 0.0f;
    if (!weighs && !scatters) continue;
    const Vec3 wo = frames_[i].to_local(wo_world);
    if (wo.z == 0.0f) continue;
    const Vec3 wi = frames_[i].to_local(wi_world);
    float pdf = 0.0f;
    const RGB f = component_f_pdf(i, wo, wi, wi_world, scatters, weighs, &pdf);
    if (weighs) pdf_sum += sample_weights_[i] * pdf;
    if (!scatters) continue;
    f_total += weights_[i] * f;
    f_cos_total += weights_[i] * (f * abs_cos_theta(wi));
  }
  *f_sum = f_total;
  *f_cos_sum = f_cos_total;
  *pdf_out = total_weight > 0.0f ? pdf_sum / total_weight : 0.0f;
}

RGB BSDF::f(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask) const {
  return weighted_sum(wo_world, wi_world, mask, [](const RGB& f, const Vec3&) { return f; });
}

RGB BSDF::f_cos(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask) const {
  return weighted_sum(wo_world, wi_world, mask,
                      [](const RGB& f, const Vec3& wi) { return f * abs_cos_theta(wi); });
}

float BSDF::pdf(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask) const {
  float sum = 0.0f, total_weight = 0.0f;
  for (int i = 0; i < count_; ++i) {
    const BxDF& b = *components_[i];
    if (!b.matches(mask)) continue;
    total_weight += sample_weights_[i];
    if (sample_weights_[i] == 0.0f) continue;
    const Vec3 wo = frames_[i].to_local(wo_world);
    if (wo.z == 0.0f) continue;
    sum += sample_weights_[i] * component_pdf(i, wo, frames_[i].to_local(wi_world));
  }
  return total_weight > 0.0f ? sum / total_weight : 0.0f;
}

RGB BSDF::f_cos_pdf(const Vec3& wo_world, const Vec3& wi_world, float* pdf_out) const {
  RGB f, f_cos;
  f_f_cos_pdf(wo_world, wi_world, kAll, &f, &f_cos, pdf_out);
  return f_cos;
}

BSDFSample BSDF::sample_f(const Vec3& wo_world, Point2 u, uint32_t mask) const {
  BSDFSample out;
  float total_weight = 0.0f;
  int last = -1;
  for (int i = 0; i < count_; ++i)
    if (components_[i]->matches(mask) && sample_weights_[i] > 0.0f) {
      total_weight += sample_weights_[i];
      last = i;
    }
  if (last < 0) return out;

  // Choose the component with u.x, then stretch the part of u.x inside its slot back to [0, 1).
  const float target = u.x * total_weight;
  int picked = last;
  float start = 0.0f;
  for (int i = 0; i < count_; ++i) {
    if (!components_[i]->matches(mask) || !(sample_weights_[i] > 0.0f)) continue;
    if (i == last || target < start + sample_weights_[i]) {
      picked = i;
      break;
    }
    start += sample_weights_[i];
  }
  const float chance = sample_weights_[picked] / total_weight;
  const float remapped = (target - start) / sample_weights_[picked];
  const Point2 u_remapped(clamp(remapped, 0.0f, 0x1.fffffep-1f), u.y);

  const BxDF& b = *components_[picked];
  const Frame& frame = frames_[picked];
  const Vec3 wo = frame.to_local(wo_world);
  if (wo.z == 0.0f) return out;
  // Initialised from the call, not assigned: an assigned copy read the callee's 4-byte stores
  // back in 16-byte pieces, a store-forwarding stall perf put at ~8% of PathTracer::step.
  Vec3 g;
  const BxDFSample s = clipped_lobe(picked, wo, &g) ? sample_clipped_lobe(b, wo, g, u_remapped)
                                                     : model_sample(b, wo, u_remapped);
  if (!s.valid()) return out;

  out.wi = frame.to_world(s.wi);
  out.flags = s.flags != 0 ? s.flags : b.flags();
  out.component = picked;

  if (b.is_delta() || (s.flags & kSpecular)) {
    // A delta lobe (a delta model, or the delta part of a mixed one such as a Principled BSDF
    // at roughness 0) cannot be evaluated by the others; only the selection probability changes.
    out.f = weights_[picked] * s.f;
    out.f_cos = out.f * abs_cos_theta(s.wi);
    out.pdf = s.pdf * chance;
    // Geometry still decides: a sampled reflection that ends up below the geometric surface (or
    // a refraction that stays above it), possible with shading normals, is dropped.
    const bool reflect = dot(out.wi, ng_) * dot(wo_world, ng_) > 0.0f;
    if (!agrees_with_geometry(out.flags, reflect)) out = BSDFSample{};
    return out;
  }

  // Non-delta: f and pdf of the whole mixture, with the geometric-normal test, as f() does
  // (one pass over the components for the three; the picked one's from its sample).
  const SampledComponent own{picked, wo, s};
  f_f_cos_pdf(wo_world, out.wi, mask, &out.f, &out.f_cos, &out.pdf, &own);
  // Every return names `out`, so it is built in the caller's slot (no 48-byte copy).
  if (!(out.pdf > 0.0f)) out = BSDFSample{};
  return out;
}

}  // namespace bxdf

#include "bxdf/bsdf.h"

#include <string>

namespace bxdf {

namespace {

// A component contributes to a pair of directions only when its kind (reflection or
// transmission) agrees with what the geometric normal says the pair is.
bool agrees_with_geometry(uint32_t flags, bool reflect) {
  return reflect ? (flags & kReflection) != 0 : (flags & kTransmission) != 0;
}

}  // namespace

void BSDF::add(const BxDF* component) {
  if (!component) throw ParameterError("BSDF::add: component is null");
  if (count_ >= kMaxComponents)
    throw ParameterError("BSDF::add: at most " + std::to_string(kMaxComponents) +
                         " components, got one more");
  components_[count_++] = component;
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

RGB BSDF::f(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask) const {
  const Vec3 wo = to_local(wo_world), wi = to_local(wi_world);
  if (wo.z == 0.0f) return RGB(0.0f);
  const bool reflect = dot(wi_world, ng_) * dot(wo_world, ng_) > 0.0f;
  RGB sum(0.0f);
  for (int i = 0; i < count_; ++i) {
    const BxDF& b = *components_[i];
    if (b.matches(mask) && agrees_with_geometry(b.flags(), reflect)) sum += b.f(wo, wi);
  }
  return sum;
}

float BSDF::pdf(const Vec3& wo_world, const Vec3& wi_world, uint32_t mask) const {
  if (count_ == 0) return 0.0f;
  const Vec3 wo = to_local(wo_world), wi = to_local(wi_world);
  if (wo.z == 0.0f) return 0.0f;
  float sum = 0.0f;
  int matching = 0;
  for (int i = 0; i < count_; ++i) {
    const BxDF& b = *components_[i];
    if (!b.matches(mask)) continue;
    ++matching;
    sum += b.pdf(wo, wi);
  }
  return matching > 0 ? sum / static_cast<float>(matching) : 0.0f;
}

BSDFSample BSDF::sample_f(const Vec3& wo_world, Point2 u, uint32_t mask) const {
  BSDFSample out;
  const int matching = num_components(mask);
  if (matching == 0) return out;

  // Choose the component with u.x, then stretch the part of u.x inside its slot back to [0, 1).
  const float scaled = u.x * static_cast<float>(matching);
  const int chosen = std::min(static_cast<int>(scaled), matching - 1);
  const BxDF* picked = nullptr;
  for (int i = 0, seen = 0; i < count_; ++i) {
    if (!components_[i]->matches(mask)) continue;
    if (seen++ == chosen) {
      picked = components_[i];
      break;
    }
  }
  const Point2 u_remapped(std::min(scaled - static_cast<float>(chosen), 0x1.fffffep-1f), u.y);

  const Vec3 wo = to_local(wo_world);
  if (wo.z == 0.0f) return out;
  const BxDFSample s = picked->sample_f(wo, u_remapped);
  if (!s.valid()) return out;

  out.wi = to_world(s.wi);
  out.flags = s.flags != 0 ? s.flags : picked->flags();
  out.f = s.f;
  out.pdf = s.pdf;

  if (picked->is_delta() || (s.flags & kSpecular)) {
    // A delta lobe (a delta model, or the delta part of a mixed one such as a Principled BSDF
    // at roughness 0) cannot be evaluated by the others; only the selection probability changes.
    out.pdf /= static_cast<float>(matching);
    // Geometry still decides: a sampled reflection that ends up below the geometric surface (or
    // a refraction that stays above it), possible with shading normals, is dropped.
    const bool reflect = dot(out.wi, ng_) * dot(wo_world, ng_) > 0.0f;
    if (!agrees_with_geometry(out.flags, reflect)) return BSDFSample{};
    return out;
  }

  if (matching > 1) {
    for (int i = 0; i < count_; ++i) {
      const BxDF& b = *components_[i];
      if (&b != picked && b.matches(mask)) out.pdf += b.pdf(wo, s.wi);
    }
  }
  out.pdf /= static_cast<float>(matching);
  // Non-delta: f of the whole mixture, with the geometric-normal test, as f() does.
  out.f = f(wo_world, out.wi, mask);
  if (!(out.pdf > 0.0f)) return BSDFSample{};
  return out;
}

}  // namespace bxdf

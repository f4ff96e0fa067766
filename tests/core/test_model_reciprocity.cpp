// Helmholtz reciprocity for every model and curated parameter set: f(wo, wi) = f(wi, wo) for
// reflection. For transmission through a refractive boundary the models follow pbrt's
// radiance convention, in which the BTDF carries (η_wo/η_wi)² (radiance is compressed going
// into the denser medium), so that f(wi, wo) = (η_wi/η_wo)² f(wo, wi); transmission without
// refraction (lambertian_transmission) is plainly symmetric.
#include <gtest/gtest.h>

#include <cstdio>

#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"
#include "model_grid.h"

using namespace bxdf;
using namespace bxdf::test;

namespace {

constexpr float kRelative = 1e-4f;
constexpr float kAbsolute = 1e-6f;

class ModelReciprocity : public ::testing::TestWithParam<std::string> {};

// The pairs: the incident directions against each other, random pairs over the sphere, and
// pairs near the horizon.
std::vector<std::pair<Vec3, Vec3>> direction_pairs() {
  std::vector<std::pair<Vec3, Vec3>> pairs;
  for (const auto& a : incident_directions())
    for (const auto& b : incident_directions()) pairs.push_back({a.wo, b.wo});
  PCG32 rng(42);
  for (int i = 0; i < 3000; ++i) {
    Vec3 a = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    Vec3 b = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    if (i % 4 == 0) b.z = std::copysign(1e-3f * rng.uniform(), b.z);  // near-grazing
    pairs.push_back({normalize(a), normalize(b)});
  }
  return pairs;
}

}  // namespace

TEST_P(ModelReciprocity, FIsReciprocal) {
  const std::string& model = GetParam();
  static const std::vector<std::pair<Vec3, Vec3>> pairs = direction_pairs();
  for (const GridEntry& e : grid_for(model)) {
    if (!e.not_reciprocal.empty()) continue;  // the entry says why
    const BxDFPtr m = make_entry(model, e);
    float eta_outside = 1.0f, eta_inside = 1.0f;
    const bool refracts = refractive_indices(*m, &eta_outside, &eta_inside);
    // Cycles' refraction has the inverse rule (no radiance scaling).
    const bool cycles_refracts = cycles_refractive_indices(*m, &eta_outside, &eta_inside);
    int failures = 0;
    std::string first;
    for (const auto& [wo, wi] : pairs) {
      const RGB forward = m->f(wo, wi), backward = m->f(wi, wo);
      float scale = 1.0f;  // backward = scale × forward
      if (refracts && wo.z * wi.z < 0.0f) {
        const float eta_wo = wo.z > 0 ? eta_outside : eta_inside;
        const float eta_wi = wi.z > 0 ? eta_outside : eta_inside;
        scale = (eta_wi / eta_wo) * (eta_wi / eta_wo);
      }
      if (cycles_refracts && wo.z * wi.z < 0.0f) {
        const float eta_wo = wo.z > 0 ? eta_outside : eta_inside;
        const float eta_wi = wi.z > 0 ? eta_outside : eta_inside;
        scale = (eta_wo / eta_wi) * (eta_wo / eta_wi);
      }
      for (int c = 0; c < 3; ++c) {
        const float expect = forward[c] * scale;
        if (std::fabs(backward[c] - expect) <=
            kRelative * std::max(backward[c], expect) + kAbsolute)
          continue;
        if (failures++ == 0) {
          char buf[300];
          std::snprintf(buf, sizeof buf,
                        "wo (%.6g, %.6g, %.6g) wi (%.6g, %.6g, %.6g) channel %d: f(wo,wi) %.7g "
                        "f(wi,wo) %.7g expected %.7g",
                        wo.x, wo.y, wo.z, wi.x, wi.y, wi.z, c, forward[c], backward[c], expect);
          first = buf;
        }
      }
    }
    if (const char* reason = non_reciprocal_reason(model)) {
      // Delta entries have f = 0 everywhere and are trivially reciprocal.
      if (!m->is_delta()) {
        EXPECT_GT(failures, 0) << describe(model, e) << " is documented as non-reciprocal ("
                               << reason << ") but was reciprocal on every pair";
      }
      continue;
    }
    EXPECT_EQ(failures, 0) << describe(model, e) << ": " << failures << " non-reciprocal values in "
                           << pairs.size() << " pairs; first: " << first;
  }
}

INSTANTIATE_TEST_SUITE_P(AllModels, ModelReciprocity,
                         ::testing::ValuesIn(registered_model_names()),
                         [](const auto& info) { return info.param; });

// Cycles' bump_shadowing_term on the Principled BSDF: Cycles builds the diffuse and sheen lobes
// as diffuse closures (CLOSURE_IS_BSDF_DIFFUSE), so a perturbed normal darkens just those two
// at grazing light; the specular lobe keeps its full value. Checked against models that have
// only the diffuse and sheen lobes (specular 0, metallic 0: no specular closure is built),
// and against the whole-closure term the BSDF already applies to a Diffuse BSDF.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/bsdf.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

ParamSet principled(float specular, float sheen) {
  ParamSet p;
  p.set("base_color", RGBValue{0.7, 0.4, 0.2});
  p.set("roughness", 0.45);
  p.set("specular", double(specular));
  p.set("sheen", double(sheen));
  p.set("sheen_tint", 0.3);
  return p;
}

Vec3 random_direction(PCG32& rng) {
  return sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
}

void expect_rgb_near(const RGB& a, const RGB& b, float tol) {
  EXPECT_NEAR(a.r, b.r, tol);
  EXPECT_NEAR(a.g, b.g, tol);
  EXPECT_NEAR(a.b, b.b, tol);
}

}  // namespace

TEST(PrincipledBumpShadowing, DiffuseClosurePartIsTheDiffuseAndSheenLobes) {
  const BxDFPtr full = make("cycles_principled", principled(0.5f, 0.7f));
  const BxDFPtr lobes = make("cycles_principled", principled(0.0f, 0.7f));
  EXPECT_TRUE(full->has_diffuse_closure_lobes());
  EXPECT_FALSE(make("cycles_glossy")->has_diffuse_closure_lobes());
  PCG32 rng(7);
  int nonzero = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 wo = random_direction(rng), wi = random_direction(rng);
    const RGB part = full->diffuse_closure_f(wo, wi);
    expect_rgb_near(part, lobes->f(wo, wi), 1e-5f);
    expect_rgb_near(lobes->diffuse_closure_f(wo, wi), lobes->f(wo, wi), 1e-5f);
    if (part.average() > 0.0f) ++nonzero;
  }
  EXPECT_GT(nonzero, 500);  // both faces: wo and wi on one side
}

TEST(PrincipledBumpShadowing, APerturbedNormalDarkensOnlyTheDiffuseAndSheenLobes) {
  const BxDFPtr full = make("cycles_principled", principled(0.5f, 0.7f));
  const BxDFPtr lobes = make("cycles_principled", principled(0.0f, 0.7f));
  const Frame shading;  // normal +Z
  const Frame perturbed = Frame::from_normal_tangent(normalize(Vec3(0.5f, 0.2f, 1.0f)), Vec3(1, 0, 0));
  BSDF textured(shading, shading.n);
  textured.add(full.get(), RGB(1.0f), &perturbed);
  BSDF whole(shading, shading.n);  // the lobes alone, darkened as a Diffuse BSDF is
  whole.add(lobes.get(), RGB(1.0f), &perturbed, /*bump_shadowed=*/true);
  BSDF unshadowed(shading, shading.n);
  unshadowed.add(lobes.get(), RGB(1.0f), &perturbed);
  PCG32 rng(11);
  int darkened = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 wo = random_direction(rng), wi = random_direction(rng);
    const RGB expected = full->f(perturbed.to_local(wo), perturbed.to_local(wi)) -
                         lobes->f(perturbed.to_local(wo), perturbed.to_local(wi)) +
                         whole.f(wo, wi);
    const bool reflect = wo.z * wi.z > 0.0f;  // the geometric test the BSDF applies
    expect_rgb_near(textured.f(wo, wi), reflect ? sanitize_nonnegative(expected) : RGB(0.0f), 2e-5f);
    // The lobes-only model is a Principled too: it gets the term without being marked.
    expect_rgb_near(unshadowed.f(wo, wi), whole.f(wo, wi), 2e-6f);
    if (reflect && whole.f(wo, wi).average() < 0.9f * lobes->f(perturbed.to_local(wo), perturbed.to_local(wi)).average())
      ++darkened;
  }
  EXPECT_GT(darkened, 50);  // the term does act
}

TEST(PrincipledBumpShadowing, TheShadingNormalItselfIsNotDarkened) {
  const BxDFPtr full = make("cycles_principled", principled(0.5f, 0.7f));
  const Frame shading = Frame::from_normal_tangent(normalize(Vec3(0.1f, -0.3f, 1.0f)), Vec3(1, 0, 0));
  BSDF bsdf(shading, shading.n);
  bsdf.add(full.get(), RGB(1.0f), &shading);
  PCG32 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 wo = random_direction(rng), wi = random_direction(rng);
    if (dot(wo, shading.n) * dot(wi, shading.n) <= 0.0f) continue;
    expect_rgb_near(bsdf.f(wo, wi), full->f(shading.to_local(wo), shading.to_local(wi)), 1e-6f);
  }
}

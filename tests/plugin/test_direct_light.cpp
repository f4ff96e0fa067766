// Analytic truth: a sphere lit by one light, direct light only, pixel-centre filter. With one
// delta light and a deterministic camera ray the estimate has no noise, so every lit pixel must
// equal f·I·cosθ/d² (point), f·I·spot(α)·cosθ/d² (spot) or f·E·cosθ (sun) to float precision,
// with f from the core's model and the geometry from a brute-force intersection in the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"
#include "reference_geometry.h"

using namespace bxdf;
using namespace bxdf::render;
using bxdf::test::D3;

namespace {

constexpr int kSize = 32;

Vec3 to_vec3(const D3& d) { return Vec3(float(d.x), float(d.y), float(d.z)); }

struct LitSphere {
  Mesh sphere = make_uv_sphere(Vec3(0, 0, 0), 1.0f, 48, 24, 0);
  bxdf::test::ReferenceCamera ref{D3(0.3, -5, 0.4), D3(0, 0, 0), 50, 36, kSize, kSize};

  CameraSettings camera() const {
    CameraSettings c;
    c.camera_to_world = look_at(to_vec3(ref.eye), to_vec3(ref.target), Vec3(0, 0, 1));
    return c;
  }
  static RenderSettings settings() {
    RenderSettings s;
    s.width = s.height = kSize;
    s.samples_per_pixel = 1;
    s.max_bounces = 0;
    s.filter = FilterType::PixelCenter;
    return s;
  }
  // The shading frame the renderer uses: the interpolated normal and dp/du of the hit triangle.
  Frame frame_at(const bxdf::test::MeshHit& h) const {
    const uint32_t* idx = &sphere.indices[3 * h.triangle];
    const D3 p0 = bxdf::test::vertex(sphere.positions, idx[0]);
    const D3 e1 = bxdf::test::vertex(sphere.positions, idx[1]) - p0;
    const D3 e2 = bxdf::test::vertex(sphere.positions, idx[2]) - p0;
    const float* uv = sphere.uvs.data();
    const double du1 = uv[2 * idx[1]] - uv[2 * idx[0]], dv1 = uv[2 * idx[1] + 1] - uv[2 * idx[0] + 1];
    const double du2 = uv[2 * idx[2]] - uv[2 * idx[0]], dv2 = uv[2 * idx[2] + 1] - uv[2 * idx[0] + 1];
    const D3 dpdu = (e1 * dv2 - e2 * dv1) * (1.0 / (du1 * dv2 - dv1 * du2));
    return Frame::from_normal_tangent(to_vec3(h.ns), normalize(to_vec3(dpdu)));
  }
};

// Compares a render with the truth(light direction, hit) function pixel by pixel. Returns the
// number of lit pixels compared.
template <class Truth>
int compare_with_truth(const LitSphere& ls, const Film& film, const BxDF& model, Truth truth) {
  int compared = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      float px[4];
      film.pixel(x, y, px);
      const D3 dir = ls.ref.ray(x, y);
      const auto hit = bxdf::test::intersect(ls.sphere, ls.ref.eye, dir);
      if (!hit) {
        EXPECT_EQ(px[0] + px[1] + px[2], 0.0f) << "background pixel " << x << "," << y;
        continue;
      }
      D3 wi;
      RGB incident;  // radiance-like factor: I·spot/d² or E
      if (!truth(*hit, &wi, &incident)) continue;
      const double cos_g = dot(wi, hit->ng), cos_s = dot(wi, hit->ns);
      // Near the terminator the flat facets and the smooth normals disagree: leave it out.
      if (cos_g < 0.05 || cos_s < 0.05) continue;
      const Frame fr = ls.frame_at(*hit);
      const Vec3 wo_l = fr.to_local(to_vec3(-dir)), wi_l = fr.to_local(to_vec3(wi));
      const RGB expected = model.f(wo_l, wi_l) * incident * static_cast<float>(cos_s);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(px[c], expected[c], 2e-3f * expected[c] + 1e-6f)
            << model.model_name() << " pixel " << x << "," << y << " channel " << c;
      EXPECT_EQ(px[3], 1.0f);
      ++compared;
    }
  }
  return compared;
}

int render_and_compare_point(const BxDFPtr& model, RGB intensity, D3 light) {
  LitSphere ls;
  Scene scene;
  scene.add_material(Material{{model}, RGB(0.0f)});
  scene.add_mesh(ls.sphere.view());
  scene.add_light(point_light(to_vec3(light), intensity));
  scene.commit();
  RenderStats stats;
  const Film film = render_scene(scene, ls.camera(), LitSphere::settings(), {}, &stats);
  EXPECT_EQ(stats.rejected_samples, 0u);
  return compare_with_truth(ls, film, *model, [&](const bxdf::test::MeshHit& h, D3* wi, RGB* inc) {
    const D3 d = light - h.p;
    const double d2 = dot(d, d);
    *wi = d * (1.0 / std::sqrt(d2));
    *inc = intensity * static_cast<float>(1.0 / d2);
    return true;
  });
}

}  // namespace

TEST(DirectLight, PointLightOnLambertianSphereIsExact) {
  const int n = render_and_compare_point(make("lambertian", [] {
    ParamSet p;
    p.set("reflectance", RGBValue{0.7, 0.5, 0.3});
    return p;
  }()), RGB(10.0f, 8.0f, 6.0f), D3(3, -3, 3));
  EXPECT_GT(n, 150);
}

// Every registered non-delta reflection model with its default parameters: the renderer's
// direct light must be the model's own f times the light's geometry, whatever the model.
TEST(DirectLight, PointLightOnEveryReflectionModelIsExact) {
  std::vector<std::string> tested;
  for (const ModelInfo& info : models()) {
    BxDFPtr model;
    try {
      model = make(info.name);
    } catch (const ParameterError&) {
      continue;  // needs a parameter without default (e.g. a measured file's path)
    }
    if (model->is_delta() || !(model->flags() & kReflection)) continue;
    SCOPED_TRACE(info.name);
    const int n = render_and_compare_point(model, RGB(12.0f), D3(-2, -4, 3));
    EXPECT_GT(n, 150);
    tested.push_back(info.name);
  }
  std::string list;
  for (const auto& t : tested) list += t + " ";
  RecordProperty("models", list);
  EXPECT_NE(std::find(tested.begin(), tested.end(), "lambertian"), tested.end());
}

// The named models of the brief with non-default parameters; the anisotropic GGX checks that the
// renderer's tangent frame (dp/du from the UVs) is the one the model is evaluated in.
TEST(DirectLight, PointLightOnGlossyAndRoughModelsIsExact) {
  struct Case {
    const char* name;
    const char* model;
    ParamSet params;
  };
  const auto params = [](std::initializer_list<std::pair<const char*, Value>> kv) {
    ParamSet p;
    for (const auto& [k, v] : kv) p.set(k, v);
    return p;
  };
  const std::vector<Case> cases = {
      {"ggx", "microfacet",
       params({{"distribution", "ggx"}, {"alpha_x", 0.25}, {"alpha_y", 0.25},
               {"reflectance", RGBValue{0.9, 0.6, 0.3}}})},
      {"ggx_anisotropic", "microfacet",
       params({{"distribution", "ggx"}, {"alpha_x", 0.1}, {"alpha_y", 0.5}})},
      {"blinn", "microfacet", params({{"distribution", "blinn"}, {"exponent", 60.0}})},
      {"beckmann_fresnel", "microfacet",
       params({{"distribution", "beckmann"}, {"alpha_x", 0.3}, {"alpha_y", 0.3},
               {"fresnel", "dielectric"}})},
      {"oren_nayar", "oren_nayar", params({{"sigma", 30.0}})},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const int n = render_and_compare_point(make(c.model, c.params), RGB(15.0f), D3(1, -4, 2));
    EXPECT_GT(n, 150);
  }
}

// A material of two components: the BSDF sums them, so the pixel is f1 + f2 times the geometry.
TEST(DirectLight, CombinedMaterialSumsItsComponents) {
  ParamSet lam_p, ggx_p;
  lam_p.set("reflectance", RGBValue{0.4, 0.2, 0.1});
  ggx_p.set("distribution", "ggx");
  ggx_p.set("reflectance", RGBValue{0.5, 0.5, 0.5});
  const BxDFPtr lam = make("lambertian", lam_p), ggx = make("microfacet", ggx_p);
  LitSphere ls;
  Scene scene;
  scene.add_material(Material{{lam, ggx}, RGB(0.0f)});
  scene.add_mesh(ls.sphere.view());
  const D3 light(1, -4, 2);
  scene.add_light(point_light(to_vec3(light), RGB(15.0f)));
  scene.commit();
  const Film film = render_scene(scene, ls.camera(), LitSphere::settings());
  // The truth through a model-like sum: evaluate both and add.
  struct Sum final : BxDFImpl<Sum> {
    Sum(const BxDF& a, const BxDF& b) : BxDFImpl(kReflection | kDiffuse | kGlossy), a_(a), b_(b) {}
    RGB eval(const Vec3& wo, const Vec3& wi) const { return a_.f(wo, wi) + b_.f(wo, wi); }
    BxDFSample sample(const Vec3&, Point2) const { return {}; }
    float density(const Vec3&, const Vec3&) const { return 0.0f; }
    const BxDF &a_, &b_;
  } sum(*lam, *ggx);
  const int n = compare_with_truth(ls, film, sum, [&](const bxdf::test::MeshHit& h, D3* wi, RGB* inc) {
    const D3 d = light - h.p;
    const double d2 = dot(d, d);
    *wi = d * (1.0 / std::sqrt(d2));
    *inc = RGB(15.0f) * static_cast<float>(1.0 / d2);
    return true;
  });
  EXPECT_GT(n, 150);
}

TEST(DirectLight, SpotLightFollowsBlenderConeAndBlend) {
  LitSphere ls;
  const BxDFPtr lam = make("lambertian");
  Scene scene;
  scene.add_material(Material{{lam}, RGB(0.0f)});
  scene.add_mesh(ls.sphere.view());
  const D3 pos(0.5, -4, 1.0);
  const D3 axis = unit(D3(0, 0, 0) - pos);
  const float spot_size = radians(20.0f), blend = 0.5f;
  const Light spot = spot_light(to_vec3(pos), to_vec3(axis), RGB(30.0f), spot_size, blend);
  scene.add_light(spot);
  scene.commit();
  const Film film = render_scene(scene, ls.camera(), LitSphere::settings());
  // Cycles 3.4's mask written out: cos α inside the cone, times smoothstep over the blend band.
  const double cos_half = std::cos(0.5 * spot_size);
  const double smooth = (1.0 - cos_half) * blend;
  int inside = 0, outside = 0;
  const int n = compare_with_truth(ls, film, *lam, [&](const bxdf::test::MeshHit& h, D3* wi, RGB* inc) {
    const D3 d = pos - h.p;
    const double d2 = dot(d, d);
    *wi = d * (1.0 / std::sqrt(d2));
    const double c = dot(-*wi, axis);
    double mask = 0.0;
    if (c > cos_half) {
      mask = c;
      const double t = c - cos_half;
      if (t < smooth) {
        const double s = t / smooth;
        mask *= s * s * (3 - 2 * s);
      }
    }
    // Pixels right at the cone's edge are too sensitive to float rounding of the cosine.
    if (std::fabs(c - cos_half) < 1e-4) return false;
    (mask > 0 ? inside : outside)++;
    *inc = RGB(30.0f) * static_cast<float>(mask / d2);
    return true;
  });
  EXPECT_GT(n, 150);
  EXPECT_GT(inside, 20);   // the cone covers part of the sphere...
  EXPECT_GT(outside, 20);  // ...and leaves part of it dark
}

TEST(DirectLight, SunGivesIrradianceTimesCosine) {
  LitSphere ls;
  const BxDFPtr lam = make("lambertian");
  Scene scene;
  scene.add_material(Material{{lam}, RGB(0.0f)});
  scene.add_mesh(ls.sphere.view());
  const D3 travel = unit(D3(-1, 2, -1.5));  // the way sunlight goes
  scene.add_light(sun_light(to_vec3(travel), RGB(3.0f, 2.0f, 1.0f), 0.0f));
  scene.commit();
  const Film film = render_scene(scene, ls.camera(), LitSphere::settings());
  const int n = compare_with_truth(ls, film, *lam, [&](const bxdf::test::MeshHit&, D3* wi, RGB* inc) {
    *wi = -travel;
    *inc = RGB(3.0f, 2.0f, 1.0f);
    return true;
  });
  EXPECT_GT(n, 150);
}

TEST(DirectLight, BlenderPointLightPowerIsFourPiIntensity) {
  const Light l = point_light_from_power(Vec3(0, 0, 0), 1000.0f, RGB(1.0f, 0.5f, 0.25f));
  EXPECT_NEAR(l.intensity.r, 1000.0f / (4.0f * kPi), 1e-3f);
  EXPECT_NEAR(l.intensity.g, 500.0f / (4.0f * kPi), 1e-3f);
  EXPECT_NEAR(l.intensity.b, 250.0f / (4.0f * kPi), 1e-3f);
  EXPECT_THROW(point_light_from_power(Vec3(0, 0, 0), -1.0f, RGB(1.0f)), ParameterError);
  EXPECT_THROW(spot_light(Vec3(0, 0, 0), Vec3(0, 0, -1), RGB(1.0f), 4.0f, 0.1f), ParameterError);
  EXPECT_THROW(sun_light(Vec3(0, 0, 0), RGB(1.0f), 0.0f), ParameterError);
}

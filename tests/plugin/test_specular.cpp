// Specular geometry: a mirror sphere and a glass sphere show the world and an emissive panel
// exactly where the geometry sends the rays. The truth traces the same triangle mesh in double
// precision with the interpolated normals (reflection, Snell refraction, Fresnel from the core),
// independently of Embree and the integrator.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "bxdf/fresnel.h"
#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"
#include "reference_geometry.h"

using namespace bxdf;
using namespace bxdf::render;
using bxdf::test::D3;

namespace {

constexpr int kSize = 32;
const RGB kWorld(0.2f, 0.3f, 0.4f);
const RGB kPanel(3.0f, 2.0f, 1.0f);
// The emissive panel: z = 2.5, x, y in [-2, 2] (faces down; emission is two-sided anyway).
constexpr double kPanelZ = 2.5, kPanelHalf = 2.0;

Vec3 to_vec3(const D3& d) { return Vec3(float(d.x), float(d.y), float(d.z)); }

struct SpecularScene {
  Mesh sphere = make_uv_sphere(Vec3(0, 0, 0), 1.0f, 64, 32, 0);
  bxdf::test::ReferenceCamera ref{D3(0.2, -4.5, 0.6), D3(0, 0, 0.1), 50, 36, kSize, kSize};

  Film render(const BxDFPtr& model, int spp, int max_bounces, int rr_depth = 3) const {
    Scene scene;
    scene.add_material(Material{{model}, RGB(0.0f)});
    scene.add_material(Material{{}, kPanel});
    scene.add_mesh(sphere.view());
    const Mesh panel = make_quad(Vec3(-kPanelHalf, -kPanelHalf, kPanelZ), Vec3(0, 2 * kPanelHalf, 0),
                                 Vec3(2 * kPanelHalf, 0, 0), 1);
    scene.add_mesh(panel.view());
    scene.set_world(kWorld);
    scene.commit();
    CameraSettings cam;
    cam.camera_to_world = look_at(to_vec3(ref.eye), to_vec3(ref.target), Vec3(0, 0, 1));
    RenderSettings s;
    s.width = s.height = kSize;
    s.samples_per_pixel = spp;
    s.max_bounces = max_bounces;
    s.filter = FilterType::PixelCenter;
    s.seed = 11;
    s.russian_roulette_depth = rr_depth;
    RenderStats stats;
    Film film = render_scene(scene, cam, s, {}, &stats);
    EXPECT_EQ(stats.rejected_samples, 0u);
    return film;
  }
};

// What an escaping ray from o along d sees: the panel, the world, or "too close to the panel's
// edge to call" (nullopt).
std::optional<RGB> background(const D3& o, const D3& d) {
  if (d.z > 1e-9) {
    const double t = (kPanelZ - o.z) / d.z;
    const D3 q = o + d * t;
    const double edge = std::max(std::fabs(q.x), std::fabs(q.y)) - kPanelHalf;
    if (std::fabs(edge) < 0.02) return std::nullopt;
    if (edge < 0) return kPanel;
  }
  return kWorld;
}

}  // namespace

TEST(Specular, MirrorSphereReflectsWorldAndPanelExactly) {
  SpecularScene sc;
  ParamSet p;
  p.set("reflectance", RGBValue{0.9, 0.8, 0.7});
  p.set("fresnel", "none");
  // Pure delta: no light sampling, one deterministic path per pixel centre, so no noise.
  const Film film = sc.render(make("specular_reflection", p), 1, 2);
  int panel = 0, world = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      float px[4];
      film.pixel(x, y, px);
      const D3 d = sc.ref.ray(x, y);
      const auto hit = bxdf::test::intersect(sc.sphere, sc.ref.eye, d);
      RGB expected;
      if (!hit) {
        const auto bg = background(sc.ref.eye, d);
        if (!bg) continue;
        expected = *bg;
      } else {
        const double cos_o = -dot(d, hit->ns);
        if (cos_o < 0.1) continue;  // silhouette: shading and geometric normals disagree
        const D3 r = d + hit->ns * (2 * cos_o);
        if (dot(r, hit->ng) < 0.02) continue;  // would leave below the facet: dropped
        if (bxdf::test::intersect(sc.sphere, hit->p, r, 1e-6)) continue;
        const auto bg = background(hit->p, r);
        if (!bg) continue;
        (*bg == kPanel ? panel : world)++;
        expected = *bg * RGB(0.9f, 0.8f, 0.7f);
      }
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(px[c], expected[c], 1e-4f * (1 + expected[c])) << x << "," << y;
    }
  EXPECT_GT(panel, 30);  // both the panel and the world appear in the mirror
  EXPECT_GT(world, 100);
}

// Glass: each interface reflects with probability F or refracts, so a pixel is a mixture over
// the tree of paths. The truth sums that tree (mean and second moment) and the render must agree
// within its Monte Carlo error.
TEST(Specular, GlassSphereRefractsAndReflectsAsSnellAndFresnelSay) {
  SpecularScene sc;
  const int max_bounces = 8, spp = 128;
  // η = 1.5, R = T = 1. Russian roulette off: its extra variance is not in the truth's moments.
  const Film film = sc.render(make("fresnel_specular"), spp, max_bounces, max_bounces + 1);

  struct Moments {
    double m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
    bool undecidable = false;
  };
  // Follows a ray that left vertex `vertex - 1` (or the camera) with path probability `prob` and
  // weight `w` (the renderer's throughput).
  std::function<void(const D3&, const D3&, int, double, const double*, Moments&)> follow =
      [&](const D3& o, const D3& d, int vertex, double prob, const double* w, Moments& m) {
        if (prob < 1e-9 || m.undecidable) return;
        const auto hit = bxdf::test::intersect(sc.sphere, o, d, 1e-6);
        if (!hit) {
          const auto bg = background(o, d);
          if (!bg) {
            m.undecidable = true;
            return;
          }
          for (int c = 0; c < 3; ++c) {
            const double v = w[c] * (*bg)[c];
            m.m1[c] += prob * v;
            m.m2[c] += prob * v * v;
          }
          return;
        }
        if (vertex > max_bounces) return;  // the path ends: glass emits nothing
        const D3 wo = -d;
        const double cos_o = dot(wo, hit->ns);  // signed: < 0 inside the glass
        if (std::fabs(cos_o) < 0.05 || std::fabs(dot(wo, hit->ng)) < 0.05) {
          m.undecidable = true;  // grazing: float and double may branch differently
          return;
        }
        const double F = fresnel_dielectric(static_cast<float>(cos_o), 1.0f, 1.5f);
        const bool outside = cos_o > 0;
        const D3 n = outside ? hit->ns : -hit->ns;  // normal on wo's side
        const double c_o = std::fabs(cos_o);
        // Reflection, chosen with probability F, weight 1.
        const D3 r = n * (2 * c_o) - wo;
        if (F > 0) {
          if (dot(r, hit->ng) * dot(wo, hit->ng) > 0) follow(hit->p, r, vertex + 1, prob * F, w, m);
        }
        if (F < 1) {
          const double eta = outside ? 1.0 / 1.5 : 1.5;  // η_o / η_i
          const double sin2_t = eta * eta * (1 - c_o * c_o);
          const double cos_t = std::sqrt(std::max(0.0, 1 - sin2_t));
          const D3 t = -wo * eta + n * (eta * c_o - cos_t);
          if (dot(t, hit->ng) * dot(wo, hit->ng) < 0) {
            double wt[3];
            for (int c = 0; c < 3; ++c) wt[c] = w[c] * eta * eta;  // (η_wo/η_wi)² radiance scale
            follow(hit->p, t, vertex + 1, prob * (1 - F), wt, m);
          }
        }
      };

  int compared = 0, refracted_panel = 0;
  double sum_diff = 0, sum_sigma = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const D3 d = sc.ref.ray(x, y);
      if (!bxdf::test::intersect(sc.sphere, sc.ref.eye, d)) continue;
      Moments m;
      const double one[3] = {1, 1, 1};
      follow(sc.ref.eye, d, 0, 1.0, one, m);
      if (m.undecidable) continue;
      float px[4];
      film.pixel(x, y, px);
      for (int c = 0; c < 3; ++c) {
        const double sigma = std::sqrt(std::max(0.0, m.m2[c] - m.m1[c] * m.m1[c]) / spp);
        EXPECT_NEAR(px[c], m.m1[c], 5 * sigma + 2e-3 * m.m1[c] + 1e-5)
            << x << "," << y << " channel " << c;
        sum_diff += px[c] - m.m1[c];
        sum_sigma += sigma * sigma;
      }
      if (m.m1[0] > 1.5 * kWorld[0]) ++refracted_panel;
      ++compared;
    }
  EXPECT_GT(compared, 150);
  EXPECT_GT(refracted_panel, 10);  // the panel shows through / in the glass
  // The mean error over all pixels: no bias beyond the noise of the sum.
  EXPECT_LT(std::fabs(sum_diff), 4 * std::sqrt(sum_sigma) + 1e-3);
}

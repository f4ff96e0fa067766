// The `environment` op of material graphs (an Environment Texture inside a material): Cycles'
// equirectangular and mirror-ball projections of the normalised vector, the image looked up as
// the `image` op looks it up, and through the very lookup the world's environment uses (the
// same direction gives the same colour in both).
#include <gtest/gtest.h>

#include "../scratch_folder.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bxdf/registry.h"
#include "bxdf/render/environment.h"
#include "bxdf/render/material_graph_json.h"
#include "bxdf/render/scene.h"
#include "bxdf/render/shapes.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;
using namespace bxdf::render;
using nlohmann::json;

namespace {

constexpr int kW = 4, kH = 2;

// Texel (x, y), row 0 at the bottom: distinct values.
float texel(int x, int y, int c) { return 0.1f + 0.1f * float(x + kW * y) + 0.01f * float(c); }

std::string write_image() {
  const std::string path = bxdf::test_support::process_temp_path("environment_op.pfm");
  std::ofstream f(path, std::ios::binary);
  f << "PF\n" << kW << " " << kH << "\n-1.0\n";  // PFM: rows bottom first
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = texel(x, y, c);
        f.write(reinterpret_cast<const char*>(&v), sizeof v);
      }
  return path;
}

struct Fixture {
  Scene scene;
  Hit hit;
  Fixture() {
    scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
    scene.add_mesh(make_quad(Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 0).view());
    scene.commit();
    hit.b1 = hit.b2 = 0.25f;
  }
  // The op's colour for `vector` (a constant direction, or absent: the position `p`).
  Vec3 lookup(const json& environment_node, const Vec3& p = Vec3(0, 0, 0)) {
    TextureStore store;
    json node = environment_node;
    node["op"] = "environment";
    node["texture"] = 0;
    const json graph = {{"textures", {{{"path", write_image()}, {"colorspace", "linear"},
                                       {"interpolation", interpolation}}}},
                        {"nodes", {node}},
                        {"emission", {{"node", 0}, {"out", "color"}}}};
    const auto g = read_material_graph(graph, "graph", "", store);
    std::vector<Vec3> registers(MaterialGraph::kMaxRegisters);
    const ShadingContext ctx{&scene, &hit, p, Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1), false};
    g->evaluate(ctx, registers.data());
    const RGB e = g->emitted(registers.data());
    return Vec3(e.r, e.g, e.b);
  }
  std::string interpolation = "closest";
};

Vec3 expected_texel(float u, float v) {
  const int x = std::min(int(std::floor(u * kW)), kW - 1), y = std::min(int(std::floor(v * kH)), kH - 1);
  return Vec3(texel(x, y, 0), texel(x, y, 1), texel(x, y, 2));
}

void expect_vec_near(const Vec3& a, const Vec3& b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace

TEST(EnvironmentOp, EquirectangularLookupOfTheNormalisedVector) {
  Fixture f;
  // (−1, −1, 1) unnormalised: u = (π − atan2(−1, −1)) / 2π = 7/8, v = 1 − acos(1/√3)/π ≈ 0.70.
  const Vec3 d(-1.0f, -1.0f, 1.0f);
  const Point2 uv = direction_to_equirect(normalize(d));
  EXPECT_NEAR(uv.x, 0.875f, 1e-6f);
  expect_vec_near(f.lookup({{"vector", {d.x * 3, d.y * 3, d.z * 3}}}), expected_texel(uv.x, uv.y), 1e-6f);
  // Slightly above +X: the image's middle column (u just below ½) in the upper row: texel (1, 1).
  const Point2 near_x = direction_to_equirect(normalize(Vec3(1.0f, 0.01f, 0.2f)));
  EXPECT_LT(near_x.x, 0.5f);
  expect_vec_near(f.lookup({{"vector", {1.0, 0.01, 0.2}}}), expected_texel(0.49f, 0.6f), 1e-6f);
}

TEST(EnvironmentOp, MirrorBallProjection) {
  Fixture f;
  // Cycles' direction_to_mirrorball: −Y looks at the ball's centre, (u, v) = (½, ½) → texel (2, 1).
  expect_vec_near(f.lookup({{"vector", {0.0, -1.0, 0.0}}, {"projection", "mirror_ball"}}),
                  expected_texel(0.5f, 0.5f), 1e-6f);
  // (1, 0, 0): dir.y − 1 = −1, div = 2√½, u = ½ (1/√2 + 1) ≈ 0.854, v = ½ → texel (3, 1).
  const Point2 uv = direction_to_mirrorball(Vec3(1, 0, 0));
  EXPECT_NEAR(uv.x, 0.5f * (1.0f / std::sqrt(2.0f) + 1.0f), 1e-6f);
  EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
  expect_vec_near(f.lookup({{"vector", {1.0, 0.0, 0.0}}, {"projection", "mirror_ball"}}),
                  expected_texel(uv.x, uv.y), 1e-6f);
}

TEST(EnvironmentOp, AnUnlinkedVectorReadsThePosition) {
  Fixture f;
  // Cycles' default for this socket is the shading point's position: the op reads ctx.p.
  const Vec3 p(-0.3f, 0.8f, 0.4f);
  const Point2 uv = direction_to_equirect(normalize(p));
  expect_vec_near(f.lookup(json::object(), p), expected_texel(uv.x, uv.y), 1e-6f);
}

TEST(EnvironmentOp, TheWorldAndTheOpShareOneLookup) {
  Fixture f;
  f.interpolation = "linear";
  EnvironmentSettings s;
  s.weight = RGB(1.0f);
  s.image.width = kW;
  s.image.height = kH;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) s.image.rgb.push_back(texel(x, y, c));
  const Environment world(s);
  PCG32 rng(3);
  for (int i = 0; i < 200; ++i) {
    const Vec3 d = sample_uniform_sphere(Point2(rng.uniform(), rng.uniform()));
    const RGB w = world.eval(d);
    expect_vec_near(f.lookup({{"vector", {d.x, d.y, d.z}}}), Vec3(w.r, w.g, w.b), 1e-6f);
  }
}

TEST(EnvironmentOp, BadProjectionIsRefusedWithTheFieldPath) {
  TextureStore store;
  const json graph = {{"textures", {{{"path", write_image()}}}},
                      {"nodes", {{{"op", "environment"}, {"texture", 0}, {"projection", "cube"}}}},
                      {"emission", 1.0}};
  try {
    read_material_graph(graph, "graph", "", store);
    FAIL() << "accepted";
  } catch (const GraphFieldError& e) {
    EXPECT_EQ(std::string(e.what()),
              "graph.nodes[0].projection: expected one of {equirectangular, mirror_ball}, got \"cube\"");
  }
}

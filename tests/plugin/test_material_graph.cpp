// Material graphs in the renderer: graphs read from JSON (bad ones refused with the field's
// path), a textured material whose texture is constant renders exactly as the untextured one,
// and a Mix of two closures with a texture factor renders as the per-pixel mix of the two.
#include <gtest/gtest.h>

#include "../scratch_folder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bxdf/registry.h"
#include "bxdf/render/camera.h"
#include "bxdf/render/material_graph_json.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene_json.h"
#include "bxdf/render/shapes.h"

using namespace bxdf;
using namespace bxdf::render;
using nlohmann::json;

namespace {

// A float image as a PFM file (OpenImageIO reads it; rows bottom first, little endian).
std::string write_pfm(const std::string& name, int w, int h, const std::vector<float>& rgb) {
  const std::string path = bxdf::test_support::process_temp_path(name);
  std::ofstream f(path, std::ios::binary);
  f << "PF\n" << w << " " << h << "\n-1.0\n";
  f.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  return path;
}

std::string graph_error(const json& graph) {
  TextureStore store;
  try {
    read_material_graph(graph, "graph", "", store);
  } catch (const GraphFieldError& e) {
    return e.what();
  }
  return "(accepted)";
}

// A floor quad filling the view of a camera looking straight down, lit by a point light.
std::vector<float> render_floor(const std::shared_ptr<const MaterialGraph>& graph,
                                const BxDFPtr& plain, bool transparent = false) {
  Scene scene;
  Material m;
  if (graph) m.graph = graph;
  else m.components.push_back(plain);
  scene.add_material(std::move(m));
  scene.add_mesh(make_quad(Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 0).view());
  scene.add_light(point_light(Vec3(0.3f, -0.2f, 1.5f), RGB(3.0f)));
  scene.commit();
  CameraSettings c;
  c.camera_to_world = look_at(Vec3(0, 0, 3), Vec3(0, 0, 0), Vec3(0, 1, 0));
  RenderSettings s;
  s.width = 16;
  s.height = 16;
  s.samples_per_pixel = 1;
  s.max_bounces = 0;
  s.filter = FilterType::PixelCenter;
  s.threads = 1;
  s.transparent_background = transparent;
  return render_scene(scene, c, s).rgba();
}

}  // namespace

TEST(MaterialGraph, BadGraphsAreRefusedWithTheFieldPath) {
  const json node0 = {{"op", "uv"}};
  EXPECT_EQ(graph_error({{"nodes", {node0, {{"op", "separate"}, {"vector", {{"node", 7}}}}}},
                         {"closures", json::array({{{"model", "lambertian"}}})}}),
            "graph.nodes[1].vector: node 7 is not earlier than 1 (no such node)");
  EXPECT_EQ(graph_error({{"nodes", {{{"op", "separate"}, {"vector", {{"node", 0}}}}}}}),
            "graph.nodes[0].vector: node 0 is not earlier than 0");
  EXPECT_NE(graph_error({{"nodes", {{{"op", "warp"}}}}}).find("graph.nodes[0].op: expected one of {const, uv,"),
            std::string::npos);
  EXPECT_NE(graph_error({{"nodes", {{{"op", "mix_rgb"}, {"blend", "mixx"}}}}}).find("graph.nodes[0].blend: expected one of {mix,"),
            std::string::npos);
  EXPECT_NE(graph_error({{"nodes", {node0, {{"op", "separate"}, {"vector", {{"node", 0}, {"out", "colour"}}}}}}})
                .find("graph.nodes[1].vector.out: expected one of {vector}"),
            std::string::npos);
  // Closures: unknown parameter, enum by reference, constants validated with range, weights.
  const json sep = {{"op", "separate"}, {"vector", {{"node", 0}}}};
  EXPECT_NE(graph_error({{"closures", {{{"model", "lambertian"}, {"params", {{"albedo", 0.5}}}}}}})
                .find("graph.closures[0].params.albedo: unknown parameter of 'lambertian'"),
            std::string::npos);
  const std::string enum_ref = graph_error(
      {{"nodes", {node0, sep}},
       {"closures", {{{"model", "cycles_glossy"}, {"params", {{"distribution", {{"node", 1}, {"out", "x"}}}}}}}}});
  EXPECT_NE(enum_ref.find("graph.closures[0].params.distribution: enum parameters must be constants"),
            std::string::npos) << enum_ref;
  const std::string range = graph_error({{"closures", {{{"model", "cycles_glossy"}, {"params", {{"roughness", 1.5}}}}}}});
  EXPECT_NE(range.find("graph.closures[0].params"), std::string::npos) << range;
  EXPECT_NE(range.find("roughness"), std::string::npos) << range;
  EXPECT_NE(range.find("[0, 1]"), std::string::npos) << range;
  EXPECT_NE(graph_error({{"closures", {{{"model", "lambertian"}, {"weight", -1}}}}})
                .find("graph.closures[0].weight: must be in [0, inf)"),
            std::string::npos);
  EXPECT_NE(graph_error({{"closures", {{{"model", "lambertian"}, {"normal", {0, 0, 1}}}}}})
                .find("graph.closures[0].normal: expected a node reference"),
            std::string::npos);
  EXPECT_NE(graph_error({{"textures", {{{"path", "/no/such/image.png"}}}}}).find("graph.textures[0].path: texture '/no/such/image.png': cannot be read"),
            std::string::npos);
  EXPECT_NE(graph_error({{"nodes", {{{"op", "color_ramp"}, {"stops", {{0.5, 1, 1, 1, 1}, {0.1, 0, 0, 0, 1}}}}}}})
                .find("graph.nodes[0].stops: color ramp stops must be sorted"),
            std::string::npos);
  EXPECT_EQ(graph_error(json::object()), "graph: a graph needs at least one closure or an emission");
}

TEST(MaterialGraph, SceneFilesReportTheGraphFieldPath) {
  const std::string text = R"({
    "camera": {"position": [0, -3, 0], "look_at": [0, 0, 0]},
    "materials": {"m": {"graph": {"nodes": [{"op": "uv"}, {"op": "math", "operation": "add",
                                             "a": {"node": 4, "out": "value"}}],
                                  "closures": [{"model": "lambertian"}]}}},
    "meshes": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
  try {
    parse_scene_json(text, "scene.json", ".");
    FAIL() << "accepted";
  } catch (const SceneFileError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene.json: field 'materials.m.graph.nodes[1].a': node 4 is not earlier than 1 (no such node)");
  }
}

TEST(MaterialGraph, ConstantTextureRendersLikeTheUntexturedMaterial) {
  const std::string path = write_pfm("bxdf_graph_constant.pfm", 3, 2, std::vector<float>(18, 0.5f));
  TextureStore store;
  const json graph = {
      {"textures", {{{"path", path}, {"colorspace", "linear"}, {"interpolation", "cubic"}}}},
      {"nodes", {{{"op", "uv"}}, {{"op", "image"}, {"texture", 0}, {"vector", {{"node", 0}}}},
                 {{"op", "math"}, {"operation", "multiply"}, {"a", {{"node", 1}, {"out", "color"}}}, {"b", 0.6}}}},
      {"closures", {{{"model", "cycles_glossy"},
                     {"params", {{"color", {{"node", 1}, {"out", "color"}}},
                                 {"roughness", {{"node", 2}, {"out", "value"}}}}}}}}};
  ParamSet p;
  p.set("color", RGBValue{0.5, 0.5, 0.5});
  p.set("roughness", double(0.5f * 0.6f));
  const std::vector<float> textured = render_floor(read_material_graph(graph, "graph", "", store), nullptr);
  const std::vector<float> plain = render_floor(nullptr, make("cycles_glossy", p));
  ASSERT_EQ(textured.size(), plain.size());
  float peak = 0.0f;
  for (size_t i = 0; i < plain.size(); ++i) {
    // Equal up to float rounding (the cubic B-spline's weights sum to 1 within an ulp or two).
    EXPECT_NEAR(textured[i], plain[i], 1e-6f * (1.0f + plain[i])) << i;
    peak = std::max(peak, plain[i]);
  }
  EXPECT_GT(peak, 0.01f);
  std::remove(path.c_str());
}

TEST(MaterialGraph, MixOfTwoClosuresWithATextureFactor) {
  // A 2×1 texture: factor 0.2 on the left half of the floor (u < 0.5), 0.9 on the right.
  const std::string path = write_pfm("bxdf_graph_mix.pfm", 2, 1, {0.2f, 0.2f, 0.2f, 0.9f, 0.9f, 0.9f});
  TextureStore store;
  const json diffuse = {{"model", "cycles_oren_nayar"}, {"params", {{"color", {0.9, 0.2, 0.1}}, {"roughness", 0.4}}}};
  const json glossy = {{"model", "cycles_glossy"}, {"params", {{"color", {0.2, 0.5, 0.9}}, {"roughness", 0.3}}}};
  json mix = {{"textures", {{{"path", path}, {"colorspace", "linear"}, {"interpolation", "closest"}}}},
              {"nodes", {{{"op", "image"}, {"texture", 0}},
                         {{"op", "math"}, {"operation", "subtract"}, {"a", 1.0}, {"b", {{"node", 0}, {"out", "color"}}}}}}};
  json d = diffuse, g = glossy;
  d["weight"] = {{"node", 1}, {"out", "value"}};  // Mix Shader: (1 − fac) · first
  g["weight"] = {{"node", 0}, {"out", "color"}};  // fac · second
  mix["closures"] = {d, g};
  const std::vector<float> mixed = render_floor(read_material_graph(mix, "graph", "", store), nullptr);
  const std::vector<float> a = render_floor(read_material_graph({{"closures", {diffuse}}}, "graph", "", store), nullptr);
  const std::vector<float> b = render_floor(read_material_graph({{"closures", {glossy}}}, "graph", "", store), nullptr);
  const int w = 16;
  int checked = 0;
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      if (x == w / 2 - 1 || x == w / 2) continue;  // the seam
      // Pixel x < w/2 looks at u < 0.5 (the camera's right is +x, the floor's u).
      const float fac = x < w / 2 ? 0.2f : 0.9f;
      for (int c = 0; c < 3; ++c) {
        const size_t i = size_t(4 * (y * w + x) + c);
        EXPECT_NEAR(mixed[i], (1 - fac) * a[i] + fac * b[i], 1e-5f + 1e-5f * a[i]) << x << "," << y;
        ++checked;
      }
    }
  EXPECT_GT(checked, 500);
  std::remove(path.c_str());
}

TEST(MaterialGraph, MeshAttributesUVMapsTangentsObjectAndGenerated) {
  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  // One triangle in object space (0,0,0), (2,0,0), (0,4,0), placed at +(10, 0, 1).
  Mesh m;
  m.positions = {10, 0, 1, 12, 0, 1, 10, 4, 1};
  m.indices = {0, 1, 2};
  m.uv_maps = {{0, 0, 1, 0, 0, 1}, {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f}};
  m.tangents = {{1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, -1}, {}};
  m.object_to_world = {1, 0, 0, 10, 0, 1, 0, 0, 0, 0, 1, 1};
  scene.add_mesh(m.view());
  scene.commit();
  Hit hit;
  hit.b1 = 0.25f;  // p = p0 + 0.25 (p1 − p0) + 0.5 (p2 − p0) = (10.5, 2, 1)
  hit.b2 = 0.5f;
  const Vec3 p(10.5f, 2.0f, 1.0f);
  const Vec3 uv0 = scene.uv(hit, 0), uv1 = scene.uv(hit, 1), none = scene.uv(hit, 2);
  EXPECT_FLOAT_EQ(uv0.x, 0.25f);
  EXPECT_FLOAT_EQ(uv0.y, 0.5f);
  EXPECT_FLOAT_EQ(uv1.x, 0.5f);
  EXPECT_EQ(none.x, 0.0f);
  Vec3 t;
  float sign = 0.0f;
  ASSERT_TRUE(scene.tangent(hit, 0, &t, &sign));
  EXPECT_FLOAT_EQ(t.x, 0.5f);  // interpolated, unnormalised: 0.25·(1,0,0) + ... + 0.5·(0,1,0)
  EXPECT_FLOAT_EQ(t.y, 0.5f);
  EXPECT_FLOAT_EQ(sign, 0.25f * 1.0f + 0.25f * 1.0f + 0.5f * -1.0f);
  EXPECT_FALSE(scene.tangent(hit, 1, &t, &sign));
  const Vec3 obj = scene.object_position(hit, p);
  EXPECT_NEAR(obj.x, 0.5f, 1e-5f);
  EXPECT_NEAR(obj.y, 2.0f, 1e-5f);
  EXPECT_NEAR(obj.z, 0.0f, 1e-5f);
  // Generated: the object-space box [0,2]×[0,4]×[0,0] (a flat axis counts as size 1 about 0).
  const Vec3 gen = scene.generated(hit, p);
  EXPECT_NEAR(gen.x, 0.25f, 1e-5f);
  EXPECT_NEAR(gen.y, 0.5f, 1e-5f);
  EXPECT_NEAR(gen.z, 0.5f, 1e-5f);
  // A singular object transform is refused, naming the mesh.
  Scene bad;
  bad.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  m.object_to_world = {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  EXPECT_THROW(bad.add_mesh(m.view()), ParameterError);
}

namespace {

// The quad [-1, 1]² at z = 0 (two triangles) with UV map 0 = ((x + 1)/2, (y + 1)/2) per corner.
Mesh uv_quad() {
  Mesh m;
  m.positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.uv_maps = {{0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1}};
  return m;
}

}  // namespace

// A bump whose height is linear in UV: the height sub-program is re-run at the offset points
// (its UV node copied), so the normal is normalize(N − distance·∇h) on both triangles.
TEST(MaterialGraph, BumpReevaluatesTheHeightAtOffsetPoints) {
  TextureStore store;
  const json graph = {
      {"nodes", {{{"op", "uv"}},
                 {{"op", "separate"}, {"vector", {{"node", 0}}}},
                 {{"op", "math"}, {"operation", "multiply"}, {"a", {{"node", 1}, {"out", "x"}}}, {"b", 0.5}},
                 {{"op", "bump"}, {"height", {{"node", 2}}}, {"distance", 0.2}},
                 {{"op", "bump"}, {"height", {{"node", 2}}}, {"distance", 0.2}, {"invert", true},
                  {"strength", 0.5}, {"normal", {{"node", 3}}}}}},
      {"closures", {{{"model", "lambertian"}, {"normal", {{"node", 3}}}}}}};
  const auto g = read_material_graph(graph, "graph", "", store);
  EXPECT_TRUE(g->reads_offsets);
  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  scene.add_mesh(uv_quad().view());
  scene.commit();
  const Vec3 n(0, 0, 1);
  // h = 0.5 u = 0.25 (x + 1): ∇h = (0.25, 0, 0).
  const Vec3 bumped = normalize(n - Vec3(0.25f, 0, 0) * 0.2f);
  std::vector<Vec3> registers(MaterialGraph::kMaxRegisters);
  for (uint32_t triangle : {0u, 1u}) {
    Hit hit;
    hit.triangle = triangle;
    hit.b1 = 0.3f;
    hit.b2 = 0.4f;
    const SurfacePoint sp = scene.surface_point(hit);
    const ShadingContext ctx{&scene, &hit, sp.p, sp.ns, sp.ng, normalize(Vec3(0.1f, 0.2f, 1.0f)), false};
    g->evaluate(ctx, registers.data());
    const Vec3 got = registers[size_t(g->closures[0].normal_reg)];
    EXPECT_NEAR(got.x, bumped.x, 2e-4f);
    EXPECT_NEAR(got.y, bumped.y, 2e-4f);
    EXPECT_NEAR(got.z, bumped.z, 2e-4f);
  }
  // A bump's height may not depend on a bump's normal (it would need offsets of offsets).
  json nested = graph;
  nested["nodes"].push_back({{"op", "fresnel"}, {"normal", {{"node", 3}}}});
  nested["nodes"].push_back({{"op", "bump"}, {"height", {{"node", 5}}}});
  EXPECT_EQ(graph_error(nested),
            "graph.nodes[6].height: a bump's height cannot depend on another bump's normal");
}

// Image nodes that read one UV point of images of one size and settings share one footprint
// computation (MaterialGraph::group_images); every node's Color and Alpha stay exactly its
// own image's lookup. Images of another size, another interpolation or other coordinates are
// looked up on their own.
TEST(MaterialGraph, ImagesOnOneUVMapShareTheirFootprint) {
  auto ramp = [](int w, int h, float scale) {
    std::vector<float> rgb;
    for (int i = 0; i < w * h; ++i) rgb.insert(rgb.end(), {scale * float(i), 0.5f * scale, 1.0f - 0.01f * float(i)});
    return rgb;
  };
  const std::string a = write_pfm("bxdf_group_a.pfm", 4, 3, ramp(4, 3, 0.05f));
  const std::string b = write_pfm("bxdf_group_b.pfm", 4, 3, ramp(4, 3, 0.02f));
  const std::string c = write_pfm("bxdf_group_c.pfm", 5, 3, ramp(5, 3, 0.03f));
  TextureStore store;
  const json graph = {
      {"textures", {{{"path", a}, {"colorspace", "linear"}}, {{"path", b}, {"colorspace", "non_color"}},
                    {{"path", c}, {"colorspace", "linear"}},
                    {{"path", a}, {"colorspace", "linear"}, {"interpolation", "closest"}}}},
      {"nodes", {{{"op", "uv"}},
                 {{"op", "image"}, {"texture", 0}, {"vector", {{"node", 0}}}},
                 {{"op", "image"}, {"texture", 1}, {"vector", {{"node", 0}}}},
                 {{"op", "image"}, {"texture", 2}, {"vector", {{"node", 0}}}},
                 {{"op", "image"}, {"texture", 3}, {"vector", {{"node", 0}}}},
                 {{"op", "vector_math"}, {"operation", "scale"}, {"a", {{"node", 0}}}, {"scale", 1.7}},
                 {{"op", "image"}, {"texture", 1}, {"vector", {{"node", 5}}}},
                 {{"op", "image"}, {"texture", 0}, {"vector", {{"node", 0}}}}}},
      {"closures", {{{"model", "lambertian"}, {"weight", {{"node", 1}, {"out", "color"}}}}}}};
  const auto g = read_material_graph(graph, "graph", "", store);
  EXPECT_EQ(g->image_groups, (std::vector<int>{1, 2, 7}));
  EXPECT_EQ(g->nodes[1].group_count, 3);
  for (int k : {2, 7}) EXPECT_TRUE(g->nodes[size_t(k)].grouped);
  for (int k : {3, 4, 6}) EXPECT_FALSE(g->nodes[size_t(k)].grouped || g->nodes[size_t(k)].group_count);

  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  scene.add_mesh(uv_quad().view());
  scene.commit();
  std::vector<Vec3> registers(MaterialGraph::kMaxRegisters);
  for (float b1 : {0.05f, 0.3f, 0.61f})
    for (float b2 : {0.1f, 0.37f}) {
      Hit hit;
      hit.b1 = b1;
      hit.b2 = b2;
      const SurfacePoint sp = scene.surface_point(hit);
      const ShadingContext ctx{&scene, &hit, sp.p, sp.ns, sp.ng, Vec3(0, 0, 1), false};
      g->evaluate(ctx, registers.data());
      const Vec3 uv = registers[size_t(g->nodes[0].out)];
      for (size_t k : {1, 2, 3, 4, 6, 7}) {
        const GraphNode& node = g->nodes[k];
        const Vec3 at = k == 6 ? uv * 1.7f : uv;
        const RGBA want = g->textures[size_t(node.index)]->lookup(at.x, at.y, node.flag);
        const Vec3 color = registers[size_t(node.out)], alpha = registers[size_t(node.out) + 1];
        EXPECT_EQ(color, Vec3(want.r, want.g, want.b)) << "node " << k;
        EXPECT_EQ(alpha.x, want.a) << "node " << k;
      }
    }
  for (const std::string& p : {a, b, c}) std::remove(p.c_str());
}

// Tangents arrive in world space (moved with the mesh by the object matrix A); normal maps
// read them in object space, as Cycles composes the mapped normal there, and move normals
// between the spaces by Aᵀ and A⁻ᵀ.
TEST(MaterialGraph, TangentsAndNormalsUnderANonUniformScale) {
  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  Mesh m = uv_quad();
  for (size_t i = 0; i < m.positions.size(); i += 3) m.positions[i] *= 2.0f;  // scale x by 2
  m.object_to_world = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  m.tangents = {std::vector<float>(24, 0.0f)};
  for (size_t c = 0; c < 6; ++c) {
    m.tangents[0][4 * c] = 1.2f;  // world (1.2, 0.8, 0) = A (0.6, 0.8, 0), sign 1
    m.tangents[0][4 * c + 1] = 0.8f;
    m.tangents[0][4 * c + 3] = 1.0f;
  }
  scene.add_mesh(m.view());
  scene.commit();
  Hit hit;
  hit.b1 = 0.2f;
  hit.b2 = 0.3f;
  Vec3 t;
  float sign = 0.0f;
  ASSERT_TRUE(scene.tangent(hit, 0, &t, &sign));
  EXPECT_FLOAT_EQ(t.x, 0.6f);
  EXPECT_FLOAT_EQ(t.y, 0.8f);
  EXPECT_FLOAT_EQ(t.z, 0.0f);
  EXPECT_FLOAT_EQ(sign, 1.0f);
  const Vec3 n(0.3f, 0.4f, 0.5f);
  const Vec3 to_object = scene.normal_to_object(hit, n), to_world = scene.normal_to_world(hit, n);
  EXPECT_FLOAT_EQ(to_object.x, 0.6f);  // Aᵀ n
  EXPECT_FLOAT_EQ(to_object.y, 0.4f);
  EXPECT_FLOAT_EQ(to_world.x, 0.15f);  // A⁻ᵀ n
  EXPECT_FLOAT_EQ(to_world.z, 0.5f);
}

// Cycles lets a negative Emission take light away: a graph's emission keeps its sign, and the
// camera sees it as it is (a black floor, so that only the emission shows).
TEST(MaterialGraph, NegativeEmissionTakesLightAway) {
  TextureStore store;
  const json graph = {{"closures", {{{"model", "lambertian"}, {"params", {{"reflectance", 0.0}}}}}},
                      {"emission", {-0.05, 0.0, 0.02}}};
  const auto g = read_material_graph(graph, "graph", "", store);
  const RGB e = g->emitted(nullptr);
  EXPECT_EQ(e.r, -0.05f);
  EXPECT_EQ(e.b, 0.02f);
  const std::vector<float> image = render_floor(g, nullptr);
  int floor = 0;
  for (size_t i = 0; i < image.size(); i += 4) {
    if (image[i] == 0.0f && image[i + 2] == 0.0f) continue;  // background
    ++floor;
    EXPECT_FLOAT_EQ(image[i], -0.05f);
    EXPECT_FLOAT_EQ(image[i + 2], 0.02f);
  }
  EXPECT_GT(floor, 100);
}

// Holdout (Cycles): the pixel turns transparent by the holdout weight on camera rays and the
// holdout reflects nothing; a half holdout mixed with a diffuse keeps half of the diffuse.
TEST(MaterialGraph, HoldoutMakesThePixelTransparent) {
  TextureStore store;
  const json diffuse = {{"closures", {{{"model", "lambertian"}, {"params", {{"reflectance", 0.8}}}}}}};
  const json full = {{"closures", {{{"model", "holdout"}}}}};
  const json half = {{"closures", {{{"model", "holdout"}, {"weight", 0.5}},
                                   {{"model", "lambertian"}, {"weight", 0.5}, {"params", {{"reflectance", 0.8}}}}}}};
  const auto lit = render_floor(read_material_graph(diffuse, "graph", "", store), nullptr, true);
  const auto gone = render_floor(read_material_graph(full, "graph", "", store), nullptr, true);
  const auto halved = render_floor(read_material_graph(half, "graph", "", store), nullptr, true);
  int floor = 0;
  for (size_t i = 0; i < lit.size(); i += 4) {
    if (lit[i + 3] == 0.0f) continue;  // background
    ++floor;
    EXPECT_EQ(gone[i], 0.0f);
    EXPECT_EQ(gone[i + 3], 0.0f);
    EXPECT_FLOAT_EQ(halved[i + 3], 0.5f);
    EXPECT_NEAR(halved[i], 0.5f * lit[i], 1e-6f);
  }
  EXPECT_GT(floor, 100);
  EXPECT_EQ(graph_error({{"closures", {{{"model", "holdout"}, {"params", json::object()}}}}}),
            "(accepted)");
  EXPECT_EQ(graph_error({{"closures", {{{"model", "holdout"}, {"params", {{"color", 1}}}}}}}),
            "graph.closures[0].params: a holdout has no parameters, got {\"color\":1}");
}

// Anisotropic orientation: Rotation turns the tangent about the normal (a quarter turn of the
// point's tangent x is the tangent y), and a Tangent value replaces the point's.
TEST(MaterialGraph, AnisotropicTangentAndRotation) {
  TextureStore store;
  auto glossy = [](const json& extra) {
    json c = {{"model", "cycles_glossy"},
              {"params", {{"distribution", "ggx"}, {"roughness", 0.4}, {"anisotropy", 0.8}}}};
    for (auto it = extra.begin(); it != extra.end(); ++it) c[it.key()] = it.value();
    return json{{"closures", {c}}};
  };
  const Vec3 n(0, 0, 1), t(1, 0, 0);
  auto f = [&](const json& graph) {
    const auto g = read_material_graph(graph, "graph", "", store);
    std::vector<Vec3> registers(MaterialGraph::kMaxRegisters);
    // Without a Tangent value, the closure reads Cycles' default tangent (evaluate fills it).
    EXPECT_GE(g->default_tangent_reg, graph["closures"][0].contains("tangent") ? -1 : 0);
    if (g->default_tangent_reg >= 0) registers[size_t(g->default_tangent_reg)] = t;
    ClosureArena arena;
    BSDF bsdf(Frame::from_normal_tangent(n, Vec3(0, 1, 0)), n);  // not the closure's frame
    g->add_closures(registers.data(), t, arena, bsdf);
    return bsdf.f(normalize(Vec3(0.3f, 0.5f, 1.0f)), normalize(Vec3(-0.6f, 0.1f, 1.0f)));
  };
  const RGB plain = f(glossy(json::object()));
  const RGB turned = f(glossy({{"rotation", 0.25}}));
  const RGB along_y = f(glossy({{"tangent", {0.0, 1.0, 0.0}}}));
  EXPECT_GT(std::fabs(plain.r - turned.r), 1e-3f * plain.r);  // anisotropy shows
  EXPECT_NEAR(turned.r, along_y.r, 1e-5f * along_y.r);
  const RGB full_turn = f(glossy({{"rotation", 1.0}}));
  EXPECT_NEAR(full_turn.r, plain.r, 1e-4f * plain.r);
}

// A batch of hits runs the program node by node over chunks of hits
// (MaterialGraph::evaluate_batch); every hit's registers are what evaluate() gives it alone,
// bit for bit, for a program with grouped images, a normal map, a bump (offset copies of its
// height) and arithmetic, over a batch that is not a whole number of chunks.
TEST(MaterialGraph, BatchEvaluationGivesEveryHitItsOwnRegisters) {
  std::vector<float> rgb;
  for (int i = 0; i < 16; ++i) rgb.insert(rgb.end(), {0.05f * float(i), 0.5f + 0.02f * float(i), 1.0f - 0.04f * float(i)});
  const std::string a = write_pfm("bxdf_batch_a.pfm", 4, 4, rgb);
  std::reverse(rgb.begin(), rgb.end());
  const std::string b = write_pfm("bxdf_batch_b.pfm", 4, 4, rgb);
  TextureStore store;
  const json graph = {
      {"textures", {{{"path", a}, {"colorspace", "srgb"}}, {{"path", b}, {"colorspace", "non_color"}}}},
      {"nodes", {{{"op", "uv"}},
                 {{"op", "image"}, {"texture", 0}, {"vector", {{"node", 0}}}},
                 {{"op", "image"}, {"texture", 1}, {"vector", {{"node", 0}}}},
                 {{"op", "normal_map"}, {"color", {{"node", 2}, {"out", "color"}}}, {"strength", 0.8}},
                 {{"op", "math"}, {"operation", "multiply"}, {"a", {{"node", 1}, {"out", "color"}}}, {"b", 0.7}},
                 {{"op", "bump"}, {"height", {{"node", 4}}}, {"distance", 0.3}, {"normal", {{"node", 3}}}}}},
      {"closures", {{{"model", "cycles_oren_nayar"}, {"params", {{"color", {{"node", 1}, {"out", "color"}}}}},
                     {"normal", {{"node", 5}}}}}}};
  const auto g = read_material_graph(graph, "graph", "", store);
  ASSERT_TRUE(g->reads_offsets);
  ASSERT_EQ(g->nodes[1].group_count, 2);
  Scene scene;
  scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
  Mesh quad = uv_quad();
  quad.tangents = {std::vector<float>(4 * 6, 0.0f)};
  for (size_t c = 0; c < 6; ++c) {
    quad.tangents[0][4 * c] = 1.0f;
    quad.tangents[0][4 * c + 3] = c % 2 ? -1.0f : 1.0f;
  }
  scene.add_mesh(quad.view());
  scene.commit();

  constexpr int kHits = 2 * MaterialGraph::kBatchChunk + 3;
  std::vector<Hit> hits(kHits);
  std::vector<SurfacePoint> points(kHits);
  std::vector<ShadingContext> ctxs(kHits);
  for (int k = 0; k < kHits; ++k) {
    hits[size_t(k)].triangle = uint32_t(k % 2);
    hits[size_t(k)].b1 = 0.04f * float(k % 7) + 0.01f;
    hits[size_t(k)].b2 = 0.9f - 0.03f * float(k);
    points[size_t(k)] = scene.surface_point(hits[size_t(k)]);
    const SurfacePoint& sp = points[size_t(k)];
    const Vec3 incoming = normalize(Vec3(0.1f * float(k % 5) - 0.2f, 0.3f, 1.0f));
    ctxs[size_t(k)] = ShadingContext{&scene, &hits[size_t(k)], sp.p, sp.ns, sp.ng, incoming, false, &sp};
  }
  const size_t n = size_t(g->num_registers);
  std::vector<Vec3> batch(n * kHits, Vec3(-7.0f, -7.0f, -7.0f));
  std::vector<Vec3*> batch_registers;
  for (int k = 0; k < kHits; ++k) batch_registers.push_back(batch.data() + n * size_t(k));
  g->evaluate_batch(ctxs.data(), batch_registers.data(), kHits);
  std::vector<Vec3> alone(MaterialGraph::kMaxRegisters);
  for (int k = 0; k < kHits; ++k) {
    g->evaluate(ctxs[size_t(k)], alone.data());
    for (size_t r = 0; r < n; ++r) {
      const Vec3& got = batch_registers[size_t(k)][r];
      EXPECT_EQ(got.x, alone[r].x) << "hit " << k << " register " << r;
      EXPECT_EQ(got.y, alone[r].y) << "hit " << k << " register " << r;
      EXPECT_EQ(got.z, alone[r].z) << "hit " << k << " register " << r;
    }
  }
  // The bumped normal varies over the hits (the test compares something that moves).
  const Vec3 n0 = batch_registers[0][size_t(g->nodes[5].out)];
  const Vec3 n1 = batch_registers[kHits - 1][size_t(g->nodes[5].out)];
  EXPECT_GT(length(n0 - n1), 1e-3f);
}

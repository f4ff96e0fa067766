// Instancing: a mesh declared once and placed by Embree instances shades and renders as the same
// geometry moved into world space (flattened), for translations, rotations, uniform and
// non-uniform scales and mirrors; emissive instances are lights; visibility applies per
// placement; bad placements are refused naming the instance.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "bxdf/registry.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene_json.h"
#include "bxdf/render/shapes.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

// 3×4 row-major object → world matrices.
using Placement = std::array<float, 12>;

Placement translate_rotate_scale(const Vec3& t, float angle_z, const Vec3& s) {
  const float c = std::cos(angle_z), n = std::sin(angle_z);
  return {c * s.x, -n * s.y, 0, t.x, n * s.x, c * s.y, 0, t.y, 0, 0, s.z, t.z};
}

// The flattened reference: what add_mesh takes for the same placement (positions to world,
// normals by the inverse transpose, winding reversed by a mirror, object transform kept for
// object-space coordinates).
Mesh flattened(const Mesh& mesh, const Placement& m) {
  ObjectTransform xf;
  EXPECT_TRUE(xf.set(m.data()));
  Mesh out = mesh;
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3 p = xf.point_to_world(
        Vec3(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]));
    out.positions[3 * v] = p.x;
    out.positions[3 * v + 1] = p.y;
    out.positions[3 * v + 2] = p.z;
    if (mesh.normals.empty()) continue;
    Vec3 n = xf.normal_to_world(
        Vec3(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]));
    EXPECT_TRUE(normalize_direction(n));
    out.normals[3 * v] = n.x;
    out.normals[3 * v + 1] = n.y;
    out.normals[3 * v + 2] = n.z;
  }
  if (xf.mirrors)
    for (size_t t = 0; t < out.num_triangles(); ++t) std::swap(out.indices[3 * t + 1], out.indices[3 * t + 2]);
  out.object_to_world.assign(m.begin(), m.end());
  return out;
}

struct Placed {
  Mesh mesh;
  std::vector<Placement> placements;
};

// The same objects two ways: instanced (one mesh per kind, placed) and flattened.
void build(Scene& scene, const std::vector<Placed>& objects, bool instanced) {
  for (const Placed& o : objects) {
    if (instanced) {
      const uint32_t id = scene.add_instanced_mesh(o.mesh.view());
      for (const Placement& p : o.placements) scene.add_instance(id, p.data());
    } else {
      for (const Placement& p : o.placements) scene.add_mesh(flattened(o.mesh, p).view());
    }
  }
}

// Materials: 0 diffuse, 1 anisotropic GGX (oriented by the tangent: dp/du, or Cycles' radial
// default from the object's generated coordinates where the mesh has no UVs), 2 emitter.
void add_materials(Scene& scene) {
  ParamSet grey;
  grey.set("reflectance", RGBValue{0.6, 0.5, 0.4});
  scene.add_material(Material{{make("lambertian", grey)}, RGB(0.0f)});
  ParamSet aniso;
  aniso.set("distribution", "ggx");
  aniso.set("alpha_x", 0.05);
  aniso.set("alpha_y", 0.4);
  aniso.set("reflectance", RGBValue{0.9, 0.9, 0.9});
  scene.add_material(Material{{make("microfacet", aniso)}, RGB(0.0f)});
  scene.add_material(Material{{}, RGB(6.0f, 5.0f, 4.0f)});
}

std::vector<Placed> test_objects(bool non_uniform) {
  Mesh ball = make_uv_sphere(Vec3(0, 0, 0), 0.5f, 24, 12, 0);
  Mesh bare = make_uv_sphere(Vec3(0.1f, 0, 0.2f), 0.45f, 24, 12, 1);
  bare.uvs.clear();  // no UVs: the default radial tangent, from generated coordinates
  Mesh lamp = make_quad(Vec3(-0.2f, -0.2f, 0), Vec3(0.4f, 0, 0), Vec3(0, 0.4f, 0), 2);
  const Vec3 one(1, 1, 1);
  const Vec3 stretch = non_uniform ? Vec3(1.3f, 0.6f, 0.9f) : Vec3(0.8f, 0.8f, 0.8f);
  std::vector<Placed> objects;
  objects.push_back({ball,
                     {translate_rotate_scale(Vec3(-1.2f, 0, 0), 0.0f, one),
                      translate_rotate_scale(Vec3(0, 0.3f, 0), 0.7f, stretch),
                      translate_rotate_scale(Vec3(1.2f, 0, 0.1f), -0.4f, Vec3(-1, 1, 1))}});
  objects.push_back({bare,
                     {translate_rotate_scale(Vec3(-0.6f, -0.9f, -0.2f), 1.1f, stretch),
                      translate_rotate_scale(Vec3(0.7f, -0.9f, 0.3f), 2.0f, Vec3(1, -1, 1))}});
  // Emitters facing down onto the balls.
  objects.push_back({lamp,
                     {{1, 0, 0, -0.5f, 0, 1, 0, 0, 0, 0, -1, 2.0f},
                      {0, 1, 0, 0.8f, 1, 0, 0, 0.5f, 0, 0, -1.5f, 1.8f}}});
  return objects;
}

void finish(Scene& scene) {
  scene.add_mesh(make_quad(Vec3(-4, -4, -0.6f), Vec3(8, 0, 0), Vec3(0, 8, 0), 0).view());
  scene.add_light(point_light(Vec3(2, -3, 4), RGB(30.0f)));
  scene.set_world(RGB(0.05f));
  scene.commit();
}

CameraSettings camera() {
  CameraSettings c;
  c.camera_to_world = look_at(Vec3(0.3f, -5, 2.5f), Vec3(0, 0, 0), Vec3(0, 0, 1));
  return c;
}

RenderSettings settings() {
  RenderSettings s;
  s.width = 64;
  s.height = 48;
  s.samples_per_pixel = 16;
  s.max_bounces = 3;
  s.threads = 2;
  return s;
}

}  // namespace

TEST(Instancing, HitsShadeAsTheFlattenedGeometry) {
  for (const bool non_uniform : {false, true}) {
    SCOPED_TRACE(non_uniform ? "non-uniform scale" : "uniform scale");
    Scene inst, flat;
    add_materials(inst);
    add_materials(flat);
    build(inst, test_objects(non_uniform), true);
    build(flat, test_objects(non_uniform), false);
    finish(inst);
    finish(flat);
    EXPECT_EQ(inst.num_instances(), 7u);
    EXPECT_EQ(inst.num_rendered_triangles(), flat.num_triangles());
    EXPECT_LT(inst.num_triangles(), flat.num_triangles());
    int compared = 0, on_instances = 0;
    const Vec3 eye(0.3f, -5, 2.5f);
    for (int i = 0; i < 60; ++i)
      for (int j = 0; j < 60; ++j) {
        Ray ray;
        ray.origin = eye;
        ray.dir = Vec3(-2.0f + 4.0f * (i + 0.5f) / 60, 5.0f, -2.5f + 3.5f * (j + 0.5f) / 60);
        ASSERT_TRUE(normalize_direction(ray.dir));
        Hit a, b;
        const bool ha = inst.intersect(ray, &a, true), hb = flat.intersect(ray, &b, true);
        ASSERT_EQ(ha, hb);
        if (!ha) continue;
        // A ray grazing a shared edge may take either triangle: compare the points only there.
        ASSERT_NEAR(a.t, b.t, 1e-4f * b.t);
        const SurfacePoint pa = inst.surface_point(a), pb = flat.surface_point(b);
        // Without its tangent (a lone diffuse hit's), the same point to the bit, tangent zero.
        SurfacePoint bare;
        inst.surface_point(a, &bare, false);
        EXPECT_TRUE(bare.p == pa.p && bare.ng == pa.ng && bare.ns == pa.ns &&
                    bare.smooth_normal == pa.smooth_normal && bare.uv.x == pa.uv.x &&
                    bare.uv.y == pa.uv.y && bare.material == pa.material);
        EXPECT_EQ(bare.tangent, Vec3(0, 0, 0));
        EXPECT_LT(length(pa.p - pb.p), 1e-4f);
        EXPECT_EQ(pa.material, pb.material);
        on_instances += a.instance != kNotInstanced;
        if (std::fabs(a.b1) < 1e-3f || std::fabs(a.b2) < 1e-3f || a.b1 + a.b2 > 0.999f) continue;
        ++compared;
        EXPECT_GT(dot(pa.ng, pb.ng), 0.99999f);
        // Instanced normals are interpolated in object space, then transformed (as Cycles does
        // for instances); flattened ones per vertex first: equal unless the scale is non-uniform.
        EXPECT_GT(dot(pa.ns, pb.ns), non_uniform ? 0.999f : 0.99999f);
        const Vec3 ga = inst.generated(a, pa.p), gb = flat.generated(b, pb.p);
        // The default tangent is left unnormalised (the shading frame normalises it).
        Vec3 ta = pa.tangent, tb = pb.tangent;
        ASSERT_TRUE(normalize_direction(ta) && normalize_direction(tb));
        EXPECT_GT(dot(ta, tb), 0.9999f);
        EXPECT_LT(length(inst.uv(a, 0) - flat.uv(b, 0)), 1e-4f);
        EXPECT_LT(length(ga - gb), 1e-4f);
        EXPECT_LT(length(inst.object_position(a, pa.p) - flat.object_position(b, pb.p)), 1e-4f);
        EXPECT_EQ(inst.area_light_of(a) >= 0, flat.area_light_of(b) >= 0);
      }
    EXPECT_GT(compared, 600);
    EXPECT_GT(on_instances, 300);
  }
}

TEST(Instancing, RendersAsTheFlattenedGeometry) {
  Scene inst, flat;
  add_materials(inst);
  add_materials(flat);
  build(inst, test_objects(false), true);
  build(flat, test_objects(false), false);
  finish(inst);
  finish(flat);
  // Two mesh lights per scene, one per placed emitter.
  EXPECT_EQ(inst.lights().size(), flat.lights().size());
  const std::vector<float> a = render_scene(inst, camera(), settings()).rgba();
  const std::vector<float> b = render_scene(flat, camera(), settings()).rgba();
  ASSERT_EQ(a.size(), b.size());
  double sum_a = 0.0, diff = 0.0;
  size_t differing = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sum_a += a[i];
    diff += std::fabs(a[i] - b[i]);
    // Same samples, same paths: only float rounding of hit points (a path that grazes an edge
    // may still go another way) separates the two.
    differing += std::fabs(a[i] - b[i]) > 1e-3f * (1.0f + std::fabs(b[i]));
  }
  EXPECT_GT(sum_a, 100.0);
  EXPECT_LT(diff / sum_a, 2e-3);
  EXPECT_LT(differing, a.size() / 100);
}

TEST(Instancing, VisibilityAppliesToEveryPlacement) {
  Scene scene;
  add_materials(scene);
  Mesh ball = make_uv_sphere(Vec3(0, 0, 0), 0.5f, 16, 8, 0);
  ball.visibility.camera = false;
  const uint32_t id = scene.add_instanced_mesh(ball.view());
  const Placement a = translate_rotate_scale(Vec3(-1, 0, 0), 0, Vec3(1, 1, 1));
  const Placement b = translate_rotate_scale(Vec3(1, 0, 0), 0, Vec3(1, 1, 1));
  scene.add_instance(id, a.data());
  scene.add_instance(id, b.data());
  scene.commit();
  for (const float x : {-1.0f, 1.0f}) {
    Ray ray;
    ray.origin = Vec3(x, -5, 0);
    ray.dir = Vec3(0, 1, 0);
    Hit hit;
    EXPECT_FALSE(scene.intersect(ray, &hit, true));  // camera rays pass
    ASSERT_TRUE(scene.intersect(ray, &hit, false));  // other rays hit it
    EXPECT_NEAR(hit.t, 4.5f, 1e-4f);
    EXPECT_EQ(hit.instance, x < 0 ? 0u : 1u);
    EXPECT_NEAR(scene.surface_point(hit).p.x, x, 1e-4f);
  }
}

TEST(Instancing, BadPlacementsAreRefusedNamingThem) {
  Scene scene;
  add_materials(scene);
  const Mesh ball = make_uv_sphere(Vec3(0, 0, 0), 0.5f, 8, 4, 0);
  const uint32_t drawn = scene.add_mesh(ball.view());
  const uint32_t shared = scene.add_instanced_mesh(ball.view());
  const Placement ok = translate_rotate_scale(Vec3(0, 0, 0), 0, Vec3(1, 1, 1));
  auto refused = [&](uint32_t mesh, const float* m, const std::string& says) {
    try {
      scene.add_instance(mesh, m);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused(drawn, ok.data(), "instance 0: mesh 0 is not an instanced mesh");
  refused(7, ok.data(), "instance 0: mesh 7 is not an instanced mesh");
  const Placement flat = translate_rotate_scale(Vec3(0, 0, 0), 0, Vec3(1, 1, 0));
  refused(shared, flat.data(), "instance 0: object_to_world is singular");
  Placement nan = ok;
  nan[3] = std::nanf("");
  refused(shared, nan.data(), "instance 0: object_to_world[3] is nan");
  Placement far = ok;
  far[7] = 1e12f;
  refused(shared, far.data(), "outside [-1e9, 1e9]");
  refused(shared, nullptr, "object_to_world is missing");
  Mesh placed = ball;
  placed.object_to_world.assign(ok.begin(), ok.end());
  EXPECT_THROW(scene.add_instanced_mesh(placed.view()), ParameterError);
  EXPECT_EQ(scene.num_instances(), 0u);
}

namespace {

std::string scene_file(const std::string& prototypes, const std::string& instances) {
  return R"({"camera": {"position": [0, -6, 2], "look_at": [0, 0, 0]},
             "materials": {"grey": {"model": "lambertian"}},
             "lights": [{"type": "sun", "direction": [0, 0.3, -1], "strength": 3}],
             "prototypes": )" + prototypes + R"(, "instances": )" + instances + "}";
}

const char* kBall = R"({"ball": {"shape": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "grey"}})";

std::string json_error(const std::string& text) {
  try {
    parse_scene_json(text, "s.json", ".");
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(Instancing, SceneFilesPlacePrototypes) {
  const LoadedScene loaded = parse_scene_json(
      scene_file(kBall, R"([{"prototype": "ball", "matrix": [[1, 0, 0, -1], [0, 1, 0, 0], [0, 0, 1, 0]]},
                            {"prototype": "ball", "matrix": [[0.5, 0, 0, 1], [0, 0.5, 0, 0], [0, 0, 0.5, 0], [0, 0, 0, 1]]}])"),
      "s.json", ".");
  EXPECT_EQ(loaded.scene->num_instances(), 2u);
  EXPECT_EQ(loaded.scene->num_rendered_triangles(), 2 * loaded.scene->num_triangles());
  Ray ray;
  ray.origin = Vec3(1, -5, 0);
  ray.dir = Vec3(0, 1, 0);
  Hit hit;
  ASSERT_TRUE(loaded.scene->intersect(ray, &hit));
  EXPECT_NEAR(hit.t, 4.75f, 1e-3f);  // the half-size ball at x = 1
}

TEST(Instancing, SceneFileErrorsNameTheField) {
  const std::string row = R"([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]])";
  struct Case {
    std::string prototypes, instances, says;
  };
  const Case cases[] = {
      {kBall, R"([{"prototype": "cube", "matrix": )" + row + "}]",
       "field 'instances[0].prototype': expected the name of a mesh in \"prototypes\" {ball}"},
      {kBall, R"([{"matrix": )" + row + "}]", "field 'instances[0].prototype': is missing"},
      {kBall, R"([{"prototype": "ball"}])", "field 'instances[0].matrix': is missing"},
      {kBall, R"([{"prototype": "ball", "matrix": [[1, 0, 0, 0]]}])",
       "field 'instances[0].matrix': expected 3 or 4 rows of 4 numbers"},
      {kBall, R"([{"prototype": "ball", "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}])",
       "field 'instances[0].matrix[0]': expected 4 numbers"},
      {kBall, R"([{"prototype": "ball", "matrix": [[1, 0, 0, 2e9], [0, 1, 0, 0], [0, 0, 1, 0]]}])",
       "field 'instances[0].matrix[0][3]': expected a number in [-1e9, 1e9]"},
      {kBall, R"([{"prototype": "ball", "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0]]}])",
       "field 'instances[0].matrix': instance 0: object_to_world is singular"},
      {kBall, R"([{"prototype": "ball", "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}])",
       "field 'instances[0].matrix[3]': expected [0, 0, 0, 1] (an affine matrix)"},
      {kBall, R"([{"prototype": "ball", "matrix": )" + row + R"(, "scale": 2}])",
       "field 'instances[0].scale': unknown field"},
      {kBall, R"({"prototype": "ball"})", "field 'instances': expected an array"},
      {kBall, "[]", "field 'instances': expected a non-empty array of instances (or \"meshes\")"},
      {R"({"ball": {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]], "material": "grey",
                    "object_to_world": )" + row + "}}",
       R"([{"prototype": "ball", "matrix": )" + row + "}]",
       "field 'prototypes.ball.object_to_world': a prototype is in its own object space"},
      {"[]", "[]", "field 'prototypes': expected an object of named meshes"},
  };
  for (const Case& c : cases) {
    const std::string message = json_error(scene_file(c.prototypes, c.instances));
    EXPECT_NE(message.find(c.says), std::string::npos) << "expected: " << c.says << "\n got: " << message;
  }
}

// The cost of texturing (issue #11's bound: at most 1.3×): one scene — a floor and two spheres
// under a point light and a grey world — rendered with a Mix of Diffuse and Glossy whose
// parameters are constants, and again with every parameter textured (base colour, roughness,
// a tangent-space normal map and the mix factor, each a 256² image read per hit through a
// material graph). The two variants are rendered back to back `--repeat` times; the median of the
// pairs' ratios is reported, with the best time of each. The time is the render threads' CPU time in tiles
// (RenderStats::tile_cpu_seconds): the work the materials make, without the time other
// processes take the cores away (the process's CPU clock swung by 30% between identical runs).
//
//   bxdf_bench_textured [--threads T] [--spp N] [--size W] [--repeat R] [--only constant|textured]
// (--only renders one variant, for profiling it alone.)
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bxdf/render/camera.h"
#include "bxdf/render/material_graph_json.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/shapes.h"

using namespace bxdf;
using namespace bxdf::render;
using nlohmann::json;

namespace {

int texture_size = 256;

std::string write_texture(const std::string& name, int channels, float (*texel)(int, int, int)) {
  const int n = texture_size;
  std::vector<unsigned char> data(size_t(n) * n * size_t(channels));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < channels; ++c)
        data[(size_t(y) * n + size_t(x)) * size_t(channels) + size_t(c)] =
            static_cast<unsigned char>(std::lround(255.0f * texel(x, y, c)));
  // Named after the process: two benchmarks run at once (an A/B on two cores) keep apart.
  const std::string path =
      (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)).string();
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, OIIO::ImageSpec(n, n, channels, OIIO::TypeDesc::UINT8)) ||
      !out->write_image(OIIO::TypeDesc::UINT8, data.data()) || !out->close()) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
  return path;
}

// Per-corner UVs and tangents (dp/du, sign +1) from the mesh's per-vertex UVs.
void add_uv_map_and_tangents(Mesh& m) {
  std::vector<float> uvs, tangents;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    auto p = [&](int k) { return Vec3(m.positions[3 * i[k]], m.positions[3 * i[k] + 1], m.positions[3 * i[k] + 2]); };
    auto uv = [&](int k, int c) { return m.uvs[2 * i[k] + size_t(c)]; };
    const Vec3 e1 = p(1) - p(0), e2 = p(2) - p(0);
    const float du1 = uv(1, 0) - uv(0, 0), dv1 = uv(1, 1) - uv(0, 1);
    const float du2 = uv(2, 0) - uv(0, 0), dv2 = uv(2, 1) - uv(0, 1);
    const float det = du1 * dv2 - dv1 * du2;
    Vec3 tangent = std::fabs(det) > 1e-12f ? (e1 * dv2 - e2 * dv1) / det : Vec3(1, 0, 0);
    if (!normalize_direction(tangent)) tangent = Vec3(1, 0, 0);
    for (int k = 0; k < 3; ++k) {
      uvs.insert(uvs.end(), {uv(k, 0), uv(k, 1)});
      tangents.insert(tangents.end(), {tangent.x, tangent.y, tangent.z, 1.0f});
    }
  }
  m.uv_maps = {uvs};
  m.tangents = {tangents};
}

double render_seconds(const Scene& scene, const CameraSettings& camera, const RenderSettings& s) {
  RenderStats stats;
  render_scene(scene, camera, s, {}, &stats);
  return stats.tile_cpu_seconds;
}

std::unique_ptr<Scene> make_scene(Material material) {
  auto scene = std::make_unique<Scene>();
  scene->add_material(std::move(material));
  Mesh floor = make_quad(Vec3(-4, -4, -1), Vec3(8, 0, 0), Vec3(0, 8, 0), 0);
  Mesh a = make_uv_sphere(Vec3(-0.6f, 0, 0), 0.9f, 64, 32, 0);
  Mesh b = make_uv_sphere(Vec3(1.2f, 0.6f, -0.4f), 0.6f, 64, 32, 0);
  for (Mesh* m : {&floor, &a, &b}) {
    add_uv_map_and_tangents(*m);
    scene->add_mesh(m->view());
  }
  scene->add_light(point_light(Vec3(2, -3, 4), RGB(60.0f)));
  scene->set_world(RGB(0.2f));
  scene->commit();
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  RenderSettings s;
  s.width = s.height = 160;
  s.samples_per_pixel = 16;
  s.max_bounces = 4;
  s.threads = 2;
  int repeat = 21;  // pairs: their median is steadier than a best-of on a shared machine (9 pairs swung by ±0.03)
  std::string only;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--only") {
      only = argv[i + 1];
      if (only != "constant" && only != "textured") {
        std::fprintf(stderr, "--only: '%s' is neither 'constant' nor 'textured'\n", only.c_str());
        return 2;
      }
      continue;
    }
    const int v = std::atoi(argv[i + 1]);
    if (k == "--threads") s.threads = v;
    else if (k == "--spp") s.samples_per_pixel = v;
    else if (k == "--size") s.width = s.height = v;
    else if (k == "--repeat") repeat = v;
    else if (k == "--texture-size") texture_size = v;
  }

  const std::string colour = write_texture("bxdf_bench_colour.png", 3, [](int x, int y, int c) {
    return 0.2f + 0.6f * float(((x / 32) + (y / 32) + c) % 2);
  });
  const std::string rough = write_texture("bxdf_bench_rough.png", 1, [](int x, int, int) {
    return 0.2f + 0.6f * float(x) / 255.0f;
  });
  const std::string bumps = write_texture("bxdf_bench_normal.png", 3, [](int x, int y, int c) {
    const float dx = 0.3f * std::sin(float(x) * 0.2f), dy = 0.3f * std::cos(float(y) * 0.2f);
    const Vec3 n = normalize(Vec3(dx, dy, 1.0f));
    return 0.5f + 0.5f * n[c];
  });
  const std::string factor = write_texture("bxdf_bench_factor.png", 1, [](int x, int y, int) {
    return float((x ^ y) & 255) / 255.0f;
  });

  // Constant: the same Mix Shader of Diffuse and Glossy with the textures' mean values (colour
  // 0.5, roughness 0.5, factor 0.5, no normal map), so that paths are as long in both variants.
  const json constant_graph = {
      {"closures", {{{"model", "cycles_oren_nayar"}, {"weight", 0.5}, {"params", {{"color", 0.5}, {"roughness", 0.5}}}},
                    {{"model", "cycles_glossy"}, {"weight", 0.5}, {"params", {{"color", 0.5}, {"roughness", 0.5}}}}}}};
  const json textured_graph = {
      {"textures", {{{"path", colour}}, {{"path", rough}, {"colorspace", "non_color"}},
                    {{"path", bumps}, {"colorspace", "non_color"}}, {{"path", factor}, {"colorspace", "non_color"}}}},
      {"nodes", {{{"op", "uv"}},
                 {{"op", "image"}, {"texture", 0}, {"vector", {{"node", 0}}}},
                 {{"op", "image"}, {"texture", 1}, {"vector", {{"node", 0}}}},
                 {{"op", "image"}, {"texture", 2}, {"vector", {{"node", 0}}}},
                 {{"op", "normal_map"}, {"color", {{"node", 3}, {"out", "color"}}}},
                 {{"op", "image"}, {"texture", 3}, {"vector", {{"node", 0}}}},
                 {{"op", "math"}, {"operation", "subtract"}, {"a", 1.0}, {"b", {{"node", 5}, {"out", "color"}}}}}},
      {"closures", {{{"model", "cycles_oren_nayar"}, {"weight", {{"node", 6}, {"out", "value"}}},
                     {"params", {{"color", {{"node", 1}, {"out", "color"}}}, {"roughness", {{"node", 2}, {"out", "color"}}}}},
                     {"normal", {{"node", 4}, {"out", "normal"}}}},
                    {{"model", "cycles_glossy"}, {"weight", {{"node", 5}, {"out", "color"}}},
                     {"params", {{"color", {{"node", 1}, {"out", "color"}}}, {"roughness", {{"node", 2}, {"out", "color"}}}}},
                     {"normal", {{"node", 4}, {"out", "normal"}}}}}}};
  TextureStore store;
  Material constant, textured;
  constant.graph = read_material_graph(constant_graph, "graph", "", store);
  textured.graph = read_material_graph(textured_graph, "graph", "", store);
  const auto constant_scene = make_scene(std::move(constant));
  const auto textured_scene = make_scene(std::move(textured));

  CameraSettings camera;
  camera.camera_to_world = look_at(Vec3(0, -6, 2.5f), Vec3(0, 0, -0.3f), Vec3(0, 0, 1));
  // Each repeat renders the two variants back to back; the machine's slow and fast phases last
  // longer than a pair, so the pair's ratio cancels them where the best times of each may come
  // from different phases. The median of the pairs' ratios is the figure; the best times are
  // shown beside it.
  double best_constant = 1e30, best_textured = 1e30;
  std::vector<double> ratios;
  render_seconds(only == "textured" ? *textured_scene : *constant_scene, camera, s);  // warm-up
  for (int r = 0; r < repeat; ++r) {
    double c = 0.0, t = 0.0;
    if (only != "textured") best_constant = std::min(best_constant, c = render_seconds(*constant_scene, camera, s));
    if (only != "constant") best_textured = std::min(best_textured, t = render_seconds(*textured_scene, camera, s));
    if (only.empty()) ratios.push_back(t / c);
  }
  std::printf("%dx%d, %d spp, %d bounces, %d threads, %d pairs:\n", s.width, s.height,
              s.samples_per_pixel, s.max_bounces, s.threads, repeat);
  if (only != "textured") std::printf("  constant parameters   %.3f s (best)\n", best_constant);
  if (only != "constant")
    std::printf("  every parameter textured (colour, roughness, normal map, mix factor)  %.3f s (best)\n",
                best_textured);
  if (only.empty()) {
    std::sort(ratios.begin(), ratios.end());
    const size_t n = ratios.size();
    const double median = n % 2 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]);
    std::printf("  textured / constant   %.2fx median of the pairs (%.2f-%.2f; best times %.2fx)  (bound: 1.30x)\n",
                median, ratios.front(), ratios.back(), best_textured / best_constant);
  }
  for (const std::string& p : {colour, rough, bumps, factor}) std::filesystem::remove(p);
  return 0;
}

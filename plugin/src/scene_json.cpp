#include "bxdf/render/scene_json.h"

#include <tiny_obj_loader.h>

#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "bxdf/input_file.h"
#include "bxdf/io/json_text.h"
#include "bxdf/io/material_json.h"
#include "bxdf/render/environment.h"
#include "bxdf/render/lights.h"
#include "bxdf/render/material_graph_json.h"
#include "bxdf/render/shapes.h"

namespace bxdf::render {

using nlohmann::json;

namespace {

// Reads one scene file; every message starts with the file name and names the JSON path.
class Reader {
 public:
  Reader(std::string file, std::string base_dir) : file_(std::move(file)), base_(std::move(base_dir)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& expected, const json& got) const {
    // Keys and strings from the file may hold control characters: the whole message is escaped.
    throw SceneFileError(printable(file_ + ": field '" + path + "': expected " + expected + ", got " +
                                   io::describe_json(got)));
  }
  [[noreturn]] void fail_message(const std::string& path, const std::string& message) const {
    throw SceneFileError(printable(file_ + ": field '" + path + "': " + message));
  }

  const json& require(const json& obj, const std::string& path, const char* key) const {
    if (!obj.contains(key)) fail_message(join(path, key), "is missing");
    return obj[key];
  }
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  // Refuses keys that are not in `known`, so that typos do not pass silently.
  void only_keys(const json& obj, const std::string& path,
                 std::initializer_list<const char*> known) const {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool ok = false;
      for (const char* k : known) ok = ok || it.key() == k;
      if (ok) continue;
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      fail_message(join(path, it.key()), "unknown field; expected one of {" + list + "}");
    }
  }
  void object(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, "an object", j);
  }

  bool boolean(const json& j, const std::string& path) const {
    if (!j.is_boolean()) fail(path, "true or false", j);
    return j.get<bool>();
  }
  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "a number", j);
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "a finite number", j);
    return v;
  }
  double number_in(const json& j, const std::string& path, double lo, double hi,
                   const std::string& range) const {
    const double v = number(j, path);
    if (v < lo || v > hi) fail(path, "a number in " + range, j);
    return v;
  }
  int integer_in(const json& j, const std::string& path, long long lo, long long hi,
                 const std::string& range) const {
    if (!j.is_number_integer()) fail(path, "an integer in " + range, j);
    // An unsigned value past INT64_MAX would wrap to a negative long long.
    const bool in_range = j.is_number_unsigned()
                              ? hi >= 0 && j.get<unsigned long long>() <= static_cast<unsigned long long>(hi) &&
                                    static_cast<long long>(j.get<unsigned long long>()) >= lo
                              : j.get<long long>() >= lo && j.get<long long>() <= hi;
    if (!in_range) fail(path, "an integer in " + range, j);
    const long long v = j.get<long long>();
    return static_cast<int>(v);
  }
  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "a string", j);
    return j.get<std::string>();
  }
  Vec3 vec3(const json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != 3) fail(path, "[x, y, z] (3 numbers)", j);
    return Vec3(static_cast<float>(number(j[0], path + "[0]")),
                static_cast<float>(number(j[1], path + "[1]")),
                static_cast<float>(number(j[2], path + "[2]")));
  }
  // A colour: [r, g, b] or one number for grey; non-negative.
  RGB colour(const json& j, const std::string& path) const {
    if (j.is_number()) {
      const float v = static_cast<float>(number_in(j, path, 0.0, 1e30, "[0, inf)"));
      return RGB(v);
    }
    if (!j.is_array() || j.size() != 3) fail(path, "[r, g, b] or a number, each in [0, inf)", j);
    RGB c;
    for (int i = 0; i < 3; ++i)
      c[i] = static_cast<float>(
          number_in(j[i], path + "[" + std::to_string(i) + "]", 0.0, 1e30, "[0, inf)"));
    return c;
  }

  // Flat float array from [[x, y, z], ...] (or a flat list whose length is a multiple of k).
  std::vector<float> floats(const json& j, const std::string& path, size_t k) const {
    const std::string shape = "an array of [" + std::string(k == 3 ? "x, y, z" : "u, v") + "]";
    if (!j.is_array()) fail(path, shape, j);
    std::vector<float> out;
    out.reserve(j.size() * k);
    for (size_t i = 0; i < j.size(); ++i) {
      const std::string p = path + "[" + std::to_string(i) + "]";
      if (!j[i].is_array() || j[i].size() != k) fail(p, std::to_string(k) + " numbers", j[i]);
      for (size_t c = 0; c < k; ++c)
        out.push_back(static_cast<float>(number(j[i][c], p + "[" + std::to_string(c) + "]")));
    }
    return out;
  }
  std::vector<uint32_t> triangles(const json& j, const std::string& path, size_t num_vertices) const {
    if (!j.is_array() || j.empty()) fail(path, "a non-empty array of [i, j, k] vertex indices", j);
    std::vector<uint32_t> out;
    const std::string range = "[0, " + std::to_string(num_vertices - 1) + "]";
    for (size_t t = 0; t < j.size(); ++t) {
      const std::string p = path + "[" + std::to_string(t) + "]";
      if (!j[t].is_array() || j[t].size() != 3) fail(p, "[i, j, k] (3 vertex indices)", j[t]);
      for (size_t c = 0; c < 3; ++c)
        out.push_back(static_cast<uint32_t>(integer_in(
            j[t][c], p + "[" + std::to_string(c) + "]", 0,
            static_cast<long long>(num_vertices) - 1, range)));
    }
    return out;
  }

  std::string file_;
  std::string base_;
};

void read_render_settings(const Reader& r, const json& j, RenderSettings& s) {
  const std::string path = "render";
  r.object(j, path);
  r.only_keys(j, path, {"width", "height", "spp", "max_bounces", "filter", "filter_width", "seed",
                        "tile_size", "transparent_max_bounces", "transparent_background", "region",
                        "adaptive_sampling", "adaptive_threshold", "adaptive_min_samples"});
  if (j.contains("width")) s.width = r.integer_in(j["width"], "render.width", 1, 65536, "[1, 65536]");
  if (j.contains("height"))
    s.height = r.integer_in(j["height"], "render.height", 1, 65536, "[1, 65536]");
  if (j.contains("spp"))
    s.samples_per_pixel = r.integer_in(j["spp"], "render.spp", 1, 1 << 24, "[1, 16777216]");
  if (j.contains("max_bounces"))
    s.max_bounces = r.integer_in(j["max_bounces"], "render.max_bounces", 0, 1024, "[0, 1024]");
  if (j.contains("filter")) {
    const std::string name = r.string(j["filter"], "render.filter");
    try {
      s.filter = parse_filter(name);
    } catch (const ParameterError&) {
      r.fail("render.filter", std::string("one of ") + kFilterNames, j["filter"]);
    }
  }
  if (j.contains("filter_width"))
    s.filter_width = static_cast<float>(
        r.number_in(j["filter_width"], "render.filter_width", 1e-6, 16.0, "(0, 16] pixels"));
  if (j.contains("seed"))
    s.seed = static_cast<uint64_t>(r.integer_in(j["seed"], "render.seed", 0, 2147483647, "[0, 2^31)"));
  if (j.contains("transparent_max_bounces"))
    s.transparent_max_bounces = r.integer_in(j["transparent_max_bounces"],
                                             "render.transparent_max_bounces", 0, 1024, "[0, 1024]");
  if (j.contains("tile_size"))
    s.tile_size = r.integer_in(j["tile_size"], "render.tile_size", 1, 4096, "[1, 4096]");
  if (j.contains("transparent_background"))
    s.transparent_background = r.boolean(j["transparent_background"], "render.transparent_background");
  if (j.contains("adaptive_sampling"))
    s.adaptive_sampling = r.boolean(j["adaptive_sampling"], "render.adaptive_sampling");
  if (j.contains("adaptive_threshold"))
    s.adaptive_threshold = static_cast<float>(r.number_in(
        j["adaptive_threshold"], "render.adaptive_threshold", 0.0, 1.0, "[0, 1] (0 = automatic)"));
  if (j.contains("adaptive_min_samples"))
    s.adaptive_min_samples = r.integer_in(j["adaptive_min_samples"], "render.adaptive_min_samples",
                                          0, 4096, "[0, 4096] (0 = automatic)");
  if (j.contains("region")) {
    // Blender's Render Region in pixels, rows from the top; whether it lies inside the image is
    // checked at render time, against the size the render gets (the CLI may change it).
    const json& region = j["region"];
    const char* shape = "[x_min, y_min, x_max, y_max] (4 integers in [0, 65536], rows from the top)";
    if (!region.is_array() || region.size() != 4) r.fail("render.region", shape, region);
    int* bounds[4] = {&s.region.x0, &s.region.y0, &s.region.x1, &s.region.y1};
    for (size_t i = 0; i < 4; ++i)
      *bounds[i] = r.integer_in(region[i], "render.region[" + std::to_string(i) + "]", 0, 65536,
                                "[0, 65536]");
  }
}

void read_camera(const Reader& r, const json& j, CameraSettings& c) {
  const std::string path = "camera";
  r.object(j, path);
  r.only_keys(j, path, {"type", "ortho_scale", "lens", "sensor_width", "sensor_height", "sensor_fit",
                        "shift_x", "shift_y", "clip_start", "clip_end", "matrix", "position", "look_at",
                        "up"});
  if (j.contains("type")) {
    const std::string type = r.string(j["type"], "camera.type");
    if (type == "PERSP") c.projection = Projection::Perspective;
    else if (type == "ORTHO") c.projection = Projection::Orthographic;
    else r.fail("camera.type", "one of \"PERSP\", \"ORTHO\"", j["type"]);
  }
  if (j.contains("ortho_scale"))
    c.ortho_scale = static_cast<float>(
        r.number_in(j["ortho_scale"], "camera.ortho_scale", 1e-6, 1e30, "(0, inf) scene units"));
  if (j.contains("lens"))
    c.lens_mm = static_cast<float>(r.number_in(j["lens"], "camera.lens", 1e-6, 1e6, "(0, inf) mm"));
  if (j.contains("sensor_width"))
    c.sensor_width_mm = static_cast<float>(
        r.number_in(j["sensor_width"], "camera.sensor_width", 1e-6, 1e6, "(0, inf) mm"));
  if (j.contains("sensor_height"))
    c.sensor_height_mm = static_cast<float>(
        r.number_in(j["sensor_height"], "camera.sensor_height", 1e-6, 1e6, "(0, inf) mm"));
  if (j.contains("sensor_fit")) {
    const std::string fit = r.string(j["sensor_fit"], "camera.sensor_fit");
    if (fit == "AUTO") c.sensor_fit = SensorFit::Auto;
    else if (fit == "HORIZONTAL") c.sensor_fit = SensorFit::Horizontal;
    else if (fit == "VERTICAL") c.sensor_fit = SensorFit::Vertical;
    else r.fail("camera.sensor_fit", "one of \"AUTO\", \"HORIZONTAL\", \"VERTICAL\"", j["sensor_fit"]);
  }
  if (j.contains("shift_x")) c.shift_x = static_cast<float>(r.number(j["shift_x"], "camera.shift_x"));
  if (j.contains("shift_y")) c.shift_y = static_cast<float>(r.number(j["shift_y"], "camera.shift_y"));
  if (j.contains("clip_start"))
    c.clip_start = static_cast<float>(
        r.number_in(j["clip_start"], "camera.clip_start", 0.0, 1e30, "[0, inf)"));
  if (j.contains("clip_end"))
    c.clip_end = static_cast<float>(
        r.number_in(j["clip_end"], "camera.clip_end", 1e-30, 1e30, "(0, inf)"));
  if (!(c.clip_end > c.clip_start))
    r.fail_message("camera.clip_end", "must be greater than clip_start (" +
                                          std::to_string(c.clip_start) + ")");

  if (j.contains("matrix")) {
    if (j.contains("position") || j.contains("look_at"))
      r.fail_message("camera.matrix", "give either matrix or position/look_at, not both");
    const json& m = j["matrix"];
    if (!m.is_array() || m.size() != 4) r.fail("camera.matrix", "4 rows of 4 numbers", m);
    for (size_t row = 0; row < 4; ++row) {
      const std::string p = "camera.matrix[" + std::to_string(row) + "]";
      if (!m[row].is_array() || m[row].size() != 4) r.fail(p, "4 numbers", m[row]);
      for (size_t col = 0; col < 4; ++col)
        c.camera_to_world[4 * row + col] =
            static_cast<float>(r.number(m[row][col], p + "[" + std::to_string(col) + "]"));
    }
  } else {
    const Vec3 eye = r.vec3(r.require(j, path, "position"), "camera.position");
    const Vec3 target = r.vec3(r.require(j, path, "look_at"), "camera.look_at");
    const Vec3 up = j.contains("up") ? r.vec3(j["up"], "camera.up") : Vec3(0, 0, 1);
    try {
      c.camera_to_world = look_at(eye, target, up);
    } catch (const ParameterError& e) {
      r.fail_message("camera.look_at", e.what());
    }
  }
}

// {"name": ..., "graph": {...}}: a material graph (docs/material-graph.md).
uint32_t read_graph_material(const Reader& r, const json& j, const std::string& path, Scene& scene,
                             TextureStore& textures) {
  r.only_keys(j, path, {"graph", "name", "format", "version"});
  Material m;
  try {
    m.graph = read_material_graph(j["graph"], "graph", r.base_, textures);
  } catch (const GraphFieldError& e) {
    r.fail_message(path + "." + e.field, e.problem);
  }
  return scene.add_material(std::move(m));
}

// Per-corner UV maps and tangents, the object transform and the texture space of an inline
// mesh, for material graphs.
void read_graph_attributes(const Reader& r, const json& j, const std::string& path, Mesh& mesh) {
  const size_t corners = 3 * mesh.num_triangles();
  auto per_corner = [&](const char* key, size_t width) {
    std::vector<std::vector<float>> out;
    if (!j.contains(key)) return out;
    const json& maps = j[key];
    if (!maps.is_array()) r.fail(path + "." + key, "an array (one entry per UV map)", maps);
    for (size_t k = 0; k < maps.size(); ++k) {
      const std::string p = path + "." + key + "[" + std::to_string(k) + "]";
      if (maps[k].is_null()) {
        out.emplace_back();
        continue;
      }
      if (!maps[k].is_array() || maps[k].size() != corners)
        r.fail(p, std::to_string(corners) + " entries (one per triangle corner)", maps[k]);
      std::vector<float> flat;
      for (size_t c = 0; c < corners; ++c) {
        const json& e = maps[k][c];
        const std::string pc = p + "[" + std::to_string(c) + "]";
        if (!e.is_array() || e.size() != width) r.fail(pc, std::to_string(width) + " numbers", e);
        for (size_t i = 0; i < width; ++i)
          flat.push_back(static_cast<float>(r.number(e[i], pc + "[" + std::to_string(i) + "]")));
      }
      out.push_back(std::move(flat));
    }
    return out;
  };
  mesh.uv_maps = per_corner("uv_maps", 2);
  for (size_t k = 0; k < mesh.uv_maps.size(); ++k)
    if (mesh.uv_maps[k].empty()) r.fail_message(path + ".uv_maps[" + std::to_string(k) + "]", "is null");
  mesh.tangents = per_corner("tangents", 4);
  if (mesh.tangents.size() > mesh.uv_maps.size())
    r.fail(path + ".tangents", "at most one entry per UV map (" + std::to_string(mesh.uv_maps.size()) + ")",
           j["tangents"]);
  mesh.tangents.resize(mesh.uv_maps.size());
  auto fixed = [&](const char* key, size_t n, std::vector<float>* out) {
    if (!j.contains(key)) return;
    const json& a = j[key];
    std::vector<float> flat;
    const json* items = &a;
    json rows = json::array();
    if (a.is_array() && !a.empty() && a[0].is_array())  // rows of a matrix
      for (const json& row : a)
        for (const json& v : row) rows.push_back(v);
    if (!rows.empty()) items = &rows;
    if (!items->is_array() || items->size() != n)
      r.fail(path + "." + key, std::to_string(n) + " numbers", a);
    for (size_t i = 0; i < n; ++i)
      flat.push_back(static_cast<float>(r.number((*items)[i], path + "." + key + "[" + std::to_string(i) + "]")));
    *out = std::move(flat);
  };
  fixed("object_to_world", 12, &mesh.object_to_world);
  fixed("texture_space", 6, &mesh.texture_space);
}

uint32_t read_material(const Reader& r, const json& j, const std::string& path, Scene& scene,
                       TextureStore& textures) {
  r.object(j, path);
  if (j.contains("graph")) return read_graph_material(r, j, path, scene, textures);
  Material m;
  const std::string where = r.file_ + ": " + path;
  // Either one model (the shared material format) or "components": several combined.
  json model_part = j;
  if (j.contains("emission")) {
    m.emission = r.colour(j["emission"], path + ".emission");
    model_part.erase("emission");
  }
  if (j.contains("components")) {
    r.only_keys(j, path, {"components", "emission", "name"});
    const json& comps = j["components"];
    if (!comps.is_array() || comps.empty() || comps.size() > size_t(BSDF::kMaxComponents))
      r.fail(path + ".components",
             "an array of 1 to " + std::to_string(BSDF::kMaxComponents) + " material objects", comps);
    for (size_t i = 0; i < comps.size(); ++i) {
      const std::string component = where + ".components[" + std::to_string(i) + "]";
      m.components.push_back(io::make_material(io::material_from_json(comps[i], component), component));
    }
  } else if (model_part.contains("model") || model_part.contains("preset")) {
    m.components.push_back(io::make_material(io::material_from_json(model_part, where), where));
  } else if (m.emission.is_black()) {
    r.fail_message(path, "a material needs \"model\" (or \"preset\"), \"components\" or \"emission\"");
  }
  return scene.add_material(std::move(m));
}

Mesh load_obj(const Reader& r, const std::string& file, const std::string& path,
              const std::map<std::string, uint32_t>& materials, const uint32_t* fixed_material) {
  namespace fs = std::filesystem;
  fs::path p(file);
  if (p.is_relative()) p = fs::path(r.base_) / p;
  try {
    check_input_file(p.string(), kMaxMeshFileBytes, "OBJ file");
  } catch (const ParameterError& e) {
    r.fail_message(path, e.what());
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.mtl_search_path = p.parent_path().string();
  tinyobj::ObjReader obj;
  if (!obj.ParseFromFile(p.string(), config))
    r.fail_message(path, "cannot read OBJ file '" + printable(p.string()) + "': " + printable(obj.Error()));
  const tinyobj::attrib_t& a = obj.GetAttrib();
  const auto& obj_materials = obj.GetMaterials();
  // Face indices come from the file: each must name an existing position, normal or UV (the
  // loader has already turned negative, relative indices into absolute ones).
  const auto check_index = [&](int index, size_t count, const char* what, const std::string& shape,
                               size_t face) {
    if (index >= 0 && static_cast<size_t>(index) < count) return;
    r.fail_message(path, "OBJ file '" + printable(p.string()) + "', object '" + printable(shape) +
                             "', face " + std::to_string(face + 1) + ": " + what + " index " +
                             (index < 0 ? "missing or invalid (0 or before the first)"
                                        : std::to_string(index + 1)) +
                             " is out of range [1, " + std::to_string(count) + "]");
  };

  // OBJ indexes positions, normals and UVs separately: make one vertex per distinct triple.
  Mesh mesh;
  std::map<std::tuple<int, int, int>, uint32_t> vertex_of;
  bool all_normals = true, all_uvs = true;
  for (const auto& shape : obj.GetShapes())
    for (size_t i = 0; i < shape.mesh.indices.size(); ++i) {
      // The loader marks a missing normal or UV with -1; a relative index that points before
      // the first entry comes out below -1.
      const tinyobj::index_t& idx = shape.mesh.indices[i];
      if (idx.normal_index < -1) check_index(idx.normal_index, a.normals.size() / 3, "normal", shape.name, i / 3);
      if (idx.texcoord_index < -1) check_index(idx.texcoord_index, a.texcoords.size() / 2, "texture", shape.name, i / 3);
      all_normals = all_normals && idx.normal_index >= 0;
      all_uvs = all_uvs && idx.texcoord_index >= 0;
    }
  for (const auto& shape : obj.GetShapes()) {
    const auto& sm = shape.mesh;
    for (size_t f = 0; f < sm.num_face_vertices.size(); ++f) {
      if (sm.num_face_vertices[f] != 3) continue;  // triangulated; skip degenerate leftovers
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t idx = sm.indices[3 * f + size_t(k)];
        check_index(idx.vertex_index, a.vertices.size() / 3, "vertex", shape.name, f);
        if (all_normals) check_index(idx.normal_index, a.normals.size() / 3, "normal", shape.name, f);
        if (all_uvs) check_index(idx.texcoord_index, a.texcoords.size() / 2, "texture", shape.name, f);
        const auto key = std::make_tuple(idx.vertex_index, all_normals ? idx.normal_index : -1,
                                         all_uvs ? idx.texcoord_index : -1);
        auto it = vertex_of.find(key);
        if (it == vertex_of.end()) {
          const uint32_t id = static_cast<uint32_t>(mesh.positions.size() / 3);
          for (int c = 0; c < 3; ++c) mesh.positions.push_back(a.vertices[3 * size_t(idx.vertex_index) + c]);
          if (all_normals)
            for (int c = 0; c < 3; ++c) mesh.normals.push_back(a.normals[3 * size_t(idx.normal_index) + c]);
          if (all_uvs)
            for (int c = 0; c < 2; ++c) mesh.uvs.push_back(a.texcoords[2 * size_t(idx.texcoord_index) + c]);
          it = vertex_of.emplace(key, id).first;
        }
        mesh.indices.push_back(it->second);
      }
      if (fixed_material) {
        mesh.material_indices.push_back(*fixed_material);
      } else {
        // Without a "material" field, the OBJ's own usemtl names pick scene materials.
        const int mid = f < sm.material_ids.size() ? sm.material_ids[f] : -1;
        const std::string name =
            mid >= 0 && size_t(mid) < obj_materials.size() ? obj_materials[size_t(mid)].name : "";
        auto found = materials.find(name);
        if (found == materials.end())
          r.fail_message(path, name.empty()
                                   ? "an OBJ face has no material (usemtl naming an entry of its "
                                     ".mtl file); give the mesh a \"material\""
                                   : "OBJ face uses material '" + name +
                                         "', which the scene's \"materials\" does not define "
                                         "(or give the mesh a \"material\")");
        mesh.material_indices.push_back(found->second);
      }
    }
  }
  if (mesh.indices.empty()) r.fail_message(path, "OBJ file '" + p.string() + "' has no triangles");
  return mesh;
}

uint32_t material_ref(const Reader& r, const json& j, const std::string& path,
                      const std::map<std::string, uint32_t>& materials) {
  const std::string name = r.string(j, path);
  auto it = materials.find(name);
  if (it == materials.end()) {
    std::string known;
    for (const auto& [k, v] : materials) known += (known.empty() ? "" : ", ") + k;
    r.fail(path, "the name of a material in \"materials\" {" + known + "}", j);
  }
  return it->second;
}

// A mesh of "meshes" (drawn where it is) or of "prototypes" (`instanced`: in its own object
// space, drawn only by "instances"); returns its scene index.
uint32_t read_mesh(const Reader& r, const json& j, const std::string& path,
                   const std::map<std::string, uint32_t>& materials, Scene& scene,
                   bool instanced = false) {
  r.object(j, path);
  Mesh mesh;
  uint32_t fixed = 0;
  const bool has_material = j.contains("material");
  if (has_material) fixed = material_ref(r, j["material"], path + ".material", materials);
  if (j.contains("obj")) {
    r.only_keys(j, path, {"obj", "material"});
    mesh = load_obj(r, r.string(j["obj"], path + ".obj"), path + ".obj", materials,
                    has_material ? &fixed : nullptr);
  } else if (j.contains("shape")) {
    const std::string shape = r.string(j["shape"], path + ".shape");
    if (!has_material) r.fail_message(path + ".material", "is missing");
    if (shape == "sphere") {
      r.only_keys(j, path, {"shape", "material", "center", "radius", "segments", "rings"});
      const Vec3 c = r.vec3(r.require(j, path, "center"), path + ".center");
      const float radius = static_cast<float>(
          r.number_in(r.require(j, path, "radius"), path + ".radius", 1e-30, 1e30, "(0, inf)"));
      const int seg = j.contains("segments")
                          ? r.integer_in(j["segments"], path + ".segments", 3, 4096, "[3, 4096]")
                          : 64;
      const int rings = j.contains("rings")
                            ? r.integer_in(j["rings"], path + ".rings", 2, 4096, "[2, 4096]")
                            : 32;
      mesh = make_uv_sphere(c, radius, seg, rings, fixed);
    } else if (shape == "quad") {
      r.only_keys(j, path, {"shape", "material", "corner", "edge_u", "edge_v"});
      mesh = make_quad(r.vec3(r.require(j, path, "corner"), path + ".corner"),
                       r.vec3(r.require(j, path, "edge_u"), path + ".edge_u"),
                       r.vec3(r.require(j, path, "edge_v"), path + ".edge_v"), fixed);
    } else if (shape == "box") {
      r.only_keys(j, path, {"shape", "material", "min", "max"});
      mesh = make_box(r.vec3(r.require(j, path, "min"), path + ".min"),
                      r.vec3(r.require(j, path, "max"), path + ".max"), fixed);
    } else {
      r.fail(path + ".shape", "one of \"sphere\", \"quad\", \"box\"", j["shape"]);
    }
  } else if (j.contains("positions")) {
    r.only_keys(j, path, {"positions", "indices", "normals", "uvs", "material", "material_indices",
                          "materials", "uv_maps", "tangents", "object_to_world", "texture_space"});
    mesh.positions = r.floats(j["positions"], path + ".positions", 3);
    if (mesh.positions.empty()) r.fail(path + ".positions", "a non-empty array of [x, y, z]", j["positions"]);
    const size_t nv = mesh.num_vertices();
    mesh.indices = r.triangles(r.require(j, path, "indices"), path + ".indices", nv);
    if (j.contains("normals")) {
      mesh.normals = r.floats(j["normals"], path + ".normals", 3);
      if (mesh.normals.size() != mesh.positions.size())
        r.fail(path + ".normals", std::to_string(nv) + " normals (one per position)", j["normals"]);
    }
    if (j.contains("uvs")) {
      mesh.uvs = r.floats(j["uvs"], path + ".uvs", 2);
      if (mesh.uvs.size() != 2 * nv)
        r.fail(path + ".uvs", std::to_string(nv) + " UVs (one per position)", j["uvs"]);
    }
    read_graph_attributes(r, j, path, mesh);
    if (j.contains("material_indices")) {
      // Per-triangle indices into this mesh's "materials" list of names.
      const json& names = r.require(j, path, "materials");
      if (!names.is_array() || names.empty())
        r.fail(path + ".materials", "a non-empty array of material names", names);
      std::vector<uint32_t> local;
      for (size_t i = 0; i < names.size(); ++i)
        local.push_back(material_ref(r, names[i], path + ".materials[" + std::to_string(i) + "]", materials));
      const json& mi = j["material_indices"];
      const size_t nt = mesh.num_triangles();
      if (!mi.is_array() || mi.size() != nt)
        r.fail(path + ".material_indices", std::to_string(nt) + " integers (one per triangle)", mi);
      for (size_t t = 0; t < nt; ++t)
        mesh.material_indices.push_back(local[size_t(r.integer_in(
            mi[t], path + ".material_indices[" + std::to_string(t) + "]", 0,
            static_cast<long long>(local.size()) - 1,
            "[0, " + std::to_string(local.size() - 1) + "]"))]);
    } else if (!has_material) {
      r.fail_message(path + ".material", "is missing (or give materials + material_indices)");
    }
    mesh.material = fixed;
  } else {
    r.fail_message(path, "a mesh needs \"obj\", \"shape\" or \"positions\"");
  }
  mesh.material = fixed;
  if (instanced && !mesh.object_to_world.empty())
    r.fail_message(path + ".object_to_world",
                   "a prototype is in its own object space; each instance's \"matrix\" places it");
  try {
    return instanced ? scene.add_instanced_mesh(mesh.view()) : scene.add_mesh(mesh.view());
  } catch (const ParameterError& e) {
    r.fail_message(path, e.what());
  }
}

// "instances": [{"prototype": name, "matrix": 3×4 or 4×4 rows (object → world, affine,
// invertible)}, ...].
void read_instances(const Reader& r, const json& list, const std::map<std::string, uint32_t>& prototypes,
                    Scene& scene) {
  if (!list.is_array()) r.fail("instances", "an array of {\"prototype\": name, \"matrix\": rows}", list);
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "instances[" + std::to_string(i) + "]";
    const json& j = list[i];
    r.object(j, path);
    r.only_keys(j, path, {"prototype", "matrix"});
    const std::string name = r.string(r.require(j, path, "prototype"), path + ".prototype");
    const auto it = prototypes.find(name);
    if (it == prototypes.end()) {
      std::string known;
      for (const auto& [k, v] : prototypes) known += (known.empty() ? "" : ", ") + k;
      r.fail(path + ".prototype", "the name of a mesh in \"prototypes\" {" + known + "}", j["prototype"]);
    }
    const json& m = r.require(j, path, "matrix");
    const std::string mp = path + ".matrix";
    if (!m.is_array() || (m.size() != 3 && m.size() != 4))
      r.fail(mp, "3 or 4 rows of 4 numbers (object to world)", m);
    float rows[16];
    for (size_t row = 0; row < m.size(); ++row) {
      const std::string rp = mp + "[" + std::to_string(row) + "]";
      if (!m[row].is_array() || m[row].size() != 4) r.fail(rp, "4 numbers", m[row]);
      for (size_t c = 0; c < 4; ++c)
        rows[4 * row + c] = static_cast<float>(r.number_in(m[row][c], rp + "[" + std::to_string(c) + "]",
                                                           -1e9, 1e9, "[-1e9, 1e9]"));
    }
    if (m.size() == 4 && !(rows[12] == 0.0f && rows[13] == 0.0f && rows[14] == 0.0f && rows[15] == 1.0f))
      r.fail(mp + "[3]", "[0, 0, 0, 1] (an affine matrix)", m[3]);
    try {
      scene.add_instance(it->second, rows);
    } catch (const ParameterError& e) {
      r.fail_message(mp, e.what());
    }
  }
}

Light read_light(const Reader& r, const json& j, const std::string& path) {
  r.object(j, path);
  const std::string type = r.string(r.require(j, path, "type"), path + ".type");
  // Intensity (W/sr) directly, or Blender's power (W) and colour.
  const auto intensity = [&]() -> RGB {
    if (j.contains("intensity")) {
      if (j.contains("power")) r.fail_message(path, "give intensity or power, not both");
      return r.colour(j["intensity"], path + ".intensity");
    }
    const float power = static_cast<float>(
        r.number_in(r.require(j, path, "power"), path + ".power", 0.0, 1e30, "[0, inf) W"));
    const RGB color = j.contains("color") ? r.colour(j["color"], path + ".color") : RGB(1.0f);
    return color * (power * kInv4Pi);
  };
  const auto radius = [&]() -> float {
    return j.contains("radius") ? static_cast<float>(r.number_in(j["radius"], path + ".radius", 0.0,
                                                                 1e30, "[0, inf) m"))
                                : 0.0f;
  };
  try {
    if (type == "point") {
      r.only_keys(j, path, {"type", "position", "intensity", "power", "color", "radius"});
      return point_light(r.vec3(r.require(j, path, "position"), path + ".position"), intensity(),
                         radius());
    }
    if (type == "area") {
      // A Blender area light: centre, full edge vectors along its X and Y; it emits along −Z,
      // that is along edge_v × edge_u.
      r.only_keys(j, path, {"type", "position", "edge_u", "edge_v", "shape", "power", "color"});
      const std::string shape = j.contains("shape") ? r.string(j["shape"], path + ".shape") : "rectangle";
      if (shape != "rectangle" && shape != "square" && shape != "ellipse" && shape != "disk")
        r.fail(path + ".shape", "one of \"square\", \"rectangle\", \"disk\", \"ellipse\"", j["shape"]);
      const Vec3 eu = r.vec3(r.require(j, path, "edge_u"), path + ".edge_u");
      const Vec3 ev = r.vec3(r.require(j, path, "edge_v"), path + ".edge_v");
      const float power = static_cast<float>(
          r.number_in(r.require(j, path, "power"), path + ".power", 0.0, 1e30, "[0, inf) W"));
      return area_light_from_power(
          r.vec3(r.require(j, path, "position"), path + ".position"), eu, ev, cross(ev, eu),
          shape == "ellipse" || shape == "disk" ? AreaShape::Ellipse : AreaShape::Rectangle, power,
          j.contains("color") ? r.colour(j["color"], path + ".color") : RGB(1.0f));
    }
    if (type == "spot") {
      r.only_keys(j, path, {"type", "position", "direction", "intensity", "power", "color",
                            "spot_size", "spot_blend", "radius"});
      const float size = j.contains("spot_size")
                             ? static_cast<float>(r.number_in(j["spot_size"], path + ".spot_size",
                                                              1e-9, kPi, "(0, pi] radians"))
                             : radians(45.0f);
      const float blend = j.contains("spot_blend")
                              ? static_cast<float>(
                                    r.number_in(j["spot_blend"], path + ".spot_blend", 0, 1, "[0, 1]"))
                              : 0.15f;
      return spot_light(r.vec3(r.require(j, path, "position"), path + ".position"),
                        r.vec3(r.require(j, path, "direction"), path + ".direction"), intensity(),
                        size, blend, radius());
    }
    if (type == "sun") {
      r.only_keys(j, path, {"type", "direction", "irradiance", "strength", "color", "angle"});
      RGB e;
      if (j.contains("irradiance")) {
        if (j.contains("strength")) r.fail_message(path, "give irradiance or strength, not both");
        e = r.colour(j["irradiance"], path + ".irradiance");
      } else {
        const float strength = static_cast<float>(r.number_in(
            r.require(j, path, "strength"), path + ".strength", 0.0, 1e30, "[0, inf) W/m^2"));
        e = (j.contains("color") ? r.colour(j["color"], path + ".color") : RGB(1.0f)) * strength;
      }
      const float angle = j.contains("angle")
                              ? static_cast<float>(r.number_in(j["angle"], path + ".angle", 0.0,
                                                               kPi * 0.999, "[0, pi) radians"))
                              : 0.0f;
      return sun_light(r.vec3(r.require(j, path, "direction"), path + ".direction"), e, angle);
    }
  } catch (const SceneFileError&) {
    throw;
  } catch (const ParameterError& e) {
    r.fail_message(path, e.what());
  }
  r.fail(path + ".type", "one of \"point\", \"spot\", \"sun\", \"area\"", j["type"]);
}

// {"color": rgb, "texture": {"path", "weight", "matrix" (3×4 rows), "interpolation"},
//  "sampling": "auto"|"manual"|"none", "map_resolution": n}: see environment.h.
EnvironmentSettings read_world(const Reader& r, const json& w) {
  r.only_keys(w, "world", {"color", "texture", "sampling", "map_resolution"});
  EnvironmentSettings s;
  if (w.contains("color")) s.constant = r.colour(w["color"], "world.color");
  if (w.contains("texture")) {
    const json& t = w["texture"];
    r.object(t, "world.texture");
    r.only_keys(t, "world.texture", {"path", "weight", "matrix", "interpolation"});
    std::filesystem::path p = r.string(r.require(t, "world.texture", "path"), "world.texture.path");
    if (p.is_relative()) p = std::filesystem::path(r.base_) / p;
    try {
      s.image = load_equirect_image(p.string());
    } catch (const std::exception& e) {
      r.fail_message("world.texture.path", e.what());
    }
    s.weight = t.contains("weight") ? r.colour(t["weight"], "world.texture.weight") : RGB(1.0f);
    if (t.contains("matrix")) {
      const json& m = t["matrix"];
      if (!m.is_array() || m.size() != 3) r.fail("world.texture.matrix", "3 rows of 4 numbers", m);
      for (int i = 0; i < 3; ++i) {
        const std::string row = "world.texture.matrix[" + std::to_string(i) + "]";
        if (!m[i].is_array() || m[i].size() != 4) r.fail(row, "4 numbers", m[i]);
        for (int k = 0; k < 4; ++k)
          s.matrix[4 * i + k] = static_cast<float>(r.number(m[i][k], row + "[" + std::to_string(k) + "]"));
      }
    }
    if (t.contains("interpolation")) {
      const std::string mode = r.string(t["interpolation"], "world.texture.interpolation");
      if (mode == "closest") s.interpolation = TextureInterpolation::Closest;
      else if (mode != "linear") r.fail("world.texture.interpolation", "\"closest\" or \"linear\"", t["interpolation"]);
    }
  }
  if (w.contains("sampling")) {
    const std::string mode = r.string(w["sampling"], "world.sampling");
    if (mode == "none") s.importance_sample = false;
    else if (mode != "auto" && mode != "manual") r.fail("world.sampling", "\"auto\", \"manual\" or \"none\"", w["sampling"]);
  }
  if (w.contains("map_resolution"))
    s.map_resolution = r.integer_in(w["map_resolution"], "world.map_resolution", 0, 65536, "[0, 65536] (even)");
  return s;
}

}  // namespace

LoadedScene parse_scene_json(const std::string& text, const std::string& name,
                             const std::string& base_dir) {
  json root;
  try {
    root = io::parse_json(text, name);
  } catch (const ParameterError& e) {
    throw SceneFileError(e.what());
  }
  const Reader r(name, base_dir);
  if (!root.is_object()) r.fail("(root)", "an object", root);
  r.only_keys(root, "", {"render", "camera", "world", "materials", "meshes", "prototypes", "instances",
                         "lights"});

  LoadedScene out;
  out.scene = std::make_unique<Scene>();
  Scene& scene = *out.scene;
  if (root.contains("render")) read_render_settings(r, root["render"], out.settings);
  read_camera(r, r.require(root, "", "camera"), out.camera);
  if (root.contains("world")) {
    const json& w = root["world"];
    if (w.is_object()) {
      try {
        scene.set_world(read_world(r, w));
      } catch (const ParameterError& e) {
        r.fail_message("world", e.what());
      }
    } else {
      scene.set_world(r.colour(w, "world"));
    }
  }

  std::map<std::string, uint32_t> materials;
  TextureStore textures;  // images shared by the materials' graphs
  const json& mats = r.require(root, "", "materials");
  if (!mats.is_object() || mats.empty())
    r.fail("materials", "an object of named materials {\"name\": {\"model\": ..., \"params\": ...}}", mats);
  for (auto it = mats.begin(); it != mats.end(); ++it) {
    try {
      materials[it.key()] = read_material(r, it.value(), "materials." + it.key(), scene, textures);
    } catch (const SceneFileError&) {
      throw;
    } catch (const ParameterError& e) {
      // The shared material reader already names the file and the material's path.
      const std::string msg = e.what();
      throw SceneFileError(msg.rfind(name, 0) == 0 ? msg : name + ": materials." + it.key() + ": " + msg);
    }
  }

  // Meshes drawn where they are, and prototypes drawn by instances: at least one of them.
  if (!root.contains("instances")) {
    const json& meshes = r.require(root, "", "meshes");
    if (!meshes.is_array() || meshes.empty()) r.fail("meshes", "a non-empty array of meshes", meshes);
  }
  if (root.contains("meshes")) {
    const json& meshes = root["meshes"];
    if (!meshes.is_array()) r.fail("meshes", "an array of meshes", meshes);
    for (size_t i = 0; i < meshes.size(); ++i)
      read_mesh(r, meshes[i], "meshes[" + std::to_string(i) + "]", materials, scene);
  }
  std::map<std::string, uint32_t> prototypes;
  if (root.contains("prototypes")) {
    const json& protos = root["prototypes"];
    if (!protos.is_object()) r.fail("prototypes", "an object of named meshes {\"name\": mesh}", protos);
    for (auto it = protos.begin(); it != protos.end(); ++it)
      prototypes[it.key()] = read_mesh(r, it.value(), "prototypes." + it.key(), materials, scene, true);
  }
  if (root.contains("instances")) {
    const json& instances = root["instances"];
    read_instances(r, instances, prototypes, scene);
    if (scene.num_instances() == 0 && !root.contains("meshes"))
      r.fail("instances", "a non-empty array of instances (or \"meshes\")", instances);
  }

  if (root.contains("lights")) {
    const json& lights = root["lights"];
    if (!lights.is_array()) r.fail("lights", "an array of lights", lights);
    for (size_t i = 0; i < lights.size(); ++i)
      scene.add_light(read_light(r, lights[i], "lights[" + std::to_string(i) + "]"));
  }
  scene.commit();
  // The camera must be valid for the image size; report it against the file.
  try {
    Camera(out.camera, out.settings.width, out.settings.height);
  } catch (const ParameterError& e) {
    r.fail_message("camera", e.what());
  }
  return out;
}

LoadedScene load_scene_json(const std::string& path) {
  std::string text;
  try {
    text = read_input_file(path, kMaxJsonFileBytes, "scene file");
  } catch (const ParameterError& e) {
    throw SceneFileError(e.what());
  }
  const std::string base = std::filesystem::path(path).parent_path().string();
  return parse_scene_json(text, printable(path), base.empty() ? "." : base);
}

}  // namespace bxdf::render

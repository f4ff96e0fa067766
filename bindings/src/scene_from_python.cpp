#include "scene_from_python.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "bxdf/params.h"
#include "array_args.h"
#include "bxdf/render/camera.h"
#include "bxdf/render/filter.h"
#include "bxdf/render/environment.h"
#include "bxdf/render/lights.h"
#include "graph_from_python.h"
#include "mesh_welding.h"
#include "model.h"

namespace bxdf::python {

namespace {

using render::Light;
using render::Material;
using render::Mesh;

// int32, Blender's own index type: its arrays are used in place, not widened into copies.
using IndexArray = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;
using Float32Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
using Float64Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

constexpr double kInf = std::numeric_limits<double>::infinity();

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw ParameterError(path + ": " + why);
}

std::string key_path(const std::string& path, const char* key) { return path + "['" + key + "']"; }
std::string item_path(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string short_repr(py::handle v) {
  std::string s = py::repr(v).cast<std::string>();
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

std::string type_name(py::handle v) { return py::str(py::type::handle_of(v).attr("__name__")).cast<std::string>(); }

std::string num(double v) {
  std::string s = py::repr(py::float_(v)).cast<std::string>();
  return s;
}

py::dict as_dict(py::handle v, const std::string& path) {
  if (!PyDict_Check(v.ptr())) refuse(path, "is a " + type_name(v) + "; expected a dict");
  return py::reinterpret_borrow<py::dict>(v);
}

bool has(const py::dict& d, const char* key) { return d.contains(key) && !d[key].is_none(); }

py::object required(const py::dict& d, const char* key, const std::string& path, const std::string& expected) {
  if (!d.contains(key)) refuse(key_path(path, key), "is missing; expected " + expected);
  py::object v = d[key];
  if (v.is_none()) refuse(key_path(path, key), "is None; expected " + expected);
  return v;
}

py::list as_list(py::handle v, const std::string& path, const std::string& expected) {
  if (!PyList_Check(v.ptr()) && !PyTuple_Check(v.ptr()))
    refuse(path, "is a " + type_name(v) + "; expected " + expected);
  return py::list(py::reinterpret_borrow<py::object>(v));
}

double number(py::handle v, const std::string& path, double lo, double hi, const std::string& range) {
  if (PyBool_Check(v.ptr()) || !PyNumber_Check(v.ptr()) || PyComplex_Check(v.ptr()))
    refuse(path, short_repr(v) + " is not a number; expected a number in " + range);
  double x;
  try {
    x = v.cast<double>();
  } catch (const py::cast_error&) {
    refuse(path, short_repr(v) + " is not a real number; expected a number in " + range);
  }
  if (!std::isfinite(x) || x < lo || x > hi) refuse(path, num(x) + " is out of range; expected a number in " + range);
  return x;
}

long long integer(py::handle v, const std::string& path, long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (PyBool_Check(v.ptr()) || PyFloat_Check(v.ptr()) || !PyIndex_Check(v.ptr()))
    refuse(path, short_repr(v) + " is not an integer; expected an integer in " + range);
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
  if (!index) throw py::error_already_set();  // e.g. KeyboardInterrupt inside __index__
  const long long x = PyLong_AsLongLong(index.ptr());
  if (x == -1 && PyErr_Occurred()) {
    if (!PyErr_ExceptionMatches(PyExc_OverflowError)) throw py::error_already_set();
    PyErr_Clear();
    refuse(path, short_repr(v) + " is out of range; expected an integer in " + range);
  }
  if (x < lo || x > hi) refuse(path, std::to_string(x) + " is out of range; expected an integer in " + range);
  return x;
}

std::string text(py::handle v, const std::string& path, const std::string& expected) {
  if (!py::isinstance<py::str>(v)) refuse(path, short_repr(v) + " is not a str; expected " + expected);
  return v.cast<std::string>();
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Any array-like of real numbers with exactly `shape` (-1 = any length), as C-contiguous T.
template <typename Array>
Array real_array(py::handle v, const std::string& path, std::vector<py::ssize_t> shape, bool integers_only) {
  const std::string dims = [&] {
    std::string s = "(";
    for (size_t i = 0; i < shape.size(); ++i)
      s += (i ? ", " : "") + (shape[i] < 0 ? std::string(i == 0 ? "N" : "M") : std::to_string(shape[i]));
    return s + (shape.size() == 1 ? ",)" : ")");
  }();
  const std::string expected = std::string(integers_only ? "an integer" : "a real") + " array of shape " + dims;
  const py::array a = as_numpy_array(v, path);
  const char kind = a.dtype().kind();
  if (integers_only ? (kind != 'i' && kind != 'u') : (kind != 'f' && kind != 'i' && kind != 'u'))
    refuse(path, "has dtype " + py::str(a.dtype()).cast<std::string>() + "; expected " + expected);
  bool ok = a.ndim() == static_cast<py::ssize_t>(shape.size());
  for (size_t i = 0; ok && i < shape.size(); ++i) ok = shape[i] < 0 || a.shape(i) == shape[i];
  if (!ok) {
    std::string got = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) got += (i ? ", " : "") + std::to_string(a.shape(i));
    got += a.ndim() == 1 ? ",)" : ")";
    refuse(path, "has shape " + got + "; expected " + expected);
  }
  if constexpr (std::is_same_v<typename Array::value_type, int32_t>) {
    // Wider integers are narrowed by forcecast, which would wrap: refuse what does not fit.
    if (a.size() > 0 && (a.itemsize() > 4 || (kind == 'u' && a.itemsize() == 4))) {
      for (const char* end : {"min", "max"}) {
        const py::object x = a.attr(end)();
        const py::int_ lo(std::numeric_limits<int32_t>::min()), hi(std::numeric_limits<int32_t>::max());
        if (PyObject_RichCompareBool(x.ptr(), lo.ptr(), Py_LT) == 1 ||
            PyObject_RichCompareBool(x.ptr(), hi.ptr(), Py_GT) == 1)
          refuse(path, "has index " + py::str(x).cast<std::string>() +
                           ", outside the 32-bit range [-2147483648, 2147483647]");
      }
    }
  }
  return Array::ensure(a);
}

void require_finite(const float* p, size_t n, size_t width, const std::string& path) {
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(p[i]))
      refuse(path, "row " + std::to_string(i / width) + " has " + num(p[i]) + "; expected finite numbers");
}

void require_indices(const IndexArray& a, long long lo, long long hi, const std::string& path) {
  const int32_t* p = a.data();
  const size_t n = static_cast<size_t>(a.size());
  const size_t width = a.ndim() == 2 ? static_cast<size_t>(a.shape(1)) : 1;
  for (size_t i = 0; i < n; ++i)
    if (p[i] < lo || p[i] >= hi)
      refuse(path, "index " + std::to_string(p[i]) + " out of range [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + ") (row " + std::to_string(i / width) + ")");
}

std::vector<double> numbers(py::handle v, const std::string& path, py::ssize_t count) {
  auto a = real_array<Float64Array>(v, path, {count}, false);
  std::vector<double> out(a.data(), a.data() + a.size());
  for (double x : out)
    if (!std::isfinite(x)) refuse(path, "has " + num(x) + "; expected finite numbers");
  return out;
}

Vec3 vec3(py::handle v, const std::string& path) {
  const auto x = numbers(v, path, 3);
  return {static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2])};
}

RGB colour(py::handle v, const std::string& path) {
  const auto x = numbers(v, path, 3);
  for (double c : x)
    if (c < 0.0) refuse(path, "has " + num(c) + "; expected three numbers in [0, inf)");
  return {static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2])};
}

std::array<double, 16> checked_matrix(const double* data, const std::string& path, bool affine) {
  std::array<double, 16> m;
  std::copy(data, data + 16, m.begin());
  for (double x : m)
    if (!std::isfinite(x)) refuse(path, "has " + num(x) + "; expected a finite 4x4 matrix");
  if (affine && (std::abs(m[12]) > 1e-6 || std::abs(m[13]) > 1e-6 || std::abs(m[14]) > 1e-6 ||
                 std::abs(m[15] - 1.0) > 1e-6))
    refuse(path, "has last row (" + num(m[12]) + ", " + num(m[13]) + ", " + num(m[14]) + ", " + num(m[15]) +
                     "); expected an affine matrix with last row (0, 0, 0, 1)");
  return m;
}

std::array<double, 16> matrix4(py::handle v, const std::string& path, bool affine) {
  const auto a = real_array<Float64Array>(v, path, {4, 4}, false);
  return checked_matrix(a.data(), path, affine);
}

Vec3 transform_point(const std::array<double, 16>& m, double x, double y, double z) {
  auto row = [&](int r) { return static_cast<float>(m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]); };
  return {row(0), row(1), row(2)};
}

// Wraps a builder's ParameterError (which names the parameter and its range) with the path.
template <typename F>
auto with_path(const std::string& path, F&& build) {
  try {
    return build();
  } catch (const std::invalid_argument& e) {
    refuse(path, e.what());
  }
}

Material material_from_python(py::handle v, const std::string& path, render::TextureStore& textures) {
  const py::dict d = as_dict(v, path);
  Material material;
  if (has(d, "graph")) {
    for (auto item : d)
      if (item.first.cast<std::string>() != "graph" && item.first.cast<std::string>() != "name")
        refuse(key_path(path, item.first.cast<std::string>().c_str()),
               "is not allowed next to 'graph' (a graph holds its closures and emission)");
    material.graph = graph_from_python(d["graph"], path, textures);
    return material;
  }
  if (has(d, "model")) {
    const py::object model = d["model"];
    text(model, key_path(path, "model"), "a model name (see bxdf.models())");
    py::dict params;
    if (has(d, "params")) params = as_dict(d["params"], key_path(path, "params"));
    material.components.push_back(with_path(path, [&] { return make_model(model, params).bxdf; }));
  }
  if (has(d, "emission")) material.emission = colour(d["emission"], key_path(path, "emission"));
  if (material.components.empty() && material.emission.r == 0.0f && material.emission.g == 0.0f &&
      material.emission.b == 0.0f)
    refuse(path, "has neither a 'model' nor a non-zero 'emission'; expected {'model': name, 'params': {...}}");
  return material;
}

bool flag(const py::dict& d, const char* key, bool fallback, const std::string& path) {
  if (!has(d, key)) return fallback;
  const py::object v = d[key];
  if (!PyBool_Check(v.ptr()) && !py::isinstance<py::int_>(v))
    refuse(key_path(path, key), short_repr(v) + " is not a bool; expected True or False");
  return v.cast<bool>();
}

// Ray visibility keys of a light dict (Blender: object visible_camera, light cast_shadow and
// Cycles' Multiple Importance).
render::LightVisibility light_visibility(const py::dict& d, const std::string& path) {
  render::LightVisibility vis;
  vis.camera = flag(d, "visible_camera", vis.camera, path);
  vis.cast_shadow = flag(d, "cast_shadow", vis.cast_shadow, path);
  vis.use_mis = flag(d, "use_mis", vis.use_mis, path);
  return vis;
}

// Blender's area light: a rectangle or ellipse in its local XY plane, size (x, y) scaled by the
// matrix, emitting along the light's −Z from the front only.
Light area_light_from_python(const py::dict& d, const std::string& path) {
  const std::string shape = lower(text(required(d, "shape", path, "'square', 'rectangle', 'disk' or 'ellipse'"),
                                       key_path(path, "shape"), "'square', 'rectangle', 'disk' or 'ellipse'"));
  const bool round = shape == "disk" || shape == "ellipse";
  if (!round && shape != "square" && shape != "rectangle")
    refuse(key_path(path, "shape"), "unknown area light shape '" + shape + "'; expected 'square', 'rectangle', 'disk' or 'ellipse'");
  const py::object size_obj = required(d, "size", path, "(size_x, size_y) in metres");
  double sx, sy;
  if (PyNumber_Check(size_obj.ptr()) && !py::isinstance<py::array>(size_obj)) {
    sx = sy = number(size_obj, key_path(path, "size"), 1e-12, kInf, "(0, inf)");
  } else {
    const auto s = numbers(size_obj, key_path(path, "size"), 2);
    for (double x : s)
      if (x <= 0.0) refuse(key_path(path, "size"), "has " + num(x) + "; expected sizes in (0, inf)");
    sx = s[0];
    sy = s[1];
  }
  const auto m = matrix4(required(d, "matrix", path, "the light's 4x4 object-to-world matrix"), key_path(path, "matrix"), true);
  const Vec3 centre = transform_point(m, 0.0, 0.0, 0.0);
  const Vec3 axis_u = transform_point(m, sx, 0.0, 0.0) - centre;
  const Vec3 axis_v = transform_point(m, 0.0, sy, 0.0) - centre;
  const Vec3 normal = centre - transform_point(m, 0.0, 0.0, 1.0);  // −Z
  const double power = number(required(d, "power", path, "the light's power in W"), key_path(path, "power"), 0.0, kInf, "[0, inf) W");
  const RGB color = colour(required(d, "color", path, "an RGB colour"), key_path(path, "color"));
  return with_path(path, [&] {
    return render::area_light_from_power(centre, axis_u, axis_v, normal,
                                         round ? render::AreaShape::Ellipse : render::AreaShape::Rectangle,
                                         static_cast<float>(power), color);
  });
}

Light light_from_python(py::handle v, const std::string& path) {
  const py::dict d = as_dict(v, path);
  const std::string type = lower(text(required(d, "type", path, "'point', 'spot', 'sun' or 'area'"),
                                      key_path(path, "type"), "'point', 'spot', 'sun' or 'area'"));
  Light light = [&]() -> Light {
    if (type == "area") return area_light_from_python(d, path);
    if (type == "point" || type == "spot") {
      const Vec3 position = vec3(required(d, "position", path, "(x, y, z)"), key_path(path, "position"));
      const RGB intensity = colour(required(d, "intensity", path, "an RGB radiant intensity in W/sr"),
                                   key_path(path, "intensity"));
      const float radius =
          has(d, "radius") ? static_cast<float>(number(d["radius"], key_path(path, "radius"), 0.0, kInf, "[0, inf) m")) : 0.0f;
      if (type == "point") return with_path(path, [&] { return render::point_light(position, intensity, radius); });
      const Vec3 direction = vec3(required(d, "direction", path, "the spot axis (x, y, z)"), key_path(path, "direction"));
      const double size = number(required(d, "spot_size", path, "the full cone angle in radians, (0, pi]"),
                                 key_path(path, "spot_size"), 1e-9, M_PI, "(0, pi] radians");
      const double blend =
          number(required(d, "spot_blend", path, "a number in [0, 1]"), key_path(path, "spot_blend"), 0.0, 1.0, "[0, 1]");
      return with_path(path, [&] {
        return render::spot_light(position, direction, intensity, static_cast<float>(size), static_cast<float>(blend), radius);
      });
    }
    if (type == "sun") {
      const Vec3 direction = vec3(required(d, "direction", path, "the direction light travels (x, y, z)"),
                                  key_path(path, "direction"));
      const RGB irradiance = colour(required(d, "irradiance", path, "an RGB irradiance in W/m^2"),
                                    key_path(path, "irradiance"));
      const double angle = has(d, "angle") ? number(d["angle"], key_path(path, "angle"), 0.0, M_PI * 0.999,
                                                    "[0, pi) radians")
                                           : 0.0;
      return with_path(path, [&] { return render::sun_light(direction, irradiance, static_cast<float>(angle)); });
    }
    refuse(key_path(path, "type"), "unknown light type '" + type + "'; expected 'point', 'spot', 'sun' or 'area'");
  }();
  light.visibility = light_visibility(d, path);
  return light;
}

// scene['world']: {"color": RGB, "texture": {"path", "weight" (RGB), "matrix" (3x4 texture
// vector of a direction), "interpolation"}, "sampling": "auto"|"manual"|"none",
// "map_resolution": int} (render/environment.h).
// The world's settings, and its image file ("" for none: a constant world).
struct WorldFromPython {
  render::EnvironmentSettings settings;
  std::string image_path;
};

WorldFromPython world_from_python(const py::dict& w, const std::string& path) {
  WorldFromPython out;
  render::EnvironmentSettings& s = out.settings;
  if (has(w, "color")) s.constant = colour(w["color"], key_path(path, "color"));
  if (has(w, "texture")) {
    const std::string tp = key_path(path, "texture");
    const py::dict t = as_dict(w["texture"], tp);
    const std::string file = text(required(t, "path", tp, "an image path"), key_path(tp, "path"), "an image path");
    s.weight = has(t, "weight") ? colour(t["weight"], key_path(tp, "weight")) : RGB(1.0f);
    if (has(t, "matrix")) {
      const auto m = real_array<Float64Array>(t["matrix"], key_path(tp, "matrix"), {3, 4}, false);
      for (int i = 0; i < 12; ++i) {
        if (!std::isfinite(m.data()[i])) refuse(key_path(tp, "matrix"), "has " + num(m.data()[i]) + "; expected finite numbers");
        s.matrix[i] = static_cast<float>(m.data()[i]);
      }
    }
    if (has(t, "interpolation")) {
      const std::string mode = lower(text(t["interpolation"], key_path(tp, "interpolation"), "'closest' or 'linear'"));
      if (mode == "closest") s.interpolation = render::TextureInterpolation::Closest;
      else if (mode != "linear") refuse(key_path(tp, "interpolation"), "'" + mode + "' is unknown; expected 'closest' or 'linear'");
    }
    out.image_path = file;
  }
  if (has(w, "sampling")) {
    const std::string mode = lower(text(w["sampling"], key_path(path, "sampling"), "'auto', 'manual' or 'none'"));
    if (mode == "none") s.importance_sample = false;
    else if (mode != "auto" && mode != "manual") refuse(key_path(path, "sampling"), "'" + mode + "' is unknown; expected 'auto', 'manual' or 'none'");
  }
  if (has(w, "map_resolution"))
    s.map_resolution = static_cast<int>(integer(w["map_resolution"], key_path(path, "map_resolution"), 0, 65536));
  return out;
}

// One mesh of scene['meshes'], validated, with its arrays kept alive for weld_corners.
struct MeshInput {
  render::MeshVisibility visibility;
  render::TerminatorOffsets terminator;
  Float32Array positions, normals, uvs;
  IndexArray triangles, normal_indices, uv_indices, material_indices;
  std::vector<uint32_t> materials;  // when some triangle takes the default material, else empty
  IndexedMeshArrays arrays;
  MeshGraphAttributes graph_attributes;
};

MeshInput mesh_from_python(py::handle v, const std::string& path, size_t num_materials,
                           const std::function<uint32_t()>& default_material) {
  const py::dict d = as_dict(v, path);
  MeshInput in;
  // The object's ray visibility and Cycles' shadow terminator offsets (geometry, shading).
  in.visibility.camera = flag(d, "visible_camera", true, path);
  in.visibility.shadow = flag(d, "visible_shadow", true, path);
  if (has(d, "terminator_offset")) {
    const auto t = numbers(d["terminator_offset"], key_path(path, "terminator_offset"), 2);
    if (!(t[0] >= 0.0 && t[0] <= 1.0 && t[1] >= 0.0 && t[1] < 1.0))
      refuse(key_path(path, "terminator_offset"), "(" + num(t[0]) + ", " + num(t[1]) +
                                                     ") is out of range; expected (geometry in [0, 1], shading in [0, 1))");
    in.terminator.geometry = static_cast<float>(t[0]);
    in.terminator.shading = static_cast<float>(t[1]);
  }
  in.positions = real_array<Float32Array>(required(d, "positions", path, "a (V, 3) float array"),
                                          key_path(path, "positions"), {-1, 3}, false);
  require_finite(in.positions.data(), static_cast<size_t>(in.positions.size()), 3, key_path(path, "positions"));
  const auto nv = static_cast<long long>(in.positions.shape(0));
  in.triangles = real_array<IndexArray>(required(d, "triangles", path, "a (T, 3) integer array"),
                                        key_path(path, "triangles"), {-1, 3}, true);
  require_indices(in.triangles, 0, nv, key_path(path, "triangles"));
  const py::ssize_t nt = in.triangles.shape(0);

  auto attribute = [&](const char* values_key, const char* index_key, py::ssize_t width, Float32Array& values,
                       IndexArray& indices) {
    const bool has_values = has(d, values_key), has_index = has(d, index_key);
    if (has_values != has_index)
      refuse(key_path(path, has_values ? index_key : values_key),
             std::string("is missing while '") + (has_values ? values_key : index_key) +
                 "' is given; expected both or neither");
    if (!has_values) return false;
    values = real_array<Float32Array>(d[values_key], key_path(path, values_key), {-1, width}, false);
    indices = real_array<IndexArray>(d[index_key], key_path(path, index_key), {nt, 3}, true);
    require_indices(indices, 0, values.shape(0), key_path(path, index_key));
    return true;
  };
  const bool has_normals = attribute("normals", "normal_indices", 3, in.normals, in.normal_indices);
  const bool has_uvs = attribute("uvs", "uv_indices", 2, in.uvs, in.uv_indices);
  if (has_uvs) require_finite(in.uvs.data(), static_cast<size_t>(in.uvs.size()), 2, key_path(path, "uvs"));

  // The caller's indices are used in place (int32 >= 0 reads the same as uint32) unless some
  // triangle has none (-1), which takes the default material in a copy.
  const uint32_t* materials = nullptr;
  if (has(d, "material_indices")) {
    in.material_indices =
        real_array<IndexArray>(d["material_indices"], key_path(path, "material_indices"), {nt}, true);
    require_indices(in.material_indices, -1, static_cast<long long>(num_materials), key_path(path, "material_indices"));
    const int32_t* mi = in.material_indices.data();
    if (std::any_of(mi, mi + nt, [](int32_t m) { return m < 0; })) {
      const uint32_t fallback = default_material();
      in.materials.resize(static_cast<size_t>(nt));
      for (py::ssize_t t = 0; t < nt; ++t) in.materials[t] = mi[t] < 0 ? fallback : static_cast<uint32_t>(mi[t]);
      materials = in.materials.data();
    } else {
      materials = reinterpret_cast<const uint32_t*>(mi);
    }
  } else {
    in.materials.assign(static_cast<size_t>(nt), default_material());
    materials = in.materials.data();
  }

  in.arrays.positions = in.positions.data();
  in.arrays.num_positions = static_cast<size_t>(nv);
  in.arrays.triangles = in.triangles.data();
  in.arrays.num_triangles = static_cast<size_t>(nt);
  if (has_normals) {
    in.arrays.normals = in.normals.data();
    in.arrays.normal_indices = in.normal_indices.data();
  }
  if (has_uvs) {
    in.arrays.uvs = in.uvs.data();
    in.arrays.uv_indices = in.uv_indices.data();
  }
  in.arrays.material_indices = materials;
  in.graph_attributes = mesh_graph_attributes(d, path, static_cast<size_t>(nt));
  return in;
}

render::CameraSettings camera_from_python(py::handle v, const std::string& path) {
  const py::dict d = as_dict(v, path);
  if (d.contains("missing") && py::bool_(d["missing"]))
    refuse(path, "the scene has no camera; expected a camera dict with 'matrix', 'lens', ...");
  render::CameraSettings c;
  if (has(d, "type")) {
    const std::string type = lower(text(d["type"], key_path(path, "type"), "'persp' or 'ortho'"));
    if (type == "ortho" || type == "orthographic")
      c.projection = render::Projection::Orthographic;
    else if (type != "persp" && type != "perspective")
      refuse(key_path(path, "type"), "'" + type + "' is not supported; expected 'persp' or 'ortho' (panoramic cameras are not rendered)");
  }
  if (has(d, "ortho_scale"))
    c.ortho_scale = static_cast<float>(number(d["ortho_scale"], key_path(path, "ortho_scale"), 1e-6, kInf, "(0, inf) scene units"));
  const auto m = matrix4(required(d, "matrix", path, "the camera's 4x4 camera-to-world matrix"), key_path(path, "matrix"), true);
  for (int i = 0; i < 16; ++i) c.camera_to_world[i] = static_cast<float>(m[i]);
  if (has(d, "lens")) c.lens_mm = static_cast<float>(number(d["lens"], key_path(path, "lens"), 1e-6, kInf, "(0, inf) mm"));
  if (has(d, "sensor_width"))
    c.sensor_width_mm = static_cast<float>(number(d["sensor_width"], key_path(path, "sensor_width"), 1e-6, kInf, "(0, inf) mm"));
  if (has(d, "sensor_height"))
    c.sensor_height_mm = static_cast<float>(number(d["sensor_height"], key_path(path, "sensor_height"), 1e-6, kInf, "(0, inf) mm"));
  if (has(d, "sensor_fit")) {
    const std::string fit = lower(text(d["sensor_fit"], key_path(path, "sensor_fit"), "'auto', 'horizontal' or 'vertical'"));
    if (fit == "auto") c.sensor_fit = render::SensorFit::Auto;
    else if (fit == "horizontal") c.sensor_fit = render::SensorFit::Horizontal;
    else if (fit == "vertical") c.sensor_fit = render::SensorFit::Vertical;
    else refuse(key_path(path, "sensor_fit"), "'" + fit + "' is unknown; expected 'auto', 'horizontal' or 'vertical'");
  }
  if (has(d, "shift")) {
    const auto s = numbers(d["shift"], key_path(path, "shift"), 2);
    c.shift_x = static_cast<float>(s[0]);
    c.shift_y = static_cast<float>(s[1]);
  }
  if (has(d, "clip")) {
    const auto s = numbers(d["clip"], key_path(path, "clip"), 2);
    if (!(s[0] >= 0.0 && s[1] > s[0]))
      refuse(key_path(path, "clip"), "(" + num(s[0]) + ", " + num(s[1]) + ") is not a range; expected (start, end) with 0 <= start < end");
    c.clip_start = static_cast<float>(s[0]);
    c.clip_end = static_cast<float>(s[1]);
  }
  // The renderer's own checks (matrix range, axes), reported against this path.
  with_path(path, [&] { return render::Camera(c, 1, 1); });
  return c;
}

}  // namespace

SceneFromPython scene_from_python(const py::handle& scene_obj, double rays_per_pixel) {
  const auto started = std::chrono::steady_clock::now();
  const std::string root = "scene";
  const py::dict d = as_dict(scene_obj, root);
  SceneFromPython out;
  out.scene = std::make_unique<render::Scene>();
  render::Scene& scene = *out.scene;

  const auto res = numbers(required(d, "resolution", root, "(width, height) in pixels"), key_path(root, "resolution"), 2);
  for (double x : res)
    if (x < 1.0 || x > 65536.0 || x != std::floor(x))
      refuse(key_path(root, "resolution"), "has " + num(x) + "; expected two integers in [1, 65536]");
  out.width = static_cast<int>(res[0]);
  out.height = static_cast<int>(res[1]);
  out.camera = camera_from_python(required(d, "camera", root, "a camera dict"), key_path(root, "camera"));

  // Materials: scene['materials'][i] is scene material i; -1 gets a default grey Lambertian
  // (Blender's look for an object without material), added on first use.
  size_t num_materials = 0;
  render::TextureStore textures;  // images shared by the materials' graphs
  if (has(d, "materials")) {
    const std::string path = key_path(root, "materials");
    const py::list materials = as_list(d["materials"], path, "a list of material dicts");
    for (size_t i = 0; i < materials.size(); ++i) {
      const std::string p = item_path(path, i);
      with_path(p, [&] { return scene.add_material(material_from_python(materials[i], p, textures)); });
    }
    num_materials = materials.size();
  }
  int64_t default_material = -1;
  auto get_default_material = [&]() -> uint32_t {
    if (default_material < 0) {
      py::dict params;
      params["reflectance"] = 0.8;
      default_material = scene.add_material(Material{{make_model(py::str("lambertian"), params).bxdf}, RGB(0.0f)});
    }
    return static_cast<uint32_t>(default_material);
  };

  std::vector<MeshInput> meshes;
  if (has(d, "meshes")) {
    const std::string path = key_path(root, "meshes");
    const py::list list = as_list(d["meshes"], path, "a list of mesh dicts");
    meshes.reserve(list.size());
    for (size_t i = 0; i < list.size(); ++i)
      meshes.push_back(mesh_from_python(list[i], item_path(path, i), num_materials, get_default_material));
  }

  // Instances: without them every mesh is drawn once, its positions taken as world space.
  std::vector<int64_t> instance_mesh;
  std::vector<std::array<double, 16>> instance_matrix;
  const bool has_im = has(d, "instance_mesh"), has_ix = has(d, "instance_matrix");
  if (has_im != has_ix)
    refuse(key_path(root, has_im ? "instance_matrix" : "instance_mesh"),
           std::string("is missing while '") + (has_im ? "instance_mesh" : "instance_matrix") +
               "' is given; expected both or neither");
  const bool instanced = has_im;
  if (instanced) {
    const auto im = real_array<IndexArray>(d["instance_mesh"], key_path(root, "instance_mesh"), {-1}, true);
    require_indices(im, 0, static_cast<long long>(meshes.size()), key_path(root, "instance_mesh"));
    const auto ix = real_array<Float64Array>(d["instance_matrix"], key_path(root, "instance_matrix"),
                                             {im.shape(0), 4, 4}, false);
    instance_mesh.assign(im.data(), im.data() + im.size());
    for (py::ssize_t i = 0; i < im.shape(0); ++i) {
      const std::string p = item_path(key_path(root, "instance_matrix"), static_cast<size_t>(i));
      instance_matrix.push_back(checked_matrix(ix.data() + 16 * i, p, true));
      for (double x : instance_matrix.back())  // the renderer's coordinate range (ray.h)
        if (std::abs(x) > render::kMaxSceneCoordinate)
          refuse(p, "has " + num(x) + "; expected entries in [-1e9, 1e9]");
    }
  }

  if (has(d, "world")) {
    const std::string path = key_path(root, "world");
    const py::dict w = as_dict(d["world"], path);
    WorldFromPython world = world_from_python(w, path);
    if (world.image_path.empty()) {
      with_path(path, [&] { scene.set_world(std::move(world.settings)); return 0; });
    } else {
      // Built once for renders of the same file and settings (environment.h).
      std::shared_ptr<const render::Environment> built;
      try {
        built = render::shared_environment(world.image_path, world.settings);
      } catch (const std::invalid_argument& e) {  // the settings (Environment's checks)
        refuse(path, e.what());
      } catch (const std::exception& e) {  // the file
        refuse(key_path(key_path(path, "texture"), "path"), e.what());
      }
      scene.set_world(std::move(built));
    }
  }

  if (has(d, "lights")) {
    const std::string path = key_path(root, "lights");
    const py::list lights = as_list(d["lights"], path, "a list of light dicts");
    for (size_t i = 0; i < lights.size(); ++i) scene.add_light(light_from_python(lights[i], item_path(path, i)));
  }

  // The heavy part (welding, transforming, copying, the BVH) needs no Python.
  {
    py::gil_scoped_release release;
    // One mesh at a time: welded, then handed over to the scene (moved, not copied), so that at
    // most one welded mesh exists besides the scene's.
    auto weld = [&](size_t i) {
      Mesh w = weld_corners(meshes[i].arrays);
      apply_graph_attributes(meshes[i].graph_attributes, w);
      w.visibility = meshes[i].visibility;
      w.terminator = meshes[i].terminator;
      return w;
    };
    auto add = [&](Mesh&& mesh, const std::string& what, bool as_instanced) -> int64_t {
      if (mesh.num_triangles() == 0) return -1;
      try {
        return static_cast<int64_t>(as_instanced ? scene.add_instanced_mesh(std::move(mesh))
                                                 : scene.add_mesh(std::move(mesh)));
      } catch (const std::invalid_argument& e) {
        refuse(what, e.what());
      }
    };
    if (instanced) {
      // A mesh placed more than once is stored once and drawn through Embree instances; one
      // placed once (or by a singular matrix, which has no object space) is moved into world
      // space, as Cycles applies the transform of an object whose geometry is not shared.
      auto invertible = [](const std::array<double, 16>& m) {
        const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                           m[2] * (m[4] * m[9] - m[5] * m[8]);
        return std::abs(det) > 1e-30;
      };
      std::vector<size_t> placements(meshes.size(), 0), flattened_uses(meshes.size(), 0);
      for (size_t i = 0; i < instance_mesh.size(); ++i)
        if (invertible(instance_matrix[i])) ++placements[static_cast<size_t>(instance_mesh[i])];
      std::vector<int64_t> scene_mesh(meshes.size(), -1);
      for (size_t m = 0; m < meshes.size(); ++m)
        if (placements[m] > 1 && meshes[m].arrays.num_triangles > 0)
          scene_mesh[m] = add(weld(m), item_path(key_path(root, "meshes"), m), true);
      for (size_t i = 0; i < instance_mesh.size(); ++i) {
        const size_t m = static_cast<size_t>(instance_mesh[i]);
        if (scene_mesh[m] < 0 || !invertible(instance_matrix[i])) ++flattened_uses[m];
      }
      // Welded meshes moved into world space more than once are kept until their last use.
      std::vector<Mesh> kept(meshes.size());
      for (size_t i = 0; i < instance_mesh.size(); ++i) {
        const size_t m = static_cast<size_t>(instance_mesh[i]);
        if (meshes[m].arrays.num_triangles == 0) continue;
        if (scene_mesh[m] < 0 || !invertible(instance_matrix[i])) {
          const std::string what = item_path(key_path(root, "instance_mesh"), i);
          if (flattened_uses[m] == 1) {
            add(transformed(weld(m), instance_matrix[i]), what, false);
          } else {
            if (kept[m].num_triangles() == 0) kept[m] = weld(m);
            const bool last_use = --flattened_uses[m] == 0;  // then moved in, not copied
            add(transformed(last_use ? std::move(kept[m]) : Mesh(kept[m]), instance_matrix[i]), what,
                false);
            if (last_use) kept[m] = Mesh();
          }
          continue;
        }
        float rows[12];
        for (int k = 0; k < 12; ++k) rows[k] = static_cast<float>(instance_matrix[i][static_cast<size_t>(k)]);
        try {
          scene.add_instance(static_cast<uint32_t>(scene_mesh[m]), rows);
        } catch (const std::invalid_argument& e) {
          refuse(item_path(key_path(root, "instance_matrix"), i), e.what());
        }
      }
    } else {
      for (size_t i = 0; i < meshes.size(); ++i)
        if (meshes[i].arrays.num_triangles > 0) add(weld(i), item_path(key_path(root, "meshes"), i), false);
    }
    const auto converted = std::chrono::steady_clock::now();
    scene.commit(rays_per_pixel * double(out.width) * double(out.height));
    out.convert_seconds = std::chrono::duration<double>(converted - started).count();
    out.bvh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - converted).count();
  }
  return out;
}

void apply_render_settings(const py::handle& settings, render::RenderSettings& s) {
  if (settings.is_none()) return;
  const std::string root = "settings";
  const py::dict d = as_dict(settings, root);
  static const char* const kKnown =
      "'samples', 'max_bounces', 'pixel_filter', 'filter_width', 'threads', 'seed', 'tile_size', "
      "'samples_per_pass', 'progressive', 'russian_roulette_depth', 'transparent_max_bounces', "
      "'transparent_background', 'region', 'adaptive_sampling', 'adaptive_threshold', "
      "'adaptive_min_samples'";
  for (const auto& item : d) {
    const std::string key = py::str(item.first).cast<std::string>();
    const std::string path = root + "['" + key + "']";
    const py::handle v = item.second;
    if (key == "samples") s.samples_per_pixel = static_cast<int>(integer(v, path, 1, 1 << 24));
    else if (key == "max_bounces") s.max_bounces = static_cast<int>(integer(v, path, 0, 1 << 16));
    else if (key == "transparent_max_bounces") s.transparent_max_bounces = static_cast<int>(integer(v, path, 0, 1024));
    else if (key == "russian_roulette_depth") s.russian_roulette_depth = static_cast<int>(integer(v, path, 0, 1 << 16));
    else if (key == "threads") s.threads = static_cast<int>(integer(v, path, 0, 1 << 16));
    else if (key == "seed") s.seed = static_cast<uint64_t>(integer(v, path, 0, std::numeric_limits<long long>::max()));
    else if (key == "tile_size") s.tile_size = static_cast<int>(integer(v, path, 1, 4096));
    else if (key == "samples_per_pass") s.samples_per_pass = static_cast<int>(integer(v, path, 0, 1 << 24));
    else if (key == "filter_width") s.filter_width = static_cast<float>(number(v, path, 1e-6, 16.0, "(0, 16] pixels"));
    else if (key == "adaptive_threshold") s.adaptive_threshold = static_cast<float>(number(v, path, 0.0, 1.0, "[0, 1] (0 = automatic)"));
    else if (key == "adaptive_min_samples") s.adaptive_min_samples = static_cast<int>(integer(v, path, 0, 4096));
    else if (key == "transparent_background" || key == "progressive" || key == "adaptive_sampling") {
      if (!PyBool_Check(v.ptr())) refuse(path, short_repr(v) + " is not a bool; expected True or False");
      (key == "progressive" ? s.progressive
       : key == "adaptive_sampling" ? s.adaptive_sampling : s.transparent_background) = v.cast<bool>();
    } else if (key == "region") {
      // Checked against the image's size where the render starts (render::rendered_rect).
      if (v.is_none()) {
        s.region = render::PixelRect{};
        continue;
      }
      const char* kShape = "; expected None or (x_min, y_min, x_max, y_max), 4 integers";
      if (!py::isinstance<py::sequence>(v) || py::isinstance<py::str>(v) || py::len(v) != 4)
        refuse(path, short_repr(v) + " is not 4 integers" + std::string(kShape));
      const py::sequence seq = py::reinterpret_borrow<py::sequence>(v);
      int c[4];
      for (int i = 0; i < 4; ++i)
        c[i] = static_cast<int>(integer(seq[size_t(i)], path + "[" + std::to_string(i) + "]", 0, 65536));
      s.region = render::PixelRect{c[0], c[1], c[2], c[3]};
    } else if (key == "pixel_filter") {
      const std::string name = lower(text(v, path, render::kFilterNames));
      try {
        s.filter = render::parse_filter(name);
      } catch (const ParameterError&) {
        refuse(path, "'" + name + "' is unknown; expected " + render::kFilterNames);
      }
    } else {
      refuse(path, "is not a setting; expected one of " + std::string(kKnown));
    }
  }
}

}  // namespace bxdf::python

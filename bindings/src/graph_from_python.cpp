#include "graph_from_python.h"

#include <pybind11/eval.h>
#include <pybind11/numpy.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "bxdf/params.h"
#include "bxdf/render/material_graph_json.h"

namespace bxdf::python {

namespace {

using Float32Array = py::array_t<float, py::array::c_style | py::array::forcecast>;

// "graph.nodes[4].vector" → "['graph']['nodes'][4]['vector']".
std::string python_path(const std::string& dotted) {
  std::string out;
  size_t start = 0;
  while (start <= dotted.size()) {
    size_t end = dotted.find('.', start);
    if (end == std::string::npos) end = dotted.size();
    const std::string token = dotted.substr(start, end - start);
    const size_t bracket = token.find('[');
    out += "['" + token.substr(0, bracket) + "']";
    if (bracket != std::string::npos) out += token.substr(bracket);
    start = end + 1;
  }
  return out;
}

std::vector<float> float_rows(py::handle v, const std::string& path, size_t rows, size_t width) {
  Float32Array a;
  try {
    a = py::cast<Float32Array>(v);
  } catch (const py::cast_error&) {
    throw ParameterError(path + ": expected a (" + std::to_string(rows) + ", " + std::to_string(width) +
                         ") float array");
  }
  if (a.ndim() != 2 || size_t(a.shape(0)) != rows || size_t(a.shape(1)) != width)
    throw ParameterError(path + ": expected shape (" + std::to_string(rows) + ", " +
                         std::to_string(width) + ") (one row per triangle corner)");
  std::vector<float> out(a.data(), a.data() + rows * width);
  for (size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      throw ParameterError(path + "[" + std::to_string(i / width) + "]: is not finite");
  return out;
}

}  // namespace

std::shared_ptr<const render::MaterialGraph> graph_from_python(py::handle graph,
                                                               const std::string& path,
                                                               render::TextureStore& textures) {
  nlohmann::json j;
  try {
    // numpy arrays and scalars become lists and numbers; anything else is refused by json.
    const py::object to_plain = py::eval("lambda o: o.tolist() if hasattr(o, 'tolist') else None");
    const std::string text = py::module_::import("json")
                                 .attr("dumps")(graph, py::arg("default") = to_plain)
                                 .cast<std::string>();
    j = nlohmann::json::parse(text);
  } catch (const py::error_already_set& e) {
    throw ParameterError(path + "['graph']: is not plain data (dicts, lists, numbers, strings): " +
                         std::string(e.what()));
  }
  try {
    return render::read_material_graph(j, "graph", "", textures);
  } catch (const render::GraphFieldError& e) {
    // A ValueError that already names the full path (not re-prefixed by the caller's wrapper).
    throw py::value_error(path + python_path(e.field) + ": " + e.problem);
  }
}

MeshGraphAttributes mesh_graph_attributes(const py::dict& d, const std::string& path,
                                          size_t num_triangles) {
  MeshGraphAttributes out;
  const size_t corners = 3 * num_triangles;
  auto list = [&](const char* key) {
    if (!d.contains(key) || d[key].is_none()) return py::list();
    if (!py::isinstance<py::list>(d[key]) && !py::isinstance<py::tuple>(d[key]))
      throw ParameterError(path + "['" + key + "']: expected a list of arrays (one per UV map)");
    return py::list(d[key]);
  };
  const py::list maps = list("uv_maps");
  for (size_t k = 0; k < maps.size(); ++k)
    out.uv_maps.push_back(float_rows(maps[k], path + "['uv_maps'][" + std::to_string(k) + "]", corners, 2));
  const py::list tangents = list("tangents");
  if (tangents.size() > maps.size())
    throw ParameterError(path + "['tangents']: has " + std::to_string(tangents.size()) +
                         " entries; expected at most one per UV map (" + std::to_string(maps.size()) + ")");
  for (size_t k = 0; k < maps.size(); ++k) {
    if (k < tangents.size() && !tangents[k].is_none())
      out.tangents.push_back(
          float_rows(tangents[k], path + "['tangents'][" + std::to_string(k) + "]", corners, 4));
    else
      out.tangents.emplace_back();
  }
  if (d.contains("texture_space") && !d["texture_space"].is_none())
    out.texture_space = float_rows(d["texture_space"], path + "['texture_space']", 2, 3);
  return out;
}

void apply_graph_attributes(const MeshGraphAttributes& a, render::Mesh& mesh) {
  mesh.uv_maps = a.uv_maps;
  mesh.tangents = a.tangents;
  mesh.texture_space = a.texture_space;
}

}  // namespace bxdf::python

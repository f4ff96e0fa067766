// Material graphs and the mesh attributes they read, from bxdf.render's scene dict: the graph
// dict goes through the one JSON graph reader (so Python, scene files and material files accept
// exactly the same graphs), and errors name the Python path, e.g.
// "scene['materials'][2]['graph']['nodes'][4]['vector']: node 7 is not earlier than 4".
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "bxdf/render/material_graph.h"
#include "bxdf/render/mesh.h"
#include "bxdf/render/texture.h"

namespace bxdf::python {

namespace py = pybind11;

std::shared_ptr<const render::MaterialGraph> graph_from_python(py::handle graph,
                                                               const std::string& path,
                                                               render::TextureStore& textures);

// A mesh dict's per-corner 'uv_maps' ((3T, 2) arrays), 'tangents' ((3T, 4) arrays or None, per
// UV map) and 'texture_space' (location, size), copied; applied to the welded mesh (whose
// triangles keep their order).
struct MeshGraphAttributes {
  std::vector<std::vector<float>> uv_maps, tangents;
  std::vector<float> texture_space;
};
MeshGraphAttributes mesh_graph_attributes(const py::dict& mesh, const std::string& path,
                                          size_t num_triangles);
void apply_graph_attributes(const MeshGraphAttributes& attributes, render::Mesh& mesh);

}  // namespace bxdf::python

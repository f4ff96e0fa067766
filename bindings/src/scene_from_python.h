// The renderer's inputs from plain Python data: the scene dict of the Blender add-on's
// export.export_scene() (see bxdf.render's docstring for the layout) and the settings dict.
// Every refusal is a ParameterError (ValueError) that starts with the field's path, e.g.
// "scene['meshes'][2]['normal_indices']: index 9 out of range [0, 8)".
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "bxdf/render/camera.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene.h"

namespace bxdf::python {

namespace py = pybind11;

struct SceneFromPython {
  std::unique_ptr<render::Scene> scene;  // committed
  render::CameraSettings camera;
  int width = 0, height = 0;
  std::vector<std::string> warnings;  // things rendered approximately (e.g. a point light's radius)
  double convert_seconds = 0.0;  // reading, welding and flattening the meshes
  double bvh_seconds = 0.0;      // Scene::commit (Embree's BVH)
};

// Builds and commits the scene (the BVH is built with the GIL released). `rays_per_pixel`:
// about how many rays a pixel will trace (samples x (1 + max bounces)), for the BVH's build
// quality (Scene::commit); 0 if not known.
SceneFromPython scene_from_python(const py::handle& scene, double rays_per_pixel = 0.0);

// Applies the keys of `settings` (a dict or None) to `out`; unknown keys and bad values are
// refused naming "settings['key']".
void apply_render_settings(const py::handle& settings, render::RenderSettings& out);

}  // namespace bxdf::python

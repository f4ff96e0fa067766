// The parts of the `bxdf` extension module; module.cpp calls each in turn. One file per idea.
#pragma once

#include <pybind11/pybind11.h>

namespace bxdf::python {

void bind_models(pybind11::module_& m);     // models(), make(), the Model class (model.cpp)
void bind_fresnel(pybind11::module_& m);    // fresnel_* and the F0 inversions (fresnel.cpp)
void bind_bake(pybind11::module_& m);       // lobe images, albedo curves, lobe meshes (bake.cpp)
void bind_presets(pybind11::module_& m);    // presets(), make_preset() (presets.cpp)
void bind_material(pybind11::module_& m);   // save_material(), load_material() (material.cpp)
void bind_measured(pybind11::module_& m);   // load_measured() (measured.cpp)
void bind_fit(pybind11::module_& m);        // fit(), fit_error() (fit.cpp)
void bind_reference(pybind11::module_& m);
void bind_render(pybind11::module_& m);     // render(), render_scene_file() (render.cpp; with plugin/)  // scalar-path hooks the tests compare with (reference.cpp)

}  // namespace bxdf::python

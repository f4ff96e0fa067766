// The compiled half of the Python package `bxdf` (imported as bxdf._bxdf; bxdf/__init__.py
// re-exports the public names).
#include <pybind11/pybind11.h>

#include "binding_modules.h"
#include "bxdf/params.h"

namespace py = pybind11;

PYBIND11_MODULE(_bxdf, m) {
  m.doc() =
      "BxDF Lab reflection models (C++ core) for Python: numpy arrays in, numpy float32 arrays "
      "out.\n\nDirections live in the local shading frame (z = surface normal); wo and wi both "
      "point away from the surface.";

  // ParameterError derives from std::invalid_argument, which pybind11 already maps to
  // ValueError; registering it explicitly keeps that true if the base class ever changes.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const bxdf::ParameterError& e) {
      // Messages are UTF-8 (readers escape what is not); should a byte slip through, it shows
      // as \xNN rather than turning the message into ''.
      const std::string message = e.what();
      py::object text = py::reinterpret_steal<py::object>(PyUnicode_DecodeUTF8(
          message.data(), static_cast<Py_ssize_t>(message.size()), "backslashreplace"));
      if (text) PyErr_SetObject(PyExc_ValueError, text.ptr());
      else PyErr_SetString(PyExc_ValueError, "invalid parameter (message not decodable)");
    }
  });

  // Every docstring starts with its own Python signature; pybind11's would show C++ types.
  py::options options;
  options.disable_function_signatures();

  bxdf::python::bind_models(m);
  bxdf::python::bind_fresnel(m);
  bxdf::python::bind_bake(m);
  bxdf::python::bind_presets(m);
  bxdf::python::bind_material(m);
  bxdf::python::bind_measured(m);
  bxdf::python::bind_fit(m);
  bxdf::python::bind_reference(m);
#ifdef BXDF_HAVE_RENDER
  bxdf::python::bind_render(m);
#endif
}

// bxdf.save_material() / load_material(): the JSON material files of plugin/io, the same
// reader and writer the renderer's scene files use (format "bxdf-material", with a version).
#include <pybind11/pybind11.h>

#include "array_args.h"
#include "binding_modules.h"
#include "bxdf/io/material_json.h"
#include "model.h"

namespace bxdf::python {

void bind_material(py::module_& m) {
  m.def(
      "save_material",
      [](const Model& model, py::handle path, const std::string& name) {
        const std::string p = path_argument(path);
        py::gil_scoped_release nogil;
        io::save_material(*model, p, name);
      },
      py::arg("model"), py::arg("path"), py::arg("name") = "",
      R"doc(save_material(model, path, name="") -> None

Writes `model` to the JSON material file `path` (str or os.PathLike), atomically (a failed
write leaves any existing file untouched):

    {"format": "bxdf-material", "version": 1, "name": "...", "model": "lambertian",
     "params": {"reflectance": [0.8, 0.8, 0.8]}}

Every parameter is written (RGB as [r, g, b], lists of records as lists of objects). `name` is
free text, omitted when empty. Raises ValueError if the file cannot be written.)doc");

  m.def(
      "load_material",
      [](py::handle path) {
        const std::string p = path_argument(path);
        BxDFPtr model;
        {
          py::gil_scoped_release nogil;
          model = io::load_material(p);
        }
        // (load_material names the file in every error, including a measured model's data file.)
        return Model{std::move(model)};
      },
      py::arg("path"),
      R"doc(load_material(path) -> Model

Reads a JSON material file (see :func:`save_material`): a "model" with "params" (missing
parameters take their defaults), or a "preset" name with optional "params" overriding it.
"format" must be "bxdf-material" and "version" at most the one this module writes, when given.
Raises ValueError naming the file, the field and what was expected, for an unreadable file,
invalid JSON, unknown fields, models or presets, and bad parameter values.)doc");
}

}  // namespace bxdf::python

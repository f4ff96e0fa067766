// bxdf.load_measured(): a measured BRDF file (MERL .binary, Cornell .brdf) as a model, through
// the registry's `measured` model like any other.
#include <pybind11/pybind11.h>

#include "array_args.h"
#include "binding_modules.h"
#include "bxdf/measured/measured_data.h"
#include "model.h"

namespace bxdf::python {

void bind_measured(py::module_& m) {
  m.def(
      "load_measured",
      [](py::handle path, const py::kwargs& params) {
        const std::string file = path_argument(path);
        {
          // The file is read here, without the GIL, so other Python threads run meanwhile;
          // make_model below finds it in the cache.
          py::gil_scoped_release nogil;
          load_measured_data(file);
        }
        py::dict all = params;  // `path` cannot be among them: Python binds it to the argument
        all["path"] = py::str(file);
        return make_model(py::str("measured"), all);
      },
      py::arg("path"),
      R"doc(load_measured(path, **params) -> Model

The measured BRDF in the file `path` (str or os.PathLike): a MERL ``.binary`` or a Cornell
``.brdf`` file, chosen by extension or content. This is ``bxdf.make("measured", path=path,
**params)``; the other parameters (e.g. ``interpolate``) are listed by
``bxdf.models()["measured"]``. Files are read once and cached by path, time and size.
Raises ValueError naming the file and the problem for a missing or malformed file.)doc");
}

}  // namespace bxdf::python

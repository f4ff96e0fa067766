// bxdf.presets() and bxdf.make_preset(): the core's named materials (core/.../presets.h).
#include <pybind11/pybind11.h>

#include "array_args.h"
#include "binding_modules.h"
#include "bxdf/presets.h"
#include "model.h"
#include "params_conversion.h"

namespace bxdf::python {

void bind_presets(py::module_& m) {
  m.def(
      "presets",
      []() {
        py::dict out;
        for (const auto& p : presets()) {
          py::dict d;
          d["model"] = p.model;
          d["doc"] = p.doc;
          d["params"] = params_to_python(p.params);
          out[py::str(p.name)] = d;
        }
        return out;
      },
      R"doc(presets() -> dict[str, dict]

The named materials of the core, in order: ``{name: {"model": str, "doc": str, "params": dict}}``.
``bxdf.make(p["model"], **p["params"])`` builds the same model as ``make_preset(name)``; the
params may leave some parameters out (they take the model's defaults). The seed's conductors
(gold, silver, copper, steel) and Lafortune fits of measured materials (clay, felt, ...).)doc");

  m.def(
      "make_preset",
      [](const py::object& name) {
        if (!py::isinstance<py::str>(name))
          refuse_argument("name", name, "is not a preset name (a str); see bxdf.presets()");
        return Model{make_preset(name.cast<std::string>())};
      },
      py::arg("name"),
      R"doc(make_preset(name) -> Model

The named material `name` (a key of :func:`presets`) as a model. ValueError for an unknown
name (the message lists the known ones).)doc");
}

}  // namespace bxdf::python

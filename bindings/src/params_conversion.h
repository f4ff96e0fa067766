// Parameters between Python and the core: keyword arguments → ParamSet (guided by the model's
// ParamSpecs, so that a malformed value is refused with the parameter's valid range), and
// ParamSet / ParamSpec → plain Python dicts, lists, tuples and numbers.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "bxdf/params.h"

namespace bxdf::python {

namespace py = pybind11;

// Converts `given` (name → Python value) for the model `model` with declarations `specs`.
// Python numbers become numbers, 3-sequences RGB triples, str strings, bool bools, and lists of
// dicts lists of records. Unknown names are passed on for validate_params to refuse by name.
ParamSet params_from_python(const std::string& model, const std::vector<ParamSpec>& specs,
                            const py::dict& given);

// Number → float, RGB → (r, g, b) tuple of floats, string → str, bool → bool,
// list → list of dicts. Round-trips through params_from_python unchanged.
py::object value_to_python(const Value& v);
py::dict params_to_python(const ParamSet& params);

// {name, kind, default, min, max, min_exclusive, max_exclusive, unit, doc} plus, where they
// apply, choices (enum), fields (list) and when ({"param", "values"}).
py::dict spec_to_python(const ParamSpec& spec);

}  // namespace bxdf::python

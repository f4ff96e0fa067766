#include "params_conversion.h"

#include <pybind11/stl.h>

#include <cmath>

namespace bxdf::python {

namespace {

std::string short_repr(py::handle value) {
  std::string s = py::repr(value).cast<std::string>();
  if (s.size() > 120) s = s.substr(0, 117) + "...";
  return s;
}

[[noreturn]] void refuse(const std::string& where, const ParamSpec& spec, py::handle value,
                         const std::string& why) {
  throw ParameterError(where + ": parameter '" + spec.name + "' = " + short_repr(value) + " " +
                       why + "; valid: " + spec.range_string());
}

// Python real numbers: int, float and numpy's integer and float scalars (or 0-d arrays);
// never bool (a bool where a number is expected is a mistake) and never str.
bool is_real_number(py::handle obj) {
  if (py::isinstance<py::bool_>(obj)) return false;
  if (py::isinstance<py::float_>(obj) || py::isinstance<py::int_>(obj)) return true;
  if (py::hasattr(obj, "dtype") && py::hasattr(obj, "ndim")) {
    const char kind = obj.attr("dtype").attr("kind").cast<std::string>()[0];
    return obj.attr("ndim").cast<int>() == 0 && (kind == 'f' || kind == 'i' || kind == 'u');
  }
  return false;
}

bool is_bool(py::handle obj) {
  if (py::isinstance<py::bool_>(obj)) return true;
  return py::hasattr(obj, "dtype") && py::hasattr(obj, "ndim") &&
         obj.attr("ndim").cast<int>() == 0 &&
         obj.attr("dtype").attr("kind").cast<std::string>() == "b";
}

double finite_real(const std::string& where, const ParamSpec& spec, py::handle obj) {
  double v;
  try {
    v = py::float_(py::reinterpret_borrow<py::object>(obj)).cast<double>();
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_OverflowError)) throw;
    refuse(where, spec, obj, "is too large for a float");  // e.g. 10**400
  }
  // The core refuses NaN and out-of-range values; Inf would pass an unbounded range, and no
  // parameter of any model means anything at infinity.
  if (std::isinf(v)) refuse(where, spec, obj, "is not finite");
  return v;
}

// A list, tuple or array with a length (but not a string, a mapping or a 0-d array).
bool is_sequence(py::handle obj) {
  if (py::isinstance<py::str>(obj) || py::isinstance<py::dict>(obj) ||
      PySequence_Check(obj.ptr()) == 0)
    return false;
  if (PySequence_Size(obj.ptr()) < 0) {  // e.g. a 0-d numpy array: "len() of unsized object"
    if (!PyErr_ExceptionMatches(PyExc_TypeError)) throw py::error_already_set();
    PyErr_Clear();
    return false;
  }
  return true;
}

Value value_from_python(const std::string& where, const ParamSpec& spec, py::handle obj) {
  switch (spec.kind) {
    case ParamKind::Float:
      if (!is_real_number(obj)) refuse(where, spec, obj, "is not a number");
      return Value(finite_real(where, spec, obj));
    case ParamKind::RGB: {
      if (is_real_number(obj)) return Value(finite_real(where, spec, obj));  // grey
      if (!is_sequence(obj)) refuse(where, spec, obj, "is not an RGB triple or a number");
      py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
      if (seq.size() != 3) refuse(where, spec, obj, "is not an RGB triple or a number");
      RGBValue c;
      for (size_t i = 0; i < 3; ++i) {
        py::object x = seq[i];
        if (!is_real_number(x)) refuse(where, spec, obj, "is not an RGB triple of numbers");
        c[i] = finite_real(where, spec, x);
      }
      return Value(c);
    }
    case ParamKind::Enum:
    case ParamKind::String:
      if (!py::isinstance<py::str>(obj)) refuse(where, spec, obj, "is not a string");
      return Value(obj.cast<std::string>());
    case ParamKind::Bool:
      if (is_bool(obj)) return Value(obj.cast<bool>());
      if (is_real_number(obj)) return Value(finite_real(where, spec, obj));  // 0 / 1
      refuse(where, spec, obj, "is not a boolean");
    case ParamKind::List: {
      if (!is_sequence(obj)) refuse(where, spec, obj, "is not a list of dicts");
      std::vector<ParamSet> items;
      py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
      for (size_t i = 0; i < seq.size(); ++i) {
        py::object item = seq[i];
        const std::string item_where = where + " " + spec.name + "[" + std::to_string(i) + "]";
        if (!py::isinstance<py::dict>(item))
          throw ParameterError(item_where + " = " + short_repr(item) +
                               " is not a dict; valid: " + spec.range_string());
        items.push_back(params_from_python(item_where, spec.fields,
                                           py::reinterpret_borrow<py::dict>(item)));
      }
      return Value(std::move(items));
    }
  }
  return Value();
}

}  // namespace

ParamSet params_from_python(const std::string& model, const std::vector<ParamSpec>& specs,
                            const py::dict& given) {
  ParamSet out;
  for (const auto& [key, value] : given) {
    if (!py::isinstance<py::str>(key))
      throw ParameterError(model + ": parameter name " + short_repr(key) + " is not a string");
    const std::string name = key.cast<std::string>();
    const ParamSpec* spec = nullptr;
    for (const auto& s : specs)
      if (s.name == name) spec = &s;
    // An unknown name: validate_params refuses it (listing the known ones) before it looks at
    // any value, so a placeholder value is enough.
    out.set(name, spec ? value_from_python(model, *spec, value) : Value());
  }
  return out;
}

py::object value_to_python(const Value& v) {
  switch (v.type()) {
    case Value::Type::Number: return py::float_(v.as_number());
    case Value::Type::RGB: {
      const auto& c = v.as_rgb();
      return py::make_tuple(c[0], c[1], c[2]);
    }
    case Value::Type::String: return py::str(v.as_string());
    case Value::Type::Bool: return py::bool_(v.as_bool());
    case Value::Type::List: {
      py::list l;
      for (const auto& item : v.as_list()) l.append(params_to_python(item));
      return std::move(l);
    }
  }
  return py::none();
}

py::dict params_to_python(const ParamSet& params) {
  py::dict d;
  for (size_t i = 0; i < params.size(); ++i)
    d[py::str(params.names()[i])] = value_to_python(params.values()[i]);
  return d;
}

py::dict spec_to_python(const ParamSpec& spec) {
  py::dict d;
  d["name"] = spec.name;
  d["kind"] = to_string(spec.kind);
  d["default"] = value_to_python(spec.default_value);
  const bool ranged = spec.kind == ParamKind::Float || spec.kind == ParamKind::RGB;
  d["min"] = ranged ? py::object(py::float_(spec.min)) : py::object(py::none());
  d["max"] = ranged ? py::object(py::float_(spec.max)) : py::object(py::none());
  d["min_exclusive"] = spec.min_exclusive;
  d["max_exclusive"] = spec.max_exclusive;
  d["unit"] = spec.unit;
  d["doc"] = spec.doc;
  if (spec.kind == ParamKind::RGB) d["subtype"] = to_string(spec.subtype);
  if (spec.kind == ParamKind::Enum) d["choices"] = py::cast(spec.choices);
  if (spec.kind == ParamKind::List) {
    py::list fields;
    for (const auto& f : spec.fields) fields.append(spec_to_python(f));
    d["fields"] = fields;
  }
  if (!spec.when_param.empty()) {
    py::dict when;
    when["param"] = spec.when_param;
    when["values"] = py::cast(spec.when_values);
    d["when"] = when;
  }
  return d;
}

}  // namespace bxdf::python

#include "array_args.h"

#include <cmath>
#include <limits>

#include "bxdf/params.h"

namespace bxdf::python {

namespace {

std::string short_repr(py::handle value) {
  std::string s = py::repr(value).cast<std::string>();
  if (s.size() > 120) s = s.substr(0, 117) + "...";
  return s;
}

std::string shape_string(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

bool is_conversion_error(const py::error_already_set& e) {
  return e.matches(PyExc_TypeError) || e.matches(PyExc_ValueError) ||
         e.matches(PyExc_OverflowError) || e.matches(PyExc_IndexError);
}

py::array as_numpy_array(py::handle obj, const std::string& name) {
  // Leaked on purpose: a static py::object would be released after the interpreter is gone.
  static const py::object& is_masked =
      *new py::object(py::module_::import("numpy.ma").attr("isMaskedArray"));
  if (is_masked(obj).cast<bool>())
    refuse_argument(name, obj,
                    "is a numpy masked array; its mask would be ignored. Pass "
                    "array.filled(value) or array.compressed() instead");
  try {
    return py::module_::import("numpy").attr("asarray")(obj);
  } catch (py::error_already_set& e) {
    if (!is_conversion_error(e)) throw;
    refuse_argument(name, obj, "is not an array of real numbers");
  }
}

std::string path_argument(py::handle path, const std::string& name) {
  if (!py::isinstance<py::str>(path) && !py::hasattr(path, "__fspath__"))
    refuse_argument(name, path, "is not a path (a str or os.PathLike)");
  py::object p = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(p)) refuse_argument(name, path, "is not a text path");
  const std::string s = p.cast<std::string>();
  if (s.empty()) refuse_argument(name, path, "is empty");
  if (s.find('\0') != std::string::npos) refuse_argument(name, path, "contains a NUL character");
  return s;
}

void refuse_argument(const std::string& name, py::handle value, const std::string& why) {
  throw ParameterError("argument '" + name + "' = " + short_repr(value) + " " + why);
}

void refuse_argument(const std::string& name, double value, const std::string& why) {
  refuse_argument(name, py::float_(value), why);
}

FloatArray real_array(py::handle obj, const std::string& name) {
  if (obj.is_none()) refuse_argument(name, obj, "is missing; expected an array of real numbers");
  py::array arr = as_numpy_array(obj, name);
  // Only real numbers convert: a silent cast of complex, bool, string or object arrays would
  // hide the caller's mistake.
  const char kind = arr.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    refuse_argument(name, obj,
                    "has dtype " + py::str(arr.dtype()).cast<std::string>() +
                        "; expected real numbers (a float or integer dtype)");
  return FloatArray::ensure(arr);
}

VectorRows vector_rows(py::handle obj, const std::string& name, size_t width) {
  VectorRows v;
  v.array = real_array(obj, name);
  v.width = width;
  const auto& a = v.array;
  const std::string expected = "; expected shape (N, " + std::to_string(width) + ") or (" +
                               std::to_string(width) + ",)";
  if (a.ndim() == 1 && static_cast<size_t>(a.shape(0)) == width) {
    v.rows = 1;
    v.single = true;
  } else if (a.ndim() == 2 && static_cast<size_t>(a.shape(1)) == width) {
    v.rows = static_cast<size_t>(a.shape(0));
  } else {
    throw ParameterError("argument '" + name + "' has shape " + shape_string(a) + expected);
  }
  v.data = a.data();
  return v;
}

size_t broadcast_rows(std::initializer_list<NamedRows> args) {
  size_t n = 1;
  const char* n_from = nullptr;
  for (const auto& a : args) {
    if (a.rows->rows == 1) continue;
    if (n_from && a.rows->rows != n)
      throw ParameterError("arguments '" + std::string(n_from) + "' and '" + a.name +
                           "' have different numbers of rows (" + std::to_string(n) + " and " +
                           std::to_string(a.rows->rows) +
                           "); give the same N, or a single vector that applies to every row");
    n = a.rows->rows;
    n_from = a.name;
  }
  // All single (or an explicit (1, w)) → one row; any empty batch → zero rows.
  for (const auto& a : args)
    if (a.rows->rows == 0) return 0;
  return n;
}

void require_in_range(const FloatArray& a, const std::string& name, float lo, float hi,
                      const std::string& range_text) {
  const float* d = a.data();
  const size_t n = static_cast<size_t>(a.size());
  for (size_t i = 0; i < n; ++i) {
    if (!(d[i] >= lo && d[i] <= hi)) {  // NaN fails both
      const std::string why = std::isfinite(d[i]) ? "is out of range" : "is not finite";
      throw ParameterError("argument '" + name + "' has element " + std::to_string(i) +
                           " (flat index) = " + py::repr(py::float_(d[i])).cast<std::string>() +
                           " which " + why + "; valid: " + range_text);
    }
  }
}

void require_finite(const FloatArray& a, const std::string& name) {
  // Finite float32 values are exactly those in [-max, max]; ±inf bounds would let Inf through.
  const float big = std::numeric_limits<float>::max();
  require_in_range(a, name, -big, big, "finite numbers");
}

double finite_number(py::handle obj, const std::string& name) {
  if (obj.is_none() || py::isinstance<py::bool_>(obj) || py::isinstance<py::str>(obj) ||
      (py::isinstance<py::array>(obj) && py::reinterpret_borrow<py::array>(obj).ndim() != 0))
    refuse_argument(name, obj, "is not a number");
  double v;
  try {
    v = py::float_(py::reinterpret_borrow<py::object>(obj)).cast<double>();
  } catch (py::error_already_set& e) {
    if (!is_conversion_error(e)) throw;
    refuse_argument(name, obj, e.matches(PyExc_OverflowError) ? "is too large for a float" : "is not a number");
  }
  if (!std::isfinite(v)) refuse_argument(name, obj, "is not finite");
  return v;
}

double number_in_range(py::handle obj, const std::string& name, double lo, double hi,
                       const std::string& range_text) {
  const double v = finite_number(obj, name);
  if (!(v >= lo && v <= hi)) refuse_argument(name, obj, "is out of range; valid: " + range_text);
  return v;
}

int int_in_range(py::handle obj, const std::string& name, long long lo, long long hi) {
  const std::string range = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  // Python ints and numpy integers (operator.index), never floats or bools.
  if (obj.is_none() || py::isinstance<py::bool_>(obj) || !PyIndex_Check(obj.ptr()))
    refuse_argument(name, obj, "is not an integer; valid: " + range);
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(obj.ptr()));
  if (!index) throw py::error_already_set();  // e.g. KeyboardInterrupt inside __index__
  const long long v = PyLong_AsLongLong(index.ptr());
  if (v == -1 && PyErr_Occurred()) {
    if (!PyErr_ExceptionMatches(PyExc_OverflowError)) throw py::error_already_set();
    PyErr_Clear();
    refuse_argument(name, obj, "is out of range; valid: " + range);
  }
  if (v < lo || v > hi) refuse_argument(name, obj, "is out of range; valid: " + range);
  return static_cast<int>(v);
}

RGB rgb_argument(py::handle obj, const std::string& name, double lo, double hi,
                 const std::string& range_text) {
  const bool is_number = py::isinstance<py::float_>(obj) || py::isinstance<py::int_>(obj) ||
                         (py::hasattr(obj, "dtype") && py::hasattr(obj, "ndim") &&
                          obj.attr("ndim").cast<int>() == 0);
  if (is_number && !py::isinstance<py::bool_>(obj)) {
    const double v = number_in_range(obj, name, lo, hi, range_text);
    return RGB(static_cast<float>(v));
  }
  FloatArray a;
  try {
    a = real_array(obj, name);
  } catch (ParameterError&) {
    refuse_argument(name, obj, "is not an RGB triple or a number; valid: " + range_text);
  }
  if (a.ndim() != 1 || a.shape(0) != 3)
    refuse_argument(name, obj, "is not an RGB triple or a number; valid: " + range_text);
  const float* d = a.data();
  for (int c = 0; c < 3; ++c)
    if (!(d[c] >= lo && d[c] <= hi))
      refuse_argument(name, obj, "is out of range; valid: " + range_text);
  return RGB(d[0], d[1], d[2]);
}

Vec3 direction_argument(py::handle obj, const std::string& name) {
  FloatArray a = real_array(obj, name);
  if (a.ndim() != 1 || a.shape(0) != 3)
    throw ParameterError("argument '" + name + "' has shape " + shape_string(a) +
                         "; expected a single direction of shape (3,)");
  require_finite(a, name);
  Vec3 w(a.data()[0], a.data()[1], a.data()[2]);
  if (!normalize_direction(w))
    refuse_argument(name, obj, "is not a direction; valid: a non-zero finite 3-vector");
  return w;
}

}  // namespace bxdf::python

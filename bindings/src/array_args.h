// Turning the numpy-like arguments of the Python API into C-contiguous float32 data, once,
// with errors (ValueError) that name the argument, the value and what is valid.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <vector>

#include "bxdf/spectrum.h"

namespace bxdf::python {

namespace py = pybind11;
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Throws bxdf::ParameterError (Python: ValueError) with "argument '<name>' = <value> <why>".
[[noreturn]] void refuse_argument(const std::string& name, py::handle value, const std::string& why);
[[noreturn]] void refuse_argument(const std::string& name, double value, const std::string& why);

// True for the errors a failed conversion of a value raises (TypeError, ValueError,
// OverflowError, IndexError): those become a ValueError naming the argument. Anything else
// (KeyboardInterrupt, MemoryError, an error inside the caller's own __array__) propagates as is.
bool is_conversion_error(const py::error_already_set& e);

// numpy.asarray(obj), refusing a masked array (whose mask numpy.asarray would drop silently).
py::array as_numpy_array(py::handle obj, const std::string& name);

// A str or os.PathLike as text; refuses empty paths and embedded NUL characters.
std::string path_argument(py::handle path, const std::string& name = "path");

// Any array-like of real numbers (int or float dtype, any layout) as C-contiguous float32.
FloatArray real_array(py::handle obj, const std::string& name);

// A batch of `width`-vectors: shape (N, width), or (width,) for a single vector (N = 1).
struct VectorRows {
  FloatArray array;  // keeps the converted data alive
  const float* data = nullptr;
  size_t rows = 0;
  size_t width = 0;
  bool single = false;  // given as one (width,) vector
  // Row i of a batch of `n` rows; a single row broadcasts to every i.
  const float* row(size_t i) const { return data + (rows == 1 ? 0 : i * width); }
};
VectorRows vector_rows(py::handle obj, const std::string& name, size_t width);

// The common batch size N of arguments that each have N rows or one row (which broadcasts).
struct NamedRows {
  const VectorRows* rows;
  const char* name;
};
size_t broadcast_rows(std::initializer_list<NamedRows> args);

// Refuses NaN/Inf (and, when given, values outside [lo, hi]) anywhere in `a`.
void require_finite(const FloatArray& a, const std::string& name);
void require_in_range(const FloatArray& a, const std::string& name, float lo, float hi,
                      const std::string& range_text);

// Scalar arguments.
double finite_number(py::handle obj, const std::string& name);
double number_in_range(py::handle obj, const std::string& name, double lo, double hi,
                       const std::string& range_text);
int int_in_range(py::handle obj, const std::string& name, long long lo, long long hi);
// A colour given as one number (grey) or three numbers; every channel finite and in [lo, hi].
RGB rgb_argument(py::handle obj, const std::string& name, double lo, double hi,
                 const std::string& range_text);
// A single direction (3,); refuses zero-length and non-finite vectors.
Vec3 direction_argument(py::handle obj, const std::string& name);

}  // namespace bxdf::python

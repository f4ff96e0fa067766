// Fresnel reflectance and the seed's F0 inversions, elementwise over arrays of any shape.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <limits>
#include <vector>

#include "array_args.h"
#include "binding_modules.h"
#include "bxdf/fresnel.h"

namespace bxdf::python {

namespace {

constexpr double kTinyPositive = std::numeric_limits<double>::min();
constexpr double kHuge = std::numeric_limits<double>::max();

std::vector<py::ssize_t> shape_of(const FloatArray& a) {
  return std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim());
}

// out[i] = fn(in[i]) with the GIL released; a 0-d input (a Python scalar) gives a float.
template <class Fn>
py::object map_scalar(const FloatArray& in, Fn fn) {
  py::array_t<float> out(shape_of(in));
  const float* src = in.data();
  float* dst = out.mutable_data();
  const size_t n = static_cast<size_t>(in.size());
  {
    py::gil_scoped_release nogil;
    for (size_t i = 0; i < n; ++i) dst[i] = fn(src[i]);
  }
  if (in.ndim() == 0) return py::float_(dst[0]);
  return std::move(out);
}

FloatArray cosines(py::handle obj) {
  FloatArray a = real_array(obj, "cos_i");
  require_in_range(a, "cos_i", -1.0f, 1.0f, "[-1, 1]");
  return a;
}

}  // namespace

void bind_fresnel(py::module_& m) {
  m.def(
      "fresnel_dielectric",
      [](py::handle cos_i, py::handle eta_i_arg, py::handle eta_t_arg) {
        const FloatArray c = cosines(cos_i);
        const float eta_i = static_cast<float>(
            number_in_range(eta_i_arg, "eta_i", kTinyPositive, kHuge, "(0, inf)"));
        const float eta_t = static_cast<float>(
            number_in_range(eta_t_arg, "eta_t", kTinyPositive, kHuge, "(0, inf)"));
        return map_scalar(c, [=](float x) { return fresnel_dielectric(x, eta_i, eta_t); });
      },
      py::arg("cos_i"), py::arg("eta_i"), py::arg("eta_t"),
      R"doc(fresnel_dielectric(cos_i, eta_i, eta_t) -> ndarray float32 (same shape as cos_i)

Unpolarised Fresnel reflectance of a dielectric interface, (r_par^2 + r_perp^2) / 2, for
light arriving at cos_i (in [-1, 1]; a scalar or an array of any shape, e.g. (N,)) from the
medium of index eta_i onto the medium of index eta_t (both > 0). cos_i < 0 means the light
arrives from the eta_t side (the indices swap); total internal reflection gives 1.
A scalar cos_i returns a float.)doc");

  m.def(
      "fresnel_conductor",
      [](py::handle cos_i, py::handle eta_arg, py::handle k_arg) {
        const FloatArray c = cosines(cos_i);
        const RGB eta = rgb_argument(eta_arg, "eta", kTinyPositive, kHuge, "(0, inf) per channel");
        const RGB k = rgb_argument(k_arg, "k", 0.0, kHuge, "[0, inf) per channel");
        std::vector<py::ssize_t> shape = shape_of(c);
        shape.push_back(3);
        py::array_t<float> out(shape);
        const float* src = c.data();
        float* dst = out.mutable_data();
        const size_t n = static_cast<size_t>(c.size());
        {
          py::gil_scoped_release nogil;
          for (size_t i = 0; i < n; ++i) {
            const RGB f = fresnel_conductor_seed(src[i], eta, k);
            dst[3 * i] = f.r;
            dst[3 * i + 1] = f.g;
            dst[3 * i + 2] = f.b;
          }
        }
        return out;
      },
      py::arg("cos_i"), py::arg("eta"), py::arg("k"),
      R"doc(fresnel_conductor(cos_i, eta, k) -> ndarray float32, shape cos_i.shape + (3,)

Fresnel reflectance of a conductor (the seed's r_par^2, r_perp^2 formula in terms of eta and
k), evaluated at |cos_i| (cos_i in [-1, 1], scalar or any shape; (N,) gives (N, 3)). `eta`
(> 0) and `k` (>= 0) are RGB: a number (grey) or three numbers, relative to the outside
medium.)doc");

  m.def(
      "eta_from_f0",
      [](py::handle f0) {
        FloatArray a = real_array(f0, "f0");
        require_in_range(a, "f0", 0.0f, 1.0f, "[0, 1]");
        return map_scalar(a, [](float x) { return eta_from_f0(x); });
      },
      py::arg("f0"),
      R"doc(eta_from_f0(f0) -> same shape as f0 (float for a scalar)

The seed's inversion of the normal-incidence reflectance F0 (in [0, 1]) of a dielectric
(k = 0): eta = (1 + sqrt(F0)) / (1 - sqrt(F0)). F0 is clamped below 1 so eta stays finite.)doc");

  m.def(
      "k_from_f0",
      [](py::handle f0) {
        FloatArray a = real_array(f0, "f0");
        require_in_range(a, "f0", 0.0f, 1.0f, "[0, 1]");
        return map_scalar(a, [](float x) { return k_from_f0(x); });
      },
      py::arg("f0"),
      R"doc(k_from_f0(f0) -> same shape as f0 (float for a scalar)

The seed's inversion of the normal-incidence reflectance F0 (in [0, 1]) of a conductor with
eta = 1: k = 2 sqrt(F0 / (1 - F0)). F0 is clamped below 1 so k stays finite.)doc");
}

}  // namespace bxdf::python

// Test hooks: the same queries as Model.f / pdf / sample_f, answered one direction at a time
// through the core's scalar API on the calling thread. The Python tests compare the batched,
// chunked, multi-threaded path against these. Not part of the public API (underscore names).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "array_args.h"
#include "binding_modules.h"
#include "model.h"

namespace bxdf::python {

namespace {

Vec3 vec_at(const VectorRows& v, size_t i) {
  const float* p = v.row(i);
  return Vec3(p[0], p[1], p[2]);
}

}  // namespace

void bind_reference(py::module_& m) {
  m.def(
      "_reference_f",
      [](const Model& model, py::handle wo_arg, py::handle wi_arg) {
        const VectorRows wo = vector_rows(wo_arg, "wo", 3), wi = vector_rows(wi_arg, "wi", 3);
        const size_t n = broadcast_rows({{&wo, "wo"}, {&wi, "wi"}});
        py::array_t<float> out({n, size_t{3}});
        float* d = out.mutable_data();
        for (size_t i = 0; i < n; ++i) {
          const RGB f = model->f(vec_at(wo, i), vec_at(wi, i));
          d[3 * i] = f.r;
          d[3 * i + 1] = f.g;
          d[3 * i + 2] = f.b;
        }
        return out;
      },
      py::arg("model"), py::arg("wo"), py::arg("wi"), "Scalar-path f, for tests.");
  m.def(
      "_reference_pdf",
      [](const Model& model, py::handle wo_arg, py::handle wi_arg) {
        const VectorRows wo = vector_rows(wo_arg, "wo", 3), wi = vector_rows(wi_arg, "wi", 3);
        const size_t n = broadcast_rows({{&wo, "wo"}, {&wi, "wi"}});
        py::array_t<float> out(n);
        float* d = out.mutable_data();
        for (size_t i = 0; i < n; ++i) d[i] = model->pdf(vec_at(wo, i), vec_at(wi, i));
        return out;
      },
      py::arg("model"), py::arg("wo"), py::arg("wi"), "Scalar-path pdf, for tests.");
  m.def(
      "_reference_sample_f",
      [](const Model& model, py::handle wo_arg, py::handle u_arg) {
        const VectorRows wo = vector_rows(wo_arg, "wo", 3), u = vector_rows(u_arg, "u", 2);
        const size_t n = broadcast_rows({{&wo, "wo"}, {&u, "u"}});
        py::array_t<float> wi_out({n, size_t{3}}), f_out({n, size_t{3}}), pdf_out(n);
        float* wi = wi_out.mutable_data();
        float* f = f_out.mutable_data();
        float* pdf = pdf_out.mutable_data();
        for (size_t i = 0; i < n; ++i) {
          const float* up = u.row(i);
          const BxDFSample s = model->sample_f(vec_at(wo, i), Point2(up[0], up[1]));
          const bool ok = s.valid();
          for (int c = 0; c < 3; ++c) {
            wi[3 * i + c] = ok ? s.wi[c] : 0.0f;
            f[3 * i + c] = ok ? s.f[c] : 0.0f;
          }
          pdf[i] = ok ? s.pdf : 0.0f;
        }
        return py::make_tuple(wi_out, f_out, pdf_out);
      },
      py::arg("model"), py::arg("wo"), py::arg("u"), "Scalar-path sample_f, for tests.");
}

}  // namespace bxdf::python

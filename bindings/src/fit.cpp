// bxdf.fit() and bxdf.fit_error(): analytic registry models fitted to a measured BRDF
// (core/fit, Ceres; present when the build found Ceres).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "array_args.h"
#include "binding_modules.h"
#include "model.h"

#ifdef BXDF_HAVE_FIT
#include "bxdf/fit/fit.h"
#include "bxdf/models/measured.h"
#endif

namespace bxdf::python {

#ifdef BXDF_HAVE_FIT
namespace {

// The data to fit to: a `measured` Model, or a path that load_measured would read.
Model measured_argument(py::handle arg) {
  if (py::isinstance<Model>(arg)) {
    Model m = arg.cast<Model>();
    if (!dynamic_cast<const MeasuredBRDF*>(m.bxdf.get()))
      refuse_argument("measured", arg, "is not a measured model; valid: bxdf.load_measured(path)");
    return m;
  }
  if (py::isinstance<py::str>(arg) || py::hasattr(arg, "__fspath__")) {
    py::dict params;
    params["path"] = py::module_::import("os").attr("fspath")(arg);
    return make_model(py::str("measured"), params);
  }
  refuse_argument("measured", arg, "is not a measured model or a file path");
}

py::dict report_to_python(const fit::FitReport& r) {
  py::dict d;
  d["model"] = r.model;
  d["error"] = r.error;
  d["baseline_error"] = r.baseline_error;
  d["sum_squares"] = r.sum_squares;
  d["samples"] = r.samples;
  d["iterations"] = r.iterations;
  d["total_iterations"] = r.total_iterations;
  d["starts"] = r.starts;
  d["start_errors"] = py::cast(r.start_errors);
  d["seconds"] = r.seconds;
  return d;
}

}  // namespace
#endif

void bind_fit(py::module_& m) {
#ifdef BXDF_HAVE_FIT
  m.def(
      "fit",
      [](py::handle measured_arg, const std::string& model, py::handle lobes,
         py::handle max_iterations, py::handle max_starts, py::handle merl_stride) {
        const Model measured = measured_argument(measured_arg);
        fit::FitOptions options;
        options.model = model;
        options.lobes = int_in_range(lobes, "lobes", 1, 3);
        options.max_iterations = int_in_range(max_iterations, "max_iterations", 1, 100000);
        options.max_starts = int_in_range(max_starts, "max_starts", 0, 1000);
        options.merl_stride = int_in_range(merl_stride, "merl_stride", 1, 180);
        fit::FitResult result;
        {
          py::gil_scoped_release nogil;
          result = fit::fit(*measured, options);
        }
        return py::make_tuple(Model{result.build()}, report_to_python(result.report));
      },
      py::arg("measured"), py::arg("model") = "lafortune", py::arg("lobes") = 2, py::kw_only(),
      py::arg("max_iterations") = 200, py::arg("max_starts") = 0, py::arg("merl_stride") = 4,
      R"doc(fit(measured, model="lafortune", lobes=2, *, max_iterations=200, max_starts=0, merl_stride=4)
    -> (fitted Model, report dict)

Fits an analytic model to a measured BRDF (a model from :func:`load_measured`, or a file path)
by minimising Ngan et al.'s cosine-weighted L2 error, the sum over measurements and RGB
channels of [(f(wo, wi) - f_measured) cos theta_i]^2, from several starting points (Ceres).

`model`: "lambertian", "lafortune" (with `lobes` = 1, 2 or 3), or a Torrance-Sparrow lobe with
a Lambertian term, returned as a `microfacet` model: "blinn", "ashikhmin_shirley",
"cook_torrance" (Beckmann) or "ggx" (Smith shadowing). The fitted model is a registry model
like any other (``bxdf.make(fitted.name, **fitted.params)`` rebuilds it).
`max_iterations` per start in [1, 100000]; `max_starts` in [0, 1000] (0 = all of the model's
starts); `merl_stride` in [1, 180]: MERL data use every theta_h and every n-th theta_d, phi_d cell.

report: ``error`` (RMS of the error above, sqrt(sum / (3 samples))), ``baseline_error`` (the
same for f = 0), ``sum_squares``, ``samples``, ``iterations`` (of the best start),
``total_iterations``, ``starts``, ``start_errors``, ``seconds`` and ``model`` (the fit's name,
e.g. "lafortune2"). Runs with the GIL released.)doc");

  m.def("fit_models", &fit::fit_model_names,
        R"doc(fit_models() -> list[str]

The names :func:`fit` accepts for `model`, e.g. ``["lambertian", "lafortune", ..., "ggx"]``.)doc");

  m.def(
      "fit_error",
      [](py::handle measured_arg, const Model& model, py::handle merl_stride) {
        const Model measured = measured_argument(measured_arg);
        const int stride = int_in_range(merl_stride, "merl_stride", 1, 180);
        const auto& data = dynamic_cast<const MeasuredBRDF&>(*measured).data();
        double error;
        {
          py::gil_scoped_release nogil;
          error = fit::fit_error(data.samples(stride), *model);
        }
        return error;
      },
      py::arg("measured"), py::arg("model"), py::arg("merl_stride") = 4,
      R"doc(fit_error(measured, model, merl_stride=4) -> float

The error :func:`fit` minimises (RMS cosine-weighted L2 against the measurements of
`measured`), for any `model`: compares fits and hand-made models on the same footing.)doc");
#else
  (void)m;
#endif
}

}  // namespace bxdf::python

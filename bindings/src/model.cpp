// models(), make() and the Model class: the registry and the vectorised f / sample_f / pdf /
// rho of every model, generic over whatever the core registers.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "array_args.h"
#include "batch.h"
#include "binding_modules.h"
#include "bxdf/registry.h"
#include "model.h"
#include "params_conversion.h"

namespace bxdf::python {

namespace {

constexpr long long kMaxSamples = 2147483647LL;  // the core counts samples in an int

const ModelInfo& model_info(const std::string& name) {
  const ModelInfo* info = find_model(name);
  if (!info) bxdf::make(name);  // throws the core's "unknown model ...; known models: ..."
  return *info;
}

}  // namespace

Model make_model(const py::object& name_arg, const py::dict& params) {
  if (!py::isinstance<py::str>(name_arg))
    refuse_argument("name", name_arg, "is not a model name (a str); see bxdf.models()");
  const std::string name = name_arg.cast<std::string>();
  const ModelInfo& info = model_info(name);
  return Model{bxdf::make(name, params_from_python(name, info.params, params))};
}

namespace {

py::set flag_names(uint32_t flags) {
  static const std::pair<uint32_t, const char*> names[] = {
      {kReflection, "reflection"}, {kTransmission, "transmission"}, {kDiffuse, "diffuse"},
      {kGlossy, "glossy"},         {kSpecular, "specular"}};
  py::set s;
  for (const auto& [bit, name] : names)
    if (flags & bit) s.add(py::str(name));
  return s;
}

std::string model_repr(const Model& m) {
  std::string s = "bxdf.make('" + m->model_name() + "'";
  const ParamSet& p = m->params();
  for (size_t i = 0; i < p.size(); ++i)
    s += ", " + p.names()[i] + "=" + py::repr(value_to_python(p.values()[i])).cast<std::string>();
  return s + ")";
}

py::array_t<float> model_f(const Model& m, py::handle wo_arg, py::handle wi_arg) {
  const VectorRows wo = vector_rows(wo_arg, "wo", 3);
  const VectorRows wi = vector_rows(wi_arg, "wi", 3);
  const size_t n = broadcast_rows({{&wo, "wo"}, {&wi, "wi"}});
  py::array_t<float> out({n, size_t{3}});
  float* out_data = out.mutable_data();
  const BxDF& bxdf = *m;
  {
    py::gil_scoped_release nogil;
    for_each_chunk(n, [&](size_t begin, size_t end) {
      SoA3 wo_s, wi_s, f_s;
      gather3(wo, begin, end - begin, wo_s);
      gather3(wi, begin, end - begin, wi_s);
      bxdf.f_batch(end - begin, wo_s.in(), wi_s.in(), f_s.rgb());
      scatter3(f_s, begin, end - begin, out_data);
    });
  }
  return out;
}

py::array_t<float> model_pdf(const Model& m, py::handle wo_arg, py::handle wi_arg) {
  const VectorRows wo = vector_rows(wo_arg, "wo", 3);
  const VectorRows wi = vector_rows(wi_arg, "wi", 3);
  const size_t n = broadcast_rows({{&wo, "wo"}, {&wi, "wi"}});
  py::array_t<float> out(n);
  float* out_data = out.mutable_data();
  const BxDF& bxdf = *m;
  {
    py::gil_scoped_release nogil;
    for_each_chunk(n, [&](size_t begin, size_t end) {
      SoA3 wo_s, wi_s;
      gather3(wo, begin, end - begin, wo_s);
      gather3(wi, begin, end - begin, wi_s);
      bxdf.pdf_batch(end - begin, wo_s.in(), wi_s.in(), out_data + begin);
    });
  }
  return out;
}

py::tuple model_sample_f(const Model& m, py::handle wo_arg, py::handle u_arg, bool exact) {
  const VectorRows wo = vector_rows(wo_arg, "wo", 3);
  const VectorRows u = vector_rows(u_arg, "u", 2);
  require_in_range(u.array, "u", 0.0f, 1.0f, "[0, 1) (1 is taken as the largest float below 1)");
  const size_t n = broadcast_rows({{&wo, "wo"}, {&u, "u"}});
  py::array_t<float> wi_out({n, size_t{3}}), f_out({n, size_t{3}}), pdf_out(n);
  float* wi_data = wi_out.mutable_data();
  float* f_data = f_out.mutable_data();
  float* pdf_data = pdf_out.mutable_data();
  const BxDF& bxdf = *m;
  {
    py::gil_scoped_release nogil;
    for_each_chunk(n, [&](size_t begin, size_t end) {
      SoA3 wo_s, wi_s, f_s;
      SoA2 u_s{};  // zeroed: GCC cannot see that gather2 fills what sample_f_batch reads
      gather3(wo, begin, end - begin, wo_s);
      gather2(u, begin, end - begin, u_s);
      if (exact && !bxdf.sample_f_is_exact()) {
        // The exact importance sampler of a walk-sampled model has no batch form.
        for (size_t i = 0; i < end - begin; ++i) {
          const BxDFSample s = bxdf.sample_f_exact(Vec3(wo_s.a[i], wo_s.b[i], wo_s.c[i]),
                                                   Point2(u_s.a[i], u_s.b[i]));
          wi_s.a[i] = s.wi.x, wi_s.b[i] = s.wi.y, wi_s.c[i] = s.wi.z;
          f_s.a[i] = s.f.r, f_s.b[i] = s.f.g, f_s.c[i] = s.f.b;
          pdf_data[begin + i] = s.pdf;
        }
      } else {
        bxdf.sample_f_batch(end - begin, wo_s.in(), u_s.a, u_s.b, wi_s.out(), f_s.rgb(),
                            pdf_data + begin);
      }
      // A failed sample (pdf 0) leaves wi undefined in the core; Python gets zeros.
      for (size_t i = 0; i < end - begin; ++i)
        if (!(pdf_data[begin + i] > 0.0f)) wi_s.a[i] = wi_s.b[i] = wi_s.c[i] = 0.0f;
      scatter3(wi_s, begin, end - begin, wi_data);
      scatter3(f_s, begin, end - begin, f_data);
    });
  }
  return py::make_tuple(wi_out, f_out, pdf_out);
}

py::array_t<float> model_rho(const Model& m, py::handle wo_arg, py::handle n_samples_arg,
                             py::handle seed_arg) {
  const VectorRows wo = vector_rows(wo_arg, "wo", 3);
  const int n_samples = int_in_range(n_samples_arg, "n_samples", 1, kMaxSamples);
  const uint64_t seed = static_cast<uint64_t>(int_in_range(seed_arg, "seed", 0, 2147483647LL));
  const size_t n = wo.rows;
  py::array_t<float> out({n, size_t{3}});
  float* out_data = out.mutable_data();
  const BxDF& bxdf = *m;
  {
    py::gil_scoped_release nogil;
    // Each direction is its own Monte Carlo estimate: one task per direction.
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const float* w = wo.row(i);
      const RGB r = bxdf.rho_hd(Vec3(w[0], w[1], w[2]), n_samples, seed);
      out_data[3 * i] = r.r;
      out_data[3 * i + 1] = r.g;
      out_data[3 * i + 2] = r.b;
    });
  }
  return out;
}

py::array_t<float> model_rho_hh(const Model& m, py::handle n_samples_arg, py::handle seed_arg) {
  const int n_samples = int_in_range(n_samples_arg, "n_samples", 1, kMaxSamples);
  const uint64_t seed = static_cast<uint64_t>(int_in_range(seed_arg, "seed", 0, 2147483647LL));
  RGB r;
  {
    py::gil_scoped_release nogil;
    r = m->rho_hh(n_samples, seed);
  }
  py::array_t<float> out(3);
  float* d = out.mutable_data();
  d[0] = r.r;
  d[1] = r.g;
  d[2] = r.b;
  return out;
}

}  // namespace

void bind_models(py::module_& m) {
  m.def(
      "models",
      []() {
        py::dict out;
        for (const auto& info : models()) {
          py::list specs;
          for (const auto& spec : info.params) specs.append(spec_to_python(spec));
          out[py::str(info.name)] = specs;
        }
        return out;
      },
      R"doc(models() -> dict[str, list[dict]]

Every registered reflection model and its parameters, in registry order:
``{model_name: [param, ...]}``, where each ``param`` is a dict with keys

- ``name``: the keyword to pass to :func:`make`
- ``kind``: ``"float"``, ``"rgb"``, ``"enum"``, ``"bool"``, ``"string"`` or ``"list"``
- ``default``: float, ``(r, g, b)`` tuple, str, bool or list of dicts
- ``min``, ``max``: the valid range of a float (or of every RGB channel); ``None`` for other kinds
- ``min_exclusive``, ``max_exclusive``: whether the bounds themselves are refused
- ``unit``: e.g. ``"degrees"`` or ``""``;  ``doc``: one line
- ``subtype`` (rgb only): ``"color"`` (a colour) or ``"per_channel"`` (three independent numbers,
  e.g. an index of refraction per channel)
- ``choices`` (enum only): the allowed strings
- ``fields`` (list only): the parameter dicts of each list element (e.g. a Lafortune lobe)
- ``when`` (only if conditional): ``{"param": name, "values": [...]}``: the parameter matters
  only while parameter ``name`` has one of ``values``.

The registry in the C++ core is the single source of these declarations.)doc");

  m.def(
      "model_doc",
      [](const py::object& name) -> std::string {
        if (!py::isinstance<py::str>(name))
          refuse_argument("name", name, "is not a model name (a str); see bxdf.models()");
        return model_info(name.cast<std::string>()).doc;
      },
      py::arg("name"),
      "model_doc(name) -> str\n\nOne-line description of the model `name` (ValueError if unknown).");

  m.def(
      "make", [](const py::object& name, const py::kwargs& params) { return make_model(name, params); },
      py::arg("name"),
        R"doc(make(name, **params) -> Model

Builds the reflection model `name` (see :func:`models`) with the given parameters; parameters
not given take their defaults.

Values: numbers for ``float`` parameters; a number (grey) or three numbers (tuple, list or
numpy array) for ``rgb``; a str for ``enum`` (one of its ``choices``) and ``string``; a bool
for ``bool``; a list of dicts for ``list`` parameters, e.g. Lafortune's
``lobes=[{"cx": -1, "cy": -1, "cz": 1, "exponent": 20}]`` (each field a number or RGB).

Raises ValueError naming the parameter, the value and the valid range for an unknown model,
an unknown parameter, a value of the wrong kind, NaN or Inf, or a value out of range.

Example: ``bxdf.make("lambertian", reflectance=(0.8, 0.5, 0.2))``)doc");

  py::class_<Model>(m, "Model", R"doc(A reflection model made by :func:`make` (immutable).

Array conventions of every method: directions are (N, 3) arrays in the local shading frame
(z = normal, both ``wo`` and ``wi`` pointing away from the surface), or one (3,) vector; any
real dtype and memory layout is accepted and converted once to C-contiguous float32. A single
(3,) or (1, 3) argument broadcasts against an (N, 3) one. Results are float32 and always
keep the batch axis: a call with only (3,) vectors returns N = 1 results, shape (1, 3) or
(1,), never squeezed. Directions need not be unit length; a zero or non-finite direction
is "no direction" and gives 0. Results are never NaN, Inf or negative.

Large batches run on all cores with the GIL released.)doc")
      .def_property_readonly(
          "name", [](const Model& self) { return self->model_name(); },
          "The registry name of the model, e.g. 'lambertian'.")
      .def_property_readonly(
          "params", [](const Model& self) { return params_to_python(self->params()); },
          "All parameters (validated, defaults filled in) as a dict; "
          "``bxdf.make(m.name, **m.params)`` rebuilds an equal model.")
      .def_property_readonly(
          "flags", [](const Model& self) { return flag_names(self->flags()); },
          "The lobe types as a set of strings from {'reflection', 'transmission', "
          "'diffuse', 'glossy', 'specular'}.")
      .def_property_readonly(
          "doc", [](const Model& self) { return model_info(self->model_name()).doc; },
          "One-line description of the model.")
      .def("f", &model_f, py::arg("wo"), py::arg("wi"),
           R"doc(f(wo, wi) -> ndarray (N, 3) float32

The BxDF value f(wo, wi) (RGB, 1/sr) for each pair of rows of `wo` and `wi` ((N, 3) or (3,)).
Delta (specular) lobes give 0 here; use sample_f.)doc")
      .def("pdf", &model_pdf, py::arg("wo"), py::arg("wi"),
           R"doc(pdf(wo, wi) -> ndarray (N,) float32

The solid-angle density with which sample_f(wo, .) chooses `wi`. Delta lobes give 0.)doc")
      .def_property_readonly(
          "sample_f_is_exact", [](const Model& self) { return self->sample_f_is_exact(); },
          "False for a model whose sample_f samples as Cycles does where that is not exact "
          "importance sampling of f: the multiscatter GGX sampling walk, and rough refraction "
          "drawn from its facets alone (its f is then the sample's weight times "
          "pdf/|cos theta_i|, not f(wo, wi)); sample_f(..., exact=True) is its exact "
          "importance sampler.")
      .def("sample_f", &model_sample_f, py::arg("wo"), py::arg("u"), py::arg("exact") = false,
           R"doc(sample_f(wo, u, exact=False) -> (wi (N, 3), f (N, 3), pdf (N,)), all float32

Importance-samples an incident direction for each row of `wo` ((N, 3) or (3,)) from the
uniform numbers `u` ((N, 2) or (2,), each in [0, 1); non-finite or out-of-range u is a
ValueError). Returns the unit direction wi, the value f(wo, wi) and its density pdf. For a
delta lobe pdf is 1 and f is the seed's weight. When no sample exists (pdf = 0), wi and f
are 0. A multiscatter GGX model (sample_f_is_exact False) samples as Cycles does, with its
random walk: f |cos theta_i| / pdf is the walk's weight and pdf is pdf(wo, wi) (Cycles'
approximate pdf), so f differs from f(wo, wi). So does a rough refraction (Glass, Refraction,
a Principled BSDF's glass): Cycles draws it from its facets alone, which never reach some pairs
where f > 0; f |cos theta_i| / pdf is f over the density of that draw and pdf is pdf(wo, wi).
So does a Principled BSDF's rough clearcoat: Cycles draws it from GGX's visible normals and
divides by a GTR1 pdf that is not that draw's density, so f |cos theta_i| / pdf is Cycles'
(biased) weight, not an estimate of f alone; pdf is pdf(wo, wi). exact=True draws wi from pdf
instead, with f and pdf those of wi.)doc")
      .def("rho", &model_rho, py::arg("wo"), py::arg("n_samples"), py::arg("seed") = 0,
           R"doc(rho(wo, n_samples, seed=0) -> ndarray (N, 3) float32

Hemispherical-directional reflectance rho_hd(wo) = integral of f(wo, wi) |cos theta_i| dwi for
each row of `wo` ((N, 3) or (3,)). Models with a closed form use it; the others take a
stratified, seeded Monte Carlo estimate with about `n_samples` samples (an integer in
[1, 2147483647]), so equal arguments give equal results. Directions run in parallel.)doc")
      .def("rho_hh", &model_rho_hh, py::arg("n_samples"), py::arg("seed") = 0,
           R"doc(rho_hh(n_samples, seed=0) -> ndarray (3,) float32

Hemispherical-hemispherical reflectance (1/pi) double integral of f |cos theta_o cos theta_i|:
the closed form where the model has one, else a stratified seeded Monte Carlo estimate with
about `n_samples` samples (an integer in [1, 2147483647]).)doc")
      .def("__repr__", &model_repr)
      .def(
          "__eq__",
          [](const Model& a, py::object other) {
            if (!py::isinstance<Model>(other)) return false;
            const Model& b = other.cast<const Model&>();
            return a->model_name() == b->model_name() && a->params() == b->params();
          },
          py::is_operator())
      .def("__hash__", [](const Model& self) { return py::hash(py::str(model_repr(self))); })
      .def(py::pickle(
          [](const Model& self) {
            return py::make_tuple(self->model_name(), params_to_python(self->params()));
          },
          [](const py::tuple& state) {
            if (state.size() != 2) throw ParameterError("bxdf.Model: bad pickle state");
            return make_model(state[0], state[1].cast<py::dict>());
          }));
}

}  // namespace bxdf::python

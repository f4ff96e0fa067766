// The Python-side model object: an immutable, shared core model plus what Python needs to
// rebuild it (its registry name and validated parameters live on the core object).
#pragma once

#include <pybind11/pybind11.h>

#include "bxdf/bxdf.h"

namespace bxdf::python {

struct Model {
  BxDFPtr bxdf;
  const BxDF& operator*() const { return *bxdf; }
  const BxDF* operator->() const { return bxdf.get(); }
};

// bxdf.make(name, **params) (model.cpp): ValueError for a non-str name, an unknown model or a
// bad parameter.
Model make_model(const pybind11::object& name, const pybind11::dict& params);

}  // namespace bxdf::python

// The Python-side model object: an immutable, shared core model plus what Python needs to
// rebuild it (its registry name and validated parameters live on the core object).
#pragma once

#include "bxdf/bxdf.h"

namespace bxdf::python {

struct Model {
  BxDFPtr bxdf;
  const BxDF& operator*() const { return *bxdf; }
  const BxDF* operator->() const { return bxdf.get(); }
};

}  // namespace bxdf::python

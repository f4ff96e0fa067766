#include "bxdf/models/measured.h"

#include "bxdf/registry.h"

#ifndef BXDF_DATA_DIR
#error "BXDF_DATA_DIR must point at the repository's data/ folder"
#endif

namespace bxdf {

ModelInfo measured_model() {
  ModelInfo m;
  m.name = "measured";
  m.doc = "Measured isotropic BRDF from a MERL .binary or Cornell .brdf file";
  m.params = {
      // The default is a real measurement shipped with the sources, so that make("measured")
      // and the generic model tests work without a path.
      string_param("path", BXDF_DATA_DIR "/measured/acryl_blue.brdf",
                   "MERL .binary or Cornell .brdf file (read once, cached by path and time)"),
      bool_param("interpolate", true,
                 "MERL: trilinear interpolation between cells instead of the nearest cell"),
  };
  m.create = [](const ParamSet& p) {
    const std::string& path = p.string("path");
    if (path.empty())
      throw ParameterError("measured: parameter 'path' = '' is empty; valid: a MERL .binary or "
                           "Cornell .brdf file");
    return std::make_unique<MeasuredBRDF>(load_measured_data(path), p.boolean("interpolate"));
  };
  return m;
}

}  // namespace bxdf

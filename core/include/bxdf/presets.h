// Named materials: the seed's conductors and the Lafortune fits of measured materials.
// A preset is only data (a registry model name and its parameters); make_preset() builds it
// through the registry like any other model.
#pragma once

#include <string>
#include <vector>

#include "bxdf/registry.h"

namespace bxdf {

struct Preset {
  std::string name;
  std::string model;
  std::string doc;
  ParamSet params;
};

const std::vector<Preset>& presets();
const Preset* find_preset(const std::string& name);
std::string preset_names();  // "gold, silver, ..." for messages
// Throws ParameterError naming the preset and the known ones.
BxDFPtr make_preset(const std::string& name);

}  // namespace bxdf

// The Fresnel parameters that several models share (specular_reflection, microfacet):
// declared once here, read once here.
#pragma once

#include <string>
#include <vector>

#include "bxdf/fresnel.h"
#include "bxdf/params.h"

namespace bxdf {

// `fresnel` ∈ {none, dielectric, conductor}, then eta_i/eta_t (dielectric only) and eta/k
// (conductor only, defaulting to the seed's gold as a grey).
std::vector<ParamSpec> fresnel_params(const std::string& default_kind);

// The Fresnel term that a validated parameter set describes.
Fresnel fresnel_from_params(const ParamSet& p);

}  // namespace bxdf

// Random valid parameter sets drawn from a model's own ParamSpecs, with a bias towards the
// extremes of each range (the bounds themselves, the first value past an exclusive bound,
// huge values for unbounded ranges), for fuzzing.
#pragma once

#include <vector>

#include "bxdf/params.h"
#include "bxdf/rng.h"

namespace bxdf::test {

ParamSet random_valid_params(const std::vector<ParamSpec>& specs, PCG32& rng);

}  // namespace bxdf::test

#include "random_params.h"

#include <algorithm>
#include <cmath>

namespace bxdf::test {

namespace {

constexpr double kHuge = 1e30;  // stands in for an infinite bound

double random_number(const ParamSpec& s, PCG32& rng) {
  const double lo = std::isinf(s.min) ? -kHuge : (s.min_exclusive ? std::nextafter(s.min, s.max) : s.min);
  const double hi = std::isinf(s.max) ? kHuge : (s.max_exclusive ? std::nextafter(s.max, s.min) : s.max);
  switch (rng.bounded(8)) {
    case 0: return lo;
    case 1: return hi;
    case 2:  // the smallest float-representable step inside the lower bound
      return std::isinf(s.min) ? lo : std::min(hi, s.min + std::max(1e-7, std::fabs(s.min) * 1e-6));
    case 3:  // log-uniform over the positive part of the range, when it spans decades
      if (lo >= 0.0 && hi > 0.0) {
        const double a = std::log(std::max(lo, 1e-8)), b = std::log(hi);
        return std::clamp(std::exp(a + (b - a) * rng.uniform_double()), lo, hi);
      }
      [[fallthrough]];
    default: {  // uniform over the range (clipped to a sane span for unbounded ones)
      const double a = std::max(lo, -1e3), b = std::min(hi, 1e3);
      return std::clamp(a + (b - a) * rng.uniform_double(), lo, hi);
    }
  }
}

Value random_value(const ParamSpec& s, PCG32& rng) {
  switch (s.kind) {
    case ParamKind::Float: return Value(random_number(s, rng));
    case ParamKind::RGB:
      if (rng.bounded(4) == 0) return Value(random_number(s, rng));  // a grey given as a number
      return Value(RGBValue{random_number(s, rng), random_number(s, rng), random_number(s, rng)});
    case ParamKind::Enum: return Value(s.choices[rng.bounded(static_cast<uint32_t>(s.choices.size()))]);
    case ParamKind::Bool: return Value(rng.bounded(2) == 1);
    case ParamKind::String: return s.default_value;  // file paths and the like: not fuzzed
    case ParamKind::List: {
      std::vector<ParamSet> items(rng.bounded(4));
      for (ParamSet& item : items) item = random_valid_params(s.fields, rng);
      return Value(std::move(items));
    }
  }
  return s.default_value;
}

}  // namespace

ParamSet random_valid_params(const std::vector<ParamSpec>& specs, PCG32& rng) {
  ParamSet p;
  for (const ParamSpec& s : specs) p.set(s.name, random_value(s, rng));
  return p;
}

}  // namespace bxdf::test

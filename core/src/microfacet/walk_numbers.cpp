#include "bxdf/microfacet/walk_numbers.h"

#include <algorithm>

namespace bxdf {
namespace microfacet {

namespace {

thread_local WalkNumbers* walk_numbers = nullptr;

// The 32-bit integer whose Cycles float (x · 2^-32) is u, for u in [0, 1).
uint32_t integer_of(float u) {
  const double x = static_cast<double>(std::clamp(u, 0.0f, 0x1.fffffep-1f)) * 4294967296.0;
  return static_cast<uint32_t>(x);
}

}  // namespace

Point2 WalkNumbers::first_facet(Point2 u) {
  if (anchor_->position != 0) {
    const float y = uniform();
    const float x = uniform();
    return Point2(x, y);
  }
  // The path's first sampling walk: its facet is u, and the LCG's two numbers here are what
  // every later vertex's draws at these positions are measured from.
  const uint32_t y = next(), x = next();
  anchor_->position = drawn_ - 1;
  anchor_->shift_y = integer_of(u.y) - y;
  anchor_->shift_x = integer_of(u.x) - x;
  return u;
}

MultiscatterWalkNumbers::MultiscatterWalkNumbers(WalkNumbers* numbers) : previous_(walk_numbers) {
  walk_numbers = numbers;
}
MultiscatterWalkNumbers::~MultiscatterWalkNumbers() { walk_numbers = previous_; }
WalkNumbers* MultiscatterWalkNumbers::current() { return walk_numbers; }
WalkNumbers** MultiscatterWalkNumbers::thread_slot() { return &walk_numbers; }

}  // namespace microfacet
}  // namespace bxdf

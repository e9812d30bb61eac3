#pragma once

#include <cmath>

#include "decider.hpp"

namespace batchccd {

// What a minimum separation must be, for Options::min_distance and for each
// per-candidate one alike: nullptr when `value` is acceptable for `decider`,
// else what it must be (for the message).
inline const char* separation_problem(double value, Decider decider) {
  if (!(value >= 0 && std::isfinite(value))) return ">= 0 and finite";  // NaN fails too
  if (decider == Decider::cubic && value > 0)
    return "0 with the cubic baseline (the cubic finds roots, not distances)";
  return nullptr;
}

}  // namespace batchccd

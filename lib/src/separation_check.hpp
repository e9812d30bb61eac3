#pragma once

#include <cmath>

#include "batchccd/options.hpp"

namespace batchccd {

// What a minimum separation must be, for Options::min_distance and for each
// per-candidate one alike: nullptr when `value` is acceptable in `mode`,
// else what it must be (for the message).
inline const char* separation_problem(double value, Mode mode) {
  if (!(value >= 0 && std::isfinite(value))) return ">= 0 and finite";  // NaN fails too
  if (mode == Mode::cubic && value > 0) return "0 in mode cubic (the cubic finds roots, not distances)";
  return nullptr;
}

}  // namespace batchccd

#pragma once

#include "batchccd/lab.hpp"
#include "batchccd/options.hpp"

namespace batchccd {

// What decides a call: Options::mode, unless a baseline takes its place.
enum class Decider { conservative, exact, fast, cubic };

inline Decider decider_of(const Options& options, const lab::Settings& settings) {
  switch (settings.baseline) {
    case lab::Baseline::fast: return Decider::fast;
    case lab::Baseline::cubic: return Decider::cubic;
    case lab::Baseline::none: break;
  }
  return options.mode == Mode::exact ? Decider::exact : Decider::conservative;
}

}  // namespace batchccd

#pragma once

// A broken invariant is a finding: say which one, then abort so that
// libFuzzer saves the input as a crash artifact.

#include <cstdio>
#include <cstdlib>

namespace batchccd::fuzz {

[[noreturn]] inline void fail(const char* invariant, const char* detail = "") {
  std::fprintf(stderr, "batchccd fuzz: invariant broken: %s %s\n", invariant, detail);
  std::abort();
}

inline void require(bool holds, const char* invariant, const char* detail = "") {
  if (!holds) fail(invariant, detail);
}

}  // namespace batchccd::fuzz

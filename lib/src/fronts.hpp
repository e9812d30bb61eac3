#pragma once

// What the calls shaped like other libraries (ipc.hpp, tight_inclusion.hpp)
// share: their arguments checked, and turned into Options.
#include <string>

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

namespace batchccd::fronts {

// Throws std::invalid_argument "<call>: <name> must be <expected>, got <value>"
// unless `holds`.
void require(bool holds, const char* call, const char* name, const char* expected, double value);

// Conservative mode with the caller's distance tolerance (its length units)
// as Options::tolerance: divided by the query's largest coordinate spread
// (at t0 or at t1), rounded down, so that relative to the size the solver
// scales the query by (never larger than that spread) it stays within
// `tolerance`. max_iterations < 0: no limit.
Options conservative_options(const Query& query, double tolerance, long max_iterations);

}  // namespace batchccd::fronts

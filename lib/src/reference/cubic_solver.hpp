#pragma once

#include "batchccd/query.hpp"

namespace batchccd::reference {

// The standard unfiltered solver, kept as the baseline (lab::Baseline::cubic):
// the coplanarity cubic's monomial coefficients in double, its roots in
// [0, 1] by bisection between the critical points, and at each root in time
// order a plain double inside test (barycentric signs for VF, segment
// parameters for EE). No error bounds: it can miss contacts, and degenerate
// geometry (zero normal, parallel edges) yields no hit.
QueryResult solve_cubic(Kind kind, const Query& query);

}  // namespace batchccd::reference

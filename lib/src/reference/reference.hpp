#pragma once

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

namespace batchccd::reference {

// What the scalar reference path did with one query: the answer and which
// stage settled it (for the batch counters).
struct Evaluation {
  QueryResult result;
  bool culled = false;     // the sign filter removed it
  bool undecided = false;  // the solver ran out of iterations
};

// The whole scalar reference path for one query (DESIGN.md §2-3): scale,
// filter, solve. The SIMD path must agree with it decision for decision.
Evaluation evaluate_query(Kind kind, const Query& query, const Options& options);

}  // namespace batchccd::reference

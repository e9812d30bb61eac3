#pragma once

#include "batchccd/batch.hpp"
#include "batchccd/lab.hpp"
#include "batchccd/options.hpp"
#include "batchccd/query.hpp"
#include "reference/filter.hpp"

namespace batchccd::reference {

// Exact mode: what exact arithmetic settled of a query, if anything.
enum class ExactStage {
  none,      // the certified path settled all of it
  toi,       // a certain contact whose first root it located to 2^-40
  decision,  // the decision (and TOI): the certified path was not certain
};

// What the scalar reference path did with one query: the answer and which
// stage settled it (for the batch counters).
struct Evaluation {
  QueryResult result;
  bool culled = false;          // the sign filter removed it
  bool undecided = false;       // the solver ran out of iterations
  ExactStage exact_stage = ExactStage::none;
  double seconds = 0;           // the evaluation's time, when Options::time_queries
};

// The whole scalar reference path for one query (docs/design.md §3-7): scale,
// filter, solve, and in exact mode settle what stays uncertain exactly. The
// SIMD path must agree with it decision for decision. `kind` may be a point
// kind (filtered with its own distances, searched as its edge-edge query).
// `lab`: a baseline in the mode's place, filters switched off (lab.hpp).
// kept: what the lane filters said of a query they kept (a batch survivor):
// they are not run again, and the pieces of the step they proved free are
// not searched. Null: the filters run here.
Evaluation evaluate_query(Kind kind, const Query& query, const Options& options,
                          const lab::Settings& lab, const FilterVerdict* kept = nullptr);

// Adds what the batch counters take from an evaluation beyond hits, culls
// and the like: exact escalations and the slowest query's time.
void count_exact_stage_and_time(const Evaluation& evaluation, Counters& counters);

}  // namespace batchccd::reference

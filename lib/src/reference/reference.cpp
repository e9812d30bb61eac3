#include "reference/reference.hpp"

#include "reference/cubic_solver.hpp"
#include "reference/filter.hpp"
#include "reference/inclusion_solver.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::reference {

Evaluation evaluate_query(Kind kind, const Query& query, const Options& options) {
  Evaluation evaluation;
  const ScaledQuery scaled = scale_query(kind, query);
  if (!scaled.finite) {
    evaluation.result = {true, 0.0, Status::invalid_input};
    return evaluation;
  }
  if (options.mode == Mode::cubic) {
    evaluation.result = solve_cubic(kind, query);
    return evaluation;
  }
  if (scaled.coincident) {  // all four points are one point throughout
    evaluation.result = {true, 0.0, Status::ok};
    return evaluation;
  }
  const bool certified = options.mode == Mode::conservative;
  if (sign_filter_culls(scaled, certified)) {
    evaluation.culled = true;
    return evaluation;
  }
  SolverSettings settings;
  settings.certified = certified;
  settings.need_toi = options.need_toi;
  settings.tolerance = options.tolerance;
  settings.toi_tolerance = options.toi_tolerance;
  settings.max_iterations = options.max_iterations;
  const SolverOutcome outcome = solve_inclusion(kind, scaled, settings);
  evaluation.undecided = outcome.undecided;
  if (outcome.hit) evaluation.result = {true, outcome.toi, Status::ok};
  return evaluation;
}

}  // namespace batchccd::reference

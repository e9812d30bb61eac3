#include "reference/reference.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>

#include <Eigen/Geometry>

#include "exact/exact_solver.hpp"
#include "exact/expansion_stage.hpp"
#include "exact/first_root.hpp"
#include "exact/plane_axis.hpp"
#include "reference/cubic_solver.hpp"
#include "reference/filter.hpp"
#include "reference/inclusion_solver.hpp"
#include "reference/planar_solver.hpp"
#include "reference/scaled_query.hpp"
#include "decider.hpp"

namespace batchccd::reference {
namespace {

const double kExactToiWidth = std::ldexp(1.0, -static_cast<int>(exact::kToiBits));

// The width a certain contact's TOI is located to: 2^-40 in exact mode,
// toi_tolerance (at least 2^-45, as the solver takes it) otherwise.
double located_toi_width(const Options& options, Decider decider) {
  return decider == Decider::exact ? kExactToiWidth : std::max(0x1p-45, options.toi_tolerance);
}

// `kept`: what the filters said of the query, whose free pieces the
// solver skips.
SolverSettings solver_settings(const Options& options, const lab::Settings& lab, Decider decider,
                               const FilterVerdict& kept) {
  SolverSettings settings;
  if (kept.free_pieces != 0) {
    settings.free_pieces = kept.free_pieces;
    settings.pieces = filter_settings(options, lab).pieces;
  }
  settings.certified = decider != Decider::fast;
  settings.need_toi = options.need_toi;
  settings.tolerance = options.tolerance;
  settings.toi_tolerance = options.toi_tolerance;
  // Certified modes: the exact stage settles whatever the search leaves
  // open, so the search need not be long.
  settings.max_iterations = settings.certified
                                ? std::min(options.max_iterations, options.exact_stage_iterations)
                                : options.max_iterations;
  if (decider == Decider::exact) settings.refined_toi_width = kExactToiWidth;
  settings.tmax = options.tmax;
  return settings;
}

// Any two points of a scaled query lie less than 7 apart (every coordinate
// of x2..x4 below 2 in magnitude, x1 at the origin).
constexpr double kLargerThanEveryDistance = 8;

// Exact arithmetic decides: floating-point expansions, then integers. Where
// the expansions cannot, `proves_miss` (a certain test cheaper than the
// integers, though not than expansions that decide) may settle a miss first.
void settle_exactly(Kind kind, const Query& query, const Options& options, const lab::Settings& lab,
                    Evaluation& evaluation, const std::function<bool()>& proves_miss = {}) {
  std::optional<exact::ExactOutcome> decided;
  if (lab.expansion_stage) decided = exact::solve_with_expansions(kind, query, options.need_toi, options.tmax);
  if (!decided && proves_miss && proves_miss()) return;
  const exact::ExactOutcome outcome =
      decided ? *decided : exact::solve_with_integers(kind, query, options.need_toi, options.tmax);
  evaluation.exact_stage = ExactStage::decision;
  evaluation.undecided = outcome.bound_reached;
  evaluation.result = outcome.hit ? QueryResult{true, outcome.toi, Status::ok} : QueryResult{};
}

// Planar motion (docs/design.md §5a): all eight points in one plane, where
// the coplanarity cubic vanishes and says nothing. Decided in the plane;
// what its signs cannot settle, exactly. False when the motion is not
// planar (or the test cannot tell): the generic path decides then.
bool decide_in_plane(Kind kind, const Query& query, const ScaledQuery& scaled, const Options& options,
                     const lab::Settings& lab, Decider decider, Evaluation& evaluation) {
  const std::optional<int> axis = exact::exact_plane_axis(query);
  if (!axis) return false;
  const double toi_width = located_toi_width(options, decider);
  const PlanarOutcome outcome =
      solve_planar(planar_shape(kind, query), scaled, *axis, options.tmax, toi_width);
  if (!outcome.certain) {
    settle_exactly(kind, query, options, lab, evaluation);
  } else if (outcome.hit) {
    evaluation.result = {true, outcome.toi, Status::ok};
  }
  return true;
}

// A point against a segment or a point (a zero-length edge is a point).
bool is_point_shape(PlanarShape shape) {
  return shape == PlanarShape::vertex_segment || shape == PlanarShape::segment_vertex ||
         shape == PlanarShape::vertices;
}

// With a separation, where the closest pair is always a vertex and a
// segment (docs/design.md §5a): motion in the axis plane `axis`, decided
// there, or else a point against a segment or a point in 3D. True when that
// search is certain (the answer is in `evaluation`).
bool decide_within_by_pairs(PlanarShape shape, std::optional<int> axis, const ScaledQuery& scaled, double separation,
                            const Options& options, Decider decider, Evaluation& evaluation) {
  const double toi_width = located_toi_width(options, decider);
  const PlanarOutcome outcome = axis ? solve_planar_within(shape, scaled, *axis, separation, options.tmax, toi_width)
                                     : solve_point_within(shape, scaled, separation, options.tmax, toi_width);
  if (!outcome.certain) return false;
  if (outcome.hit) evaluation.result = {true, outcome.toi, Status::ok};
  return true;
}

// Parameter boxes the first search with a separation gets: conservative
// advancement needs none, and where boxes are needed (nearly planar
// motion) the pairs' search is the cheaper.
constexpr std::int64_t kFirstSearchBudget = 16;

// A query with a minimum separation (docs/design.md §11): no cubic and no
// exact stage. Conservative advancement settles nearly every query in a few
// steps, planar motion and points included, so it comes first, with a
// small budget of boxes; what it leaves uncertain, the pairs' search may
// settle (an axis plane's motion, a point), else the search with the whole
// budget where the first ran out of it. What none settles is reported as
// a hit it could not rule out.
void evaluate_within_distance(const Query& query, const ScaledQuery& scaled, Kind kind, const Options& options,
                              const lab::Settings& lab, Decider decider, const FilterVerdict& kept,
                              Evaluation& evaluation) {
  const double separation = to_scaled_length(scaled, options.min_distance);
  if (separation >= kLargerThanEveryDistance) {
    evaluation.result = {true, 0.0, Status::ok};
    return;
  }
  SolverSettings settings = solver_settings(options, lab, decider, kept);
  settings.min_distance = separation;
  // No exact stage to hand over to: the whole budget.
  settings.max_iterations = options.max_iterations;
  const bool exact = decider == Decider::exact;
  if (exact) {  // the band it may report: 2^-40 of the query's size; the TOI to 2^-40
    settings.tolerance = kExactToiWidth;
    settings.toi_tolerance = kExactToiWidth;
  }
  SolverSettings first = settings;
  first.max_iterations = std::min(settings.max_iterations, kFirstSearchBudget);
  SolverOutcome outcome = solve_inclusion(kind, scaled, first);
  if (!outcome.certain && decider != Decider::fast) {
    const PlanarShape shape = planar_shape(kind, query);
    // Axis planes only (exact_plane_axis's tilted planes do not keep distances).
    const std::optional<int> axis = lab.planar_path ? exact::shared_axis(query) : std::nullopt;
    if ((axis || (lab.point_search && is_point_shape(shape))) &&
        decide_within_by_pairs(shape, axis, scaled, separation, options, decider, evaluation))
      return;
  }
  // Within its budget the first search is the whole one.
  if (outcome.undecided && first.max_iterations < settings.max_iterations)
    outcome = solve_inclusion(kind, scaled, settings);
  evaluation.undecided = outcome.undecided || (exact && outcome.hit && !outcome.certain);
  if (outcome.hit) evaluation.result = {true, outcome.toi, Status::ok};
}

// Whether the query certainly misses in its projection along the axis its
// points' planes lean on most: then it misses in 3D (docs/design.md §5a).
bool misses_in_projection(Kind kind, const Query& query, const ScaledQuery& scaled, double tmax) {
  Vec3 normals = Vec3::Zero();
  for (int tau = 0; tau < 2; ++tau) {
    const Vec3 &a = scaled.relative[0][tau], &b = scaled.relative[1][tau], &c = scaled.relative[2][tau];
    normals += a.cross(b).cwiseAbs() + a.cross(c).cwiseAbs() + b.cross(c).cwiseAbs();
  }
  int axis = 0;
  normals.maxCoeff(&axis);
  const PlanarOutcome outcome = solve_planar(planar_shape(kind, query), scaled, axis, tmax, 1);
  return outcome.certain && !outcome.hit;
}

// A point against a segment or a point that certainly never touches in [0, tmax].
bool proves_point_miss(Kind kind, const Query& query, const ScaledQuery& scaled, double tmax) {
  const PlanarShape shape = planar_shape(kind, query);
  if (!is_point_shape(shape)) return false;
  const PlanarOutcome outcome = solve_point_within(shape, scaled, 0, tmax, 1);
  return outcome.certain && !outcome.hit;
}

Evaluation evaluate(Kind asked, const Query& query, const Options& options, const lab::Settings& lab,
                    const FilterVerdict* kept) {
  // A point kind is searched as the edge-edge query it is stored as, and
  // filtered with its own distances, as the lanes filter it.
  const Kind kind = evaluated_kind(asked);
  Evaluation evaluation;
  const Decider decider = decider_of(options, lab);
  if (decider == Decider::cubic) {  // the baseline as it is, without the scaled frame
    evaluation.result = all_finite(query) ? solve_cubic(kind, query)
                                          : QueryResult{true, 0.0, Status::invalid_input};
    if (evaluation.result.toi > options.tmax) evaluation.result = {};
    return evaluation;
  }
  const FilterVerdict verdict =
      kept != nullptr ? *kept : run_filters(kind, query, settings_for(asked, filter_settings(options, lab)));
  if (verdict.culled()) {
    evaluation.culled = true;
    return evaluation;
  }
  const ScaledQuery scaled = scale_query(kind, query);
  if (!scaled.finite) {
    evaluation.result = {true, 0.0, Status::invalid_input};
    return evaluation;
  }
  const bool exact = decider == Decider::exact;
  if (options.min_distance > 0) {
    // Coincident points are within any separation: a hit at 0.
    if (scaled.coincident) evaluation.result = {true, 0.0, Status::ok};
    else evaluate_within_distance(query, scaled, kind, options, lab, decider, verdict, evaluation);
    return evaluation;
  }
  if (scaled.coincident) {  // all four points are one point throughout
    // Scaling may have flushed tiny differences to zero: only exact
    // arithmetic can tell those from a true coincidence.
    if (exact) {
      settle_exactly(kind, query, options, lab, evaluation);
    } else {
      evaluation.result = {true, 0.0, Status::ok};
    }
    return evaluation;
  }
  if (decider != Decider::fast && lab.planar_path && decide_in_plane(kind, query, scaled, options, lab, decider, evaluation))
    return evaluation;
  SolverOutcome outcome = solve_inclusion(kind, scaled, solver_settings(options, lab, decider, verdict));
  // A certain contact whose interval straddles tmax may come after it:
  // not certain of what counts.
  if (outcome.certain && outcome.hit && outcome.toi_upper > options.tmax) outcome.certain = false;
  // Exact mode: every uncertain decision. Conservative mode: those but a
  // contact within tolerance, which its promise allows; the others (out of
  // iterations, or undecidable at the smallest boxes) would be guesses.
  // Exact arithmetic settles them (docs/design.md §7).
  const bool conservative = decider == Decider::conservative;
  // Nearly planar motion is where the search stays uncertain, and where a
  // projection onto the plane often proves a miss (docs/design.md §5a).
  const auto misses_in_plane = [&] {
    return lab.planar_path && misses_in_projection(kind, query, scaled, options.tmax);
  };
  // A point against a segment or a point: the pairs' search proves misses
  // (docs/design.md §5a), where the coplanarity cubic, identically zero,
  // could not.
  if (!outcome.certain && (exact || conservative) && lab.point_search && proves_point_miss(kind, query, scaled, options.tmax))
    return evaluation;
  if (!outcome.certain && (exact || (conservative && !outcome.within_tolerance))) {
    settle_exactly(kind, query, options, lab, evaluation, misses_in_plane);
    return evaluation;
  }
  // A contact within tolerance conservative mode may report: a miss proven
  // in the plane is still the better answer.
  if (!outcome.certain && conservative && misses_in_plane()) return evaluation;
  evaluation.undecided = outcome.undecided;
  if (outcome.hit) evaluation.result = {true, outcome.toi, Status::ok};
  const double toi_width = located_toi_width(options, decider);
  if ((exact || conservative) && outcome.certain && outcome.hit && options.need_toi &&
      outcome.toi_upper - outcome.toi > toi_width) {
    // A certain contact whose cubic's signs got too close to call before
    // that width (slow relative motion, a multiple root, or a root exactly
    // at a halving point): its root located exactly.
    evaluation.exact_stage = ExactStage::toi;
    const auto toi = lab.expansion_stage
                         ? exact::first_root_lower_bound(kind, query, outcome.toi, outcome.toi_upper)
                         : exact::first_root_with_integers(kind, query, outcome.toi, outcome.toi_upper);
    if (toi) {
      evaluation.result.toi = *toi;
    } else {
      settle_exactly(kind, query, options, lab, evaluation);
    }
  }
  return evaluation;
}

}  // namespace

Evaluation evaluate_query(Kind kind, const Query& query, const Options& options, const lab::Settings& lab,
                          const FilterVerdict* kept) {
  if (!options.time_queries) return evaluate(kind, query, options, lab, kept);
  const auto start = std::chrono::steady_clock::now();
  Evaluation evaluation = evaluate(kind, query, options, lab, kept);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  evaluation.seconds = elapsed.count();
  return evaluation;
}

void count_exact_stage_and_time(const Evaluation& evaluation, Counters& counters) {
  const bool escalated = evaluation.exact_stage != ExactStage::none;
  counters.exact_escalations += escalated;
  counters.max_query_seconds = std::max(counters.max_query_seconds, evaluation.seconds);
  counters.solved_seconds += evaluation.seconds;
  if (escalated) counters.escalated_seconds += evaluation.seconds;
}

}  // namespace batchccd::reference

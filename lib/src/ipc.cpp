#include "batchccd/ipc.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "batchccd/ccd.hpp"
#include "fronts.hpp"
#include "ipc_rules.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::ipc {
namespace {

// ipc-toolkit's constants around Tight Inclusion (ipc/ccd/ccd.cpp,
// ipc/ccd/tight_inclusion_ccd.cpp).
constexpr double kInitialDistanceToleranceScale = 0.5;
constexpr double kSmallToi = 1e-6;
constexpr long kUnlimitedIterations = -1;

// The finest time resolution the solver takes (Options::toi_tolerance).
constexpr double kFinestToiTolerance = 0x1p-45;

bool moves(const Query& query) {
  for (int k = 0; k < 4; ++k)
    if (query.points[k] != query.points[k + 4]) return true;
  return false;
}

// How fast the distance between the primitives can fall: the largest
// displacement of one primitive's points plus that of the other's (Query's
// layout: VF p | a, b, c; the others x0, x1 | x2, x3).
double approach_speed_bound(Kind kind, const Query& query) {
  std::array<double, 4> displacement;
  for (int k = 0; k < 4; ++k) displacement[k] = (query.points[k + 4] - query.points[k]).norm();
  if (kind == Kind::vertex_face)
    return displacement[0] + std::max({displacement[1], displacement[2], displacement[3]});
  return std::max(displacement[0], displacement[1]) + std::max(displacement[2], displacement[3]);
}

QueryResult ask(Kind kind, const Query& query, double min_distance, double distance_tolerance, double tmax,
                long max_iterations, double toi_tolerance = Options{}.toi_tolerance) {
  Options options = fronts::conservative_options(query, distance_tolerance, max_iterations);
  options.tmax = tmax;
  options.min_distance = min_distance;
  options.toi_tolerance = toi_tolerance;
  return query_ccd(kind, query, options);
}

// ipc-toolkit's retry when the first toi is too small to step: the
// caller's separation itself, no iteration limit, the toi rescaled. As
// initial_distance > min_distance the first contact comes after 0, so a
// lower bound of 0 is not an answer (a zero step stalls a line search):
// asked again as finely as the solver resolves time, then bounded by speed.
QueryResult small_toi_retry(Kind kind, const Query& query, double initial_distance, double min_distance,
                            double distance_tolerance, double tmax, double conservative_rescaling) {
  QueryResult result = ask(kind, query, min_distance, distance_tolerance, tmax, kUnlimitedIterations);
  if (result.hit && result.toi == 0)
    result = ask(kind, query, min_distance, distance_tolerance, tmax, kUnlimitedIterations, kFinestToiTolerance);
  if (result.hit && result.toi == 0)
    result.toi = 0.5 * (initial_distance - min_distance) / approach_speed_bound(kind, query);
  if (result.hit)
    result.toi = std::max(result.toi * conservative_rescaling, std::numeric_limits<double>::denorm_min());
  return result;
}

// The settings NarrowPhase holds, checked by its constructor and by every
// call (its members may change in between).
void require_settings(const char* call, double tolerance, double conservative_rescaling) {
  fronts::require(tolerance > 0 && std::isfinite(tolerance), call, "tolerance", "positive and finite", tolerance);
  fronts::require(conservative_rescaling > 0 && conservative_rescaling <= 1, call, "conservative_rescaling",
                  "in (0, 1]", conservative_rescaling);
}

}  // namespace

NarrowPhase::NarrowPhase(double tolerance_, long max_iterations_, double conservative_rescaling_)
    : tolerance(tolerance_), max_iterations(max_iterations_), conservative_rescaling(conservative_rescaling_) {
  require_settings("batchccd::ipc::NarrowPhase", tolerance, conservative_rescaling);
}

namespace rules {

void require_arguments(const char* call, double min_distance, double tmax, double tolerance,
                       double conservative_rescaling) {
  fronts::require(min_distance >= 0 && std::isfinite(min_distance), call, "min_distance", ">= 0 and finite",
                  min_distance);
  fronts::require(tmax >= 0 && tmax <= 1, call, "tmax", "in [0, 1]", tmax);
  require_settings(call, tolerance, conservative_rescaling);
}

bool decide(Kind kind, const Query& query, double& toi, double min_distance, double tmax, double tolerance,
            long max_iterations, double conservative_rescaling) {
  if (!reference::all_finite(query)) {  // never step into what cannot be checked
    toi = 0;
    return true;
  }
  const double initial_distance = std::sqrt(squared_distance(kind, query, 0));
  if (initial_distance <= min_distance) {  // with or without motion, as there
    toi = 0;
    return true;
  }
  if (!moves(query) || tmax == 0) return false;

  const double distance_tolerance = std::min(kInitialDistanceToleranceScale * initial_distance, tolerance);
  // Part of the gap above min_distance (at most 1e-4) kept free, as there.
  const double effective_separation =
      min_distance +
      std::min((1 - conservative_rescaling) * (initial_distance - min_distance), rules::kLargestRescalingSeparation);
  QueryResult result = ask(kind, query, effective_separation, distance_tolerance, tmax, max_iterations);
  if (result.hit && result.toi < kSmallToi)
    result = small_toi_retry(kind, query, initial_distance, min_distance, distance_tolerance, tmax,
                             conservative_rescaling);
  if (result.hit) toi = result.toi;
  return result.hit;
}

}  // namespace rules

namespace detail {

bool ccd(const char* call, Kind kind, std::span<const PointArgument> points, double& toi, double min_distance,
         double tmax, double tolerance, long max_iterations, double conservative_rescaling) {
  const Query query = batchccd::detail::query_from_points(call, kind, points);
  rules::require_arguments(call, min_distance, tmax, tolerance, conservative_rescaling);
  return rules::decide(kind, query, toi, min_distance, tmax, tolerance, max_iterations, conservative_rescaling);
}

}  // namespace detail
}  // namespace batchccd::ipc

#include "batchccd/ipc.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <string>

#include "batchccd/ccd.hpp"
#include "fronts.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::ipc {
namespace {

// ipc-toolkit's constants around Tight Inclusion (ipc/ccd/ccd.cpp,
// ipc/ccd/tight_inclusion_ccd.cpp).
constexpr double kInitialDistanceToleranceScale = 0.5;
constexpr double kLargestRescalingSeparation = 1e-4;
constexpr double kSmallToi = 1e-6;

bool moves(const Query& query) {
  for (int k = 0; k < 4; ++k)
    if (query.points[k] != query.points[k + 4]) return true;
  return false;
}

QueryResult ask(Kind kind, const Query& query, double min_distance, double distance_tolerance, double tmax,
                long max_iterations) {
  Options options = fronts::conservative_options(query, distance_tolerance, max_iterations);
  options.tmax = tmax;
  options.min_distance = min_distance;
  return query_ccd(kind, query, options);
}

void require_lengths(const char* call, Kind kind, std::span<const detail::PointArgument> points) {
  const bool planar_allowed = kind == Kind::vertex_edge || kind == Kind::vertex_vertex;
  const detail::PointArgument& first = points.front();
  const bool first_fits = first.length == 3 || (planar_allowed && first.length == 2);
  fronts::require(first_fits, call, first.name, planar_allowed ? "of length 2 or 3" : "of length 3",
                  static_cast<double>(first.length));
  const std::string like_first = "of length " + std::to_string(first.length) + " like " + first.name;
  for (const detail::PointArgument& argument : points)
    fronts::require(argument.length == first.length, call, argument.name, like_first.c_str(),
                    static_cast<double>(argument.length));
}

}  // namespace

namespace detail {

bool ccd(const char* call, Kind kind, std::span<const PointArgument> points, double& toi, double min_distance,
         double tmax, double tolerance, long max_iterations, double conservative_rescaling) {
  const std::size_t per_time = static_cast<std::size_t>(points_per_time(kind));
  assert(points.size() == 2 * per_time);
  require_lengths(call, kind, points);
  fronts::require(min_distance >= 0 && std::isfinite(min_distance), call, "min_distance", ">= 0 and finite",
                  min_distance);
  fronts::require(tmax >= 0 && tmax <= 1, call, "tmax", "in [0, 1]", tmax);
  fronts::require(tolerance > 0 && std::isfinite(tolerance), call, "tolerance", "positive and finite", tolerance);
  fronts::require(conservative_rescaling > 0 && conservative_rescaling <= 1, call, "conservative_rescaling",
                  "in (0, 1]", conservative_rescaling);

  std::array<Vec3, 4> at_t0, at_t1;
  for (std::size_t k = 0; k < per_time; ++k) {
    at_t0[k] = points[k].point;
    at_t1[k] = points[per_time + k].point;
  }
  const Query query = make_query(kind, std::span<const Vec3>(at_t0.data(), per_time),
                                 std::span<const Vec3>(at_t1.data(), per_time));

  if (!reference::all_finite(query)) {  // never step into what cannot be checked
    toi = 0;
    return true;
  }
  if (!moves(query)) return false;
  const double initial_distance = std::sqrt(squared_distance(kind, query, 0));
  if (initial_distance <= min_distance) {
    toi = 0;
    return true;
  }
  if (tmax == 0) return false;

  const double distance_tolerance = std::min(kInitialDistanceToleranceScale * initial_distance, tolerance);
  const double effective_separation =
      std::min((1 - conservative_rescaling) * initial_distance, kLargestRescalingSeparation) + min_distance;
  QueryResult result = ask(kind, query, effective_separation, distance_tolerance, tmax, max_iterations);
  if (result.hit && result.toi < kSmallToi) {
    // Too close to step: the separation alone, the step rescaled instead.
    result = ask(kind, query, min_distance, distance_tolerance, tmax, max_iterations);
    result.toi *= conservative_rescaling;
  }
  if (result.hit) toi = result.toi;
  return result.hit;
}

}  // namespace detail
}  // namespace batchccd::ipc

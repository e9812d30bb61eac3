#include "batchccd/tight_inclusion.hpp"

#include <cmath>
#include <limits>

#include "batchccd/ccd.hpp"
#include "fronts.hpp"

namespace batchccd::ticcd::detail {

bool decide(const char* call, Kind kind, std::span<const batchccd::detail::PointArgument> points, double ms,
            double& toi, double tolerance, double t_max, long max_itr, double& output_tolerance) {
  const Query query = batchccd::detail::query_from_points(call, kind, points);
  fronts::require(ms >= 0 && std::isfinite(ms), call, "ms", ">= 0 and finite", ms);
  fronts::require(t_max > 0 && t_max <= 1, call, "t_max", "in (0, 1]", t_max);
  fronts::require(tolerance > 0 && std::isfinite(tolerance), call, "tolerance", "positive and finite", tolerance);
  Options options = fronts::conservative_options(query, tolerance, max_itr);
  options.min_distance = ms;
  options.tmax = t_max;
  const QueryResult result = query_ccd(kind, query, options);
  output_tolerance = tolerance;
  toi = result.hit ? result.toi : std::numeric_limits<double>::infinity();
  return result.hit;
}

}  // namespace batchccd::ticcd::detail

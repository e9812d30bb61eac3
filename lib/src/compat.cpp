#include "batchccd/compat.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "batchccd/ccd.hpp"

namespace batchccd::compat {
namespace {

void check_arguments(double tmax, double tolerance) {
  if (!(tmax >= 0.0 && tmax <= 1.0))  // also rejects NaN
    throw std::invalid_argument("batchccd::compat: tmax must be in [0, 1], got " +
                                std::to_string(tmax));
  if (!(tolerance > 0.0 && std::isfinite(tolerance)))
    throw std::invalid_argument("batchccd::compat: tolerance must be positive and finite, got " +
                                std::to_string(tolerance));
}

// Largest spread of one coordinate over the four points at t0 or at t1. It is
// never below the size the solver scales the query by (scale_query: the
// largest rounded difference from the first point, rounding is monotone), so
// tolerance / extent, applied relative to that size, stays within tolerance.
double coordinate_extent(const Query& query) {
  double extent = 0;
  for (int time = 0; time < 2; ++time)
    for (int axis = 0; axis < 3; ++axis) {
      double low = query.points[4 * time][axis], high = low;
      for (int k = 1; k < 4; ++k) {
        low = std::min(low, query.points[4 * time + k][axis]);
        high = std::max(high, query.points[4 * time + k][axis]);
      }
      extent = std::max(extent, high - low);
    }
  return extent;
}

Options options_for(const Query& query, double tolerance, std::int64_t max_iterations) {
  Options options;  // conservative, TOI wanted
  const double extent = coordinate_extent(query);
  if (extent > 0 && std::isfinite(extent))  // otherwise the query needs no tolerance
    options.tolerance = std::nextafter(tolerance / extent, 0.0);  // rounded down
  options.max_iterations =
      max_iterations < 0 ? std::numeric_limits<std::int64_t>::max() : max_iterations;
  return options;
}

bool solve(Kind kind, const Query& query, double& toi, double tmax, double tolerance,
           std::int64_t max_iterations) {
  check_arguments(tmax, tolerance);
  const QueryResult result = query_ccd(kind, query, options_for(query, tolerance, max_iterations));
  // result.toi is a lower bound of the first contact over the whole step, in
  // the caller's time units already: a contact counts when it starts by tmax.
  if (result.hit && result.toi <= tmax) {
    toi = result.toi;
    return true;
  }
  toi = std::numeric_limits<double>::infinity();
  return false;
}

}  // namespace

bool vertex_face_ccd(const Vec3& p_t0, const Vec3& a_t0, const Vec3& b_t0, const Vec3& c_t0,
                     const Vec3& p_t1, const Vec3& a_t1, const Vec3& b_t1, const Vec3& c_t1,
                     double& toi, double tmax, double tolerance, std::int64_t max_iterations) {
  return solve(Kind::vertex_face, {{p_t0, a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1}}, toi, tmax,
               tolerance, max_iterations);
}

bool edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0,
                   const Vec3& eb1_t0, const Vec3& ea0_t1, const Vec3& ea1_t1,
                   const Vec3& eb0_t1, const Vec3& eb1_t1, double& toi, double tmax,
                   double tolerance, std::int64_t max_iterations) {
  return solve(Kind::edge_edge,
               {{ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1}}, toi, tmax,
               tolerance, max_iterations);
}

}  // namespace batchccd::compat

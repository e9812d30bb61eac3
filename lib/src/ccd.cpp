#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"

#include <array>
#include <cassert>
#include <string>

#include "fronts.hpp"
#include "reference/closest_distance.hpp"
#include "reference/reference.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd {

QueryResult lab::query_ccd(Kind kind, const Query& query, const Options& options, const Settings& settings) {
  validate(options, settings);
  return reference::evaluate_query(kind, query, options, settings).result;
}

QueryResult query_ccd(Kind kind, const Query& query, const Options& options) {
  return lab::query_ccd(kind, query, options, {});
}

namespace detail {

Query query_from_points(const char* call, Kind kind, std::span<const PointArgument> points) {
  const std::size_t per_time = static_cast<std::size_t>(points_per_time(kind));
  assert(points.size() == 2 * per_time);
  const bool planar_allowed = kind == Kind::vertex_edge || kind == Kind::vertex_vertex;
  const PointArgument& first = points.front();
  const bool first_fits = first.length == 3 || (planar_allowed && first.length == 2);
  fronts::require(first_fits, call, first.name, planar_allowed ? "of length 2 or 3" : "of length 3",
                  static_cast<double>(first.length));
  const std::string like_first = "of length " + std::to_string(first.length) + " like " + first.name;
  for (const PointArgument& argument : points)
    fronts::require(argument.length == first.length, call, argument.name, like_first.c_str(),
                    static_cast<double>(argument.length));
  std::array<Vec3, 4> at_t0, at_t1;
  for (std::size_t k = 0; k < per_time; ++k) {
    at_t0[k] = points[k].point;
    at_t1[k] = points[per_time + k].point;
  }
  return make_query(kind, std::span<const Vec3>(at_t0.data(), per_time),
                    std::span<const Vec3>(at_t1.data(), per_time));
}

}  // namespace detail

double squared_distance(Kind kind, const Query& query, double t) {
  std::array<reference::Point<double>, 4> x;
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = (1 - t) * query.points[k] + t * query.points[k + 4];
    x[k] = {p.x(), p.y(), p.z()};
  }
  return reference::squared_distance(kind == Kind::vertex_face, x);
}

}  // namespace batchccd

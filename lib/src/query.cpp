#include "batchccd/query.hpp"

#include <stdexcept>
#include <string>

namespace batchccd {

int points_per_time(Kind kind) {
  switch (kind) {
    case Kind::vertex_edge: return 3;
    case Kind::vertex_vertex: return 2;
    default: return 4;
  }
}

namespace {

template <class QueryType, class Point>
QueryType query_from(Kind kind, std::span<const Point> points_t0, std::span<const Point> points_t1) {
  const std::size_t count = static_cast<std::size_t>(points_per_time(kind));
  if (points_t0.size() != count || points_t1.size() != count)
    throw std::invalid_argument(std::string("make_query: a ") + to_string(kind) + " query takes " +
                                std::to_string(count) + " points at t0 and at t1, got " +
                                std::to_string(points_t0.size()) + " and " +
                                std::to_string(points_t1.size()));
  // Which given point fills each of a time's four slots (Query's layout).
  static constexpr int kSlots[4][4] = {{0, 1, 2, 3}, {0, 1, 2, 3}, {0, 0, 1, 2}, {0, 0, 1, 1}};
  const int(&slots)[4] = kSlots[static_cast<int>(kind)];
  QueryType query;
  for (int k = 0; k < 4; ++k) {
    query.points[k] = points_t0[slots[k]];
    query.points[4 + k] = points_t1[slots[k]];
  }
  return query;
}

}  // namespace

Query make_query(Kind kind, std::span<const Vec3> points_t0, std::span<const Vec3> points_t1) {
  return query_from<Query>(kind, points_t0, points_t1);
}

Query2D make_query(Kind kind, std::span<const Vec2> points_t0, std::span<const Vec2> points_t1) {
  return query_from<Query2D>(kind, points_t0, points_t1);
}

Query lifted(const Query2D& query) {
  Query spatial;
  for (int k = 0; k < 8; ++k) spatial.points[k] = {query.points[k].x(), query.points[k].y(), 0.0};
  return spatial;
}

}  // namespace batchccd

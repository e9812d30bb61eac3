#pragma once

// Queries as several suites build them (a mesh's candidates as queries of
// their kinds), and the transforms that describe the same motion another
// way, so that an exact answer stays the same (the TOI too, but under time
// reversal): scaling by a power of two, axes permuted or flipped, a
// translation (exact where the sums are), time reversed, the points listed
// in another equivalent order.

#include <array>
#include <cmath>
#include <initializer_list>
#include <utility>
#include <vector>

#include "batchccd/batch.hpp"
#include "batchccd/query.hpp"

namespace batchccd::testing {

// Points at t0 and t1 in the order of Query (VF: p, a, b, c; EE: ea0, ea1,
// eb0, eb1).
inline Query from_points(const Vec3& x0, const Vec3& y0, const Vec3& z0, const Vec3& w0, const Vec3& x1,
                         const Vec3& y1, const Vec3& z1, const Vec3& w1) {
  return Query{{x0, y0, z0, w0, x1, y1, z1, w1}};
}

struct KindQuery {
  Kind kind;
  Query query;
};

// Every candidate of a mesh (3D or 2D, every kind) as the query it names,
// in mesh_ccd's order: vertex-face, edge-edge, vertex-edge, vertex-vertex.
inline std::vector<KindQuery> candidate_queries(const MeshView& mesh, const CandidateLists& candidates) {
  const auto at = [&](const PositionsView& positions, int v) {
    Vec3 point = Vec3::Zero();
    for (int c = 0; c < positions.cols(); ++c) point[c] = positions(v, c);
    return point;
  };
  const auto query = [&](Kind kind, std::initializer_list<int> ids) {
    std::vector<Vec3> t0, t1;
    for (const int v : ids) {
      t0.push_back(at(mesh.positions_t0, v));
      t1.push_back(at(mesh.positions_t1, v));
    }
    return KindQuery{kind, make_query(kind, t0, t1)};
  };
  std::vector<KindQuery> all;
  for (const auto& [v, f] : candidates.vertex_face)
    all.push_back(query(Kind::vertex_face, {v, mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)}));
  for (const auto& [a0, a1, b0, b1] : candidates.edge_edge) all.push_back(query(Kind::edge_edge, {a0, a1, b0, b1}));
  for (const auto& [p, e0, e1] : candidates.vertex_edge) all.push_back(query(Kind::vertex_edge, {p, e0, e1}));
  for (const auto& [p, q] : candidates.vertex_vertex) all.push_back(query(Kind::vertex_vertex, {p, q}));
  return all;
}

// Points that do not move.
inline Query at_rest(const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& w) {
  return from_points(x, y, z, w, x, y, z, w);
}

// Every coordinate times 2^exponent (rounded where it leaves the doubles).
inline Query scaled(Query query, int exponent) {
  for (Vec3& point : query.points)
    for (int axis = 0; axis < 3; ++axis) point[axis] = std::ldexp(point[axis], exponent);
  return query;
}

// New axis k is old axis order[k].
inline Query axes_permuted(Query query, const std::array<int, 3>& order) {
  for (Vec3& point : query.points) point = Vec3(point[order[0]], point[order[1]], point[order[2]]);
  return query;
}

// Axis k negated where bit k of mask is set.
inline Query axes_flipped(Query query, int mask) {
  for (Vec3& point : query.points)
    for (int axis = 0; axis < 3; ++axis)
      if (mask & (1 << axis)) point[axis] = -point[axis];
  return query;
}

inline Query translated(Query query, const Vec3& offset) {
  for (Vec3& point : query.points) point += offset;
  return query;
}

// t0 and t1 swapped: a contact at t happens at 1 - t.
inline Query time_reversed(Query query) {
  for (int k = 0; k < 4; ++k) std::swap(query.points[k], query.points[k + 4]);
  return query;
}

// New point k (at t0; t1 alike) is old point order[k].
inline Query reordered(const Query& query, const std::array<int, 4>& order) {
  Query result;
  for (int k = 0; k < 4; ++k) {
    result.points[k] = query.points[order[k]];
    result.points[k + 4] = query.points[order[k] + 4];
  }
  return result;
}

}  // namespace batchccd::testing

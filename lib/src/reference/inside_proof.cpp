#include "reference/inside_proof.hpp"

#include <algorithm>

namespace batchccd::reference {
namespace {

using BallVector = Vector3<Ball>;

// With x1 at the origin: a = 0, b = x2, c = x3, p = x4, n = b x c. At a time
// where p lies in the triangle's plane, p is inside iff all three
// e_k = (edge_k x (p - start_k)) . n are >= 0 (each is |n|^2 times a
// barycentric coordinate).
std::array<Ball, 3> edge_functions(const PositionBalls& x) {
  const BallVector &b = x[0], &c = x[1], &p = x[2];
  const BallVector normal = cross(b, c);
  return {dot(cross(b, p), normal), dot(cross(c - b, p - b), normal), dot(cross(p, c), normal)};
}

// With x1 = ea0 at the origin: edge a is (0, x2), edge b (x3, x4). Where the
// lines are coplanar they meet at ea0 + u da = eb0 + v db with
// u = ((eb0 x db) . n) / |n|^2, v = ((eb0 x da) . n) / |n|^2, n = da x db.
// The meeting point's parameters times |n|^2, each with its distance to
// the far end: u, |n|^2 - u, v, |n|^2 - v.
std::array<Ball, 4> edge_parameters(const PositionBalls& x) {
  const BallVector &direction_a = x[0], &start_b = x[1];
  const BallVector direction_b = x[2] - x[1];
  const BallVector normal = cross(direction_a, direction_b);
  const Ball normal_squared = dot(normal, normal);
  const Ball u = dot(cross(start_b, direction_b), normal);
  const Ball v = dot(cross(start_b, direction_a), normal);
  return {u, normal_squared - u, v, normal_squared - v};
}

template <std::size_t n>
bool all_positive(const std::array<Ball, n>& values) {
  return std::all_of(values.begin(), values.end(), [](const Ball& x) { return x.certainly_positive(); });
}
template <std::size_t n>
bool any_negative(const std::array<Ball, n>& values) {
  return std::any_of(values.begin(), values.end(), [](const Ball& x) { return x.certainly_negative(); });
}

}  // namespace

bool certainly_inside(Kind kind, const PositionBalls& positions) {
  return kind == Kind::vertex_face ? all_positive(edge_functions(positions)) : all_positive(edge_parameters(positions));
}

bool certainly_outside(Kind kind, const PositionBalls& positions) {
  return kind == Kind::vertex_face ? any_negative(edge_functions(positions)) : any_negative(edge_parameters(positions));
}

}  // namespace batchccd::reference

#include "reference/inside_proof.hpp"

namespace batchccd::reference {
namespace {

using BallVector = Vector3<Ball>;

// With x1 at the origin: a = 0, b = x2, c = x3, p = x4, n = b x c. At a time
// where p lies in the triangle's plane, p is inside iff all three
// e_k = (edge_k x (p - start_k)) . n are >= 0 (each is |n|^2 times a
// barycentric coordinate).
bool vertex_inside_triangle(const PositionBalls& x) {
  const BallVector &b = x[0], &c = x[1], &p = x[2];
  const BallVector normal = cross(b, c);
  return dot(cross(b, p), normal).certainly_positive() &&
         dot(cross(c - b, p - b), normal).certainly_positive() &&
         dot(cross(p, c), normal).certainly_positive();
}

// With x1 = ea0 at the origin: edge a is (0, x2), edge b (x3, x4). Where the
// lines are coplanar they meet at ea0 + u da = eb0 + v db with
// u = ((eb0 x db) . n) / |n|^2, v = ((eb0 x da) . n) / |n|^2, n = da x db.
bool edges_cross(const PositionBalls& x) {
  const BallVector &direction_a = x[0], &start_b = x[1];
  const BallVector direction_b = x[2] - x[1];
  const BallVector normal = cross(direction_a, direction_b);
  const Ball normal_squared = dot(normal, normal);
  const Ball u = dot(cross(start_b, direction_b), normal);
  const Ball v = dot(cross(start_b, direction_a), normal);
  return u.certainly_positive() && (normal_squared - u).certainly_positive() &&
         v.certainly_positive() && (normal_squared - v).certainly_positive();
}

}  // namespace

bool certainly_inside(Kind kind, const PositionBalls& positions) {
  return kind == Kind::vertex_face ? vertex_inside_triangle(positions) : edges_cross(positions);
}

}  // namespace batchccd::reference

#include "reference/inside_proof.hpp"

namespace batchccd::reference {
namespace {

using BallVector = Vector3<Ball>;

// The quantities whose signs decide both proofs, each formed only when the
// ones before it left the proof open (a proof mostly settles at the first).
// `verdict` is called on each in turn until it returns true; returns whether
// one did.
//
// With x1 at the origin: a = 0, b = x2, c = x3, p = x4, n = b x c. At a time
// where p lies in the triangle's plane, p is inside iff all three
// e_k = (edge_k x (p - start_k)) . n are >= 0 (each is |n|^2 times a
// barycentric coordinate).
template <class Verdict>
bool any_edge_function(const PositionBalls& x, Verdict verdict) {
  const BallVector &b = x[0], &c = x[1], &p = x[2];
  const BallVector normal = cross(b, c);
  return verdict(dot(cross(b, p), normal)) || verdict(dot(cross(c - b, p - b), normal)) ||
         verdict(dot(cross(p, c), normal));
}

// With x1 = ea0 at the origin: edge a is (0, x2), edge b (x3, x4). Where the
// lines are coplanar they meet at ea0 + u da = eb0 + v db with
// u = ((eb0 x db) . n) / |n|^2, v = ((eb0 x da) . n) / |n|^2, n = da x db.
// The meeting point's parameters times |n|^2, each with its distance to
// the far end: u, |n|^2 - u, v, |n|^2 - v.
template <class Verdict>
bool any_edge_parameter(const PositionBalls& x, Verdict verdict) {
  const BallVector &direction_a = x[0], &start_b = x[1];
  const BallVector direction_b = x[2] - x[1];
  const BallVector normal = cross(direction_a, direction_b);
  const Ball u = dot(cross(start_b, direction_b), normal);
  if (verdict(u)) return true;
  const Ball normal_squared = dot(normal, normal);
  if (verdict(normal_squared - u)) return true;
  const Ball v = dot(cross(start_b, direction_a), normal);
  return verdict(v) || verdict(normal_squared - v);
}

template <class Verdict>
bool any_of_kind(Kind kind, const PositionBalls& positions, Verdict verdict) {
  return kind == Kind::vertex_face ? any_edge_function(positions, verdict) : any_edge_parameter(positions, verdict);
}

}  // namespace

bool certainly_inside(Kind kind, const PositionBalls& positions) {
  return !any_of_kind(kind, positions, [](const Ball& x) { return !x.certainly_positive(); });
}

bool certainly_outside(Kind kind, const PositionBalls& positions) {
  return any_of_kind(kind, positions, [](const Ball& x) { return x.certainly_negative(); });
}

}  // namespace batchccd::reference

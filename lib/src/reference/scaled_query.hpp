#pragma once

#include <array>

#include "batchccd/query.hpp"

namespace batchccd::reference {

// A query moved into the frame of its first point x1 (docs/design.md §1 numbering:
// VF x1..x3 the triangle, x4 the vertex; EE x1,x2 edge a, x3,x4 edge b) and
// scaled by powers of two (docs/design.md §3, "The scaled frame"):
//
//   relative[i][tau] = (x_{i+2}(tau) - x_1(tau)) * 2^scale,  i = 0, 1, 2
//
// Translating by the moving point x1(t) is exact in exact arithmetic (the
// relative motion stays linear), so x1 sits at the origin for all t. Every
// component carries at most one rounding (|error| <= u |value|, from the
// subtraction) plus an absolute floor `absolute_error` from underflow. The
// largest component lies in [1, 2), so nothing later overflows, and a query
// scaled by any power of two (within double range) maps to the same frame
// bit for bit: decisions and TOI do not depend on units.
struct ScaledQuery {
  std::array<std::array<Vec3, 2>, 3> relative;
  double absolute_error = 0;
  bool finite = true;      // false: some input coordinate is NaN or infinite
  bool coincident = false; // all four points coincide at t0 and t1
  // An input length l is (l * input_factor) * 2^exponent in this frame.
  double input_factor = 1;  // 1/4 for inputs near overflow
  int exponent = 0;
};

ScaledQuery scale_query(Kind kind, const Query& query);

// A length of the input's units (Options::min_distance) in the scaled
// frame of `query`: exact, but raised to 2^-1022 where it falls below
// (an upper bound then), +inf past the double range (where it exceeds
// every distance in the frame). The lane kernels compute it alike.
double to_scaled_length(const ScaledQuery& query, double length);

// Every coordinate finite (no NaN, no infinity).
bool all_finite(const Query& query);

// Inputs at least this large are quartered before the differences are taken
// (their differences could overflow); shared with the lane kernels.
inline constexpr double kHugeInput = 0x1p1022;

// The kind a query is evaluated as: point-edge and point-point queries are
// edge-edge queries with zero-length edges (Query's layout).
constexpr Kind evaluated_kind(Kind kind) {
  return kind == Kind::vertex_face ? Kind::vertex_face : Kind::edge_edge;
}

// Index of x_k (k = 1..4, docs/design.md §1) among Query::points at t0 (add 4 for t1).
// Always inlined: the lane kernels, compiled with other instruction sets,
// call it too, and an out-of-line copy from them must never be shared.
[[gnu::always_inline]] constexpr int point_index(Kind kind, int k) {
  // VF files list the vertex first: p, a, b, c; docs/design.md §1 numbers a, b, c, p.
  return kind == Kind::edge_edge ? k - 1 : (k == 4 ? 0 : k);
}

}  // namespace batchccd::reference

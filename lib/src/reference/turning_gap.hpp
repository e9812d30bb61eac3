#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "batchccd/query.hpp"
#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"

namespace batchccd::reference {

// Whether two primitives stay more than `min_distance` apart over a time
// interval along a direction that turns linearly over it
// (docs/design.md §11, the solver's turning step): n(s) = (1 - s) n0 + s n1
// for s in [0, 1] across the interval, with n0 at its start and n1 at its
// end, and the positions x2..x4 relative to x1 (the scaled frame's) at its
// start and end, the motion between linear.
//
// Along n(s) every point's projection is a quadratic in s, and the
// primitives lie more than min_distance apart when the gap between the
// side n points to ("upper": VF the vertex x4, EE edge a = x1 x2) and the
// other ("lower": the triangle x1 x2 x3, edge b = x3 x4) exceeds
// min_distance |n(s)|: for every upper-lower pair, the gap's Bernstein
// coefficients n0 . D0, (n0 . D1 + n1 . D0) / 2 and n1 . D1 (D the pair's
// difference at either end) against min_distance times the longer of n0
// and n1 (|n(s)| is convex, so at most that).
//
// Error model: each position may err by 3 u of `reach` (componentwise at
// least every position's magnitude over the interval, as interpolated
// positions at times on a 2^-45 grid do) plus `absolute_error` (the scaled
// frame's); a projection then errs by at most 8 u of |n| . reach plus the
// absolute error times |n|'s weight. 16 u also covers the at most seven
// roundings of a coefficient's sums, each at most u of the sum of its
// terms' magnitudes. `certified` false: plain signs (the fast baseline).
inline bool turning_apart(Kind kind, const Vector3<double>& n0, const std::array<Vector3<double>, 3>& at_start,
                          const Vector3<double>& n1, const std::array<Vector3<double>, 3>& at_end,
                          const std::array<Vector3<double>, 3>& reach, double absolute_error, double min_distance,
                          bool certified) {
  const double start_length = std::sqrt(dot(n0, n0)), end_length = std::sqrt(dot(n1, n1));
  const double longer = std::max(start_length, end_length) * (1 + 8 * kUnitRoundoff);
  if (!(longer > 0) || !std::isfinite(longer)) return false;
  const double threshold = min_distance * longer * (1 + 4 * kUnitRoundoff) + kUnderflowFloor;
  // projection[d][e][k]: direction d (0 start, 1 end) on the positions at
  // end e of point k (x1..x4; x1, the origin, projects to 0 exactly),
  // error[d][k] its error bound.
  double projection[2][2][4] = {}, error[2][4] = {};
  const Vector3<double>* directions[2] = {&n0, &n1};
  const std::array<Vector3<double>, 3>* positions[2] = {&at_start, &at_end};
  for (int d = 0; d < 2; ++d) {
    const Vector3<double>& n = *directions[d];
    const Vector3<double> magnitude{std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
    const double weight = magnitude.x + magnitude.y + magnitude.z;
    const double floor = certified ? weight * (absolute_error + 0x1p-1073) + kUnderflowFloor : 0;
    for (int k = 1; k < 4; ++k) {
      error[d][k] = certified ? 16 * kUnitRoundoff * dot(magnitude, reach[k - 1]) + floor : 0;
      for (int e = 0; e < 2; ++e) projection[d][e][k] = dot(n, (*positions[e])[k - 1]);
    }
  }
  // A lower bound of n_d . (x_upper - x_lower) at end e.
  const auto gap = [&](int d, int e, int upper, int lower) {
    return (projection[d][e][upper] - error[d][upper]) - (projection[d][e][lower] + error[d][lower]);
  };
  // Points 0..3 are x1..x4: VF upper {3}, lower {0, 1, 2}; EE upper {0, 1}, lower {2, 3}.
  const bool vertex_face = kind == Kind::vertex_face;
  for (int upper = 0; upper < 4; ++upper)
    for (int lower = 0; lower < 4; ++lower) {
      const bool pair = vertex_face ? upper == 3 && lower < 3 : upper < 2 && lower >= 2;
      if (!pair) continue;
      if (!(gap(0, 0, upper, lower) > threshold) || !(gap(1, 1, upper, lower) > threshold) ||
          !(gap(0, 1, upper, lower) + gap(1, 0, upper, lower) > 2 * threshold))
        return false;
    }
  return true;
}

}  // namespace batchccd::reference

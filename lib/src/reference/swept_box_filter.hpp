#pragma once

#include "batchccd/query.hpp"
#include "reference/error_bounds.hpp"
#include "reference/separation_filter.hpp"

// The first lane filter (docs/design.md §4): the swept boxes of the two
// primitives in the frame of x1, where every point still moves on a line,
// so each primitive stays within the box of its points at t = 0 and t = 1.
// Apart along an axis (by more than the separation s), no contact. Tighter
// than a broad phase's world boxes wherever the primitives move together,
// and comparisons only. Written once over T (double, or an xsimd batch),
// in either frame (docs/design.md §3).
namespace batchccd::reference {

// Without a separation the comparisons are exact: every coordinate of the
// frame is a monotonic function of the input's (differences, quartering,
// scaling by powers of two, each rounded), so fl(x - a) > fl(y - b)
// implies x - a > y - b. With one the gap is taken with a margin: each
// coordinate errs by at most u of `overall` (the largest coordinate
// magnitude) plus the frame's absolute error, the gap's subtraction by u
// of itself.
template <class T>
auto swept_boxes_apart(Kind kind, const Vector3<T> (&relative)[3][2], T overall, bool within, T separation,
                       T absolute_error = T(0)) {
  // VF: the face (x1, x2, x3) against the vertex x4; EE: edge (x1, x2) against edge (x3, x4).
  const int first_other = kind == Kind::vertex_face ? 2 : 1;
  const T threshold = within ? (separation + T(8 * kUnitRoundoff) * overall + T(4) * absolute_error) *
                                   T(SeparationErrors::grow)
                             : T(0);
  const auto apart_along = [&](auto coordinate) {
    T low_a(0), high_a(0);  // x1 itself
    T low_b = coordinate(relative[first_other][0]), high_b = low_b;
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) {
        const T x = coordinate(relative[i][tau]);
        if (i < first_other) {
          low_a = min_of(x, low_a), high_a = max_of(x, high_a);
        } else {
          low_b = min_of(x, low_b), high_b = max_of(x, high_b);
        }
      }
    return ((low_b - high_a) > threshold) | ((low_a - high_b) > threshold);
  };
  return apart_along([](const Vector3<T>& v) { return v.x; }) | apart_along([](const Vector3<T>& v) { return v.y; }) |
         apart_along([](const Vector3<T>& v) { return v.z; });
}

}  // namespace batchccd::reference

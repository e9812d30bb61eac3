#pragma once

#include "batchccd/query.hpp"
#include "reference/error_bounds.hpp"
#include "reference/separation_filter.hpp"

// The first lane filter (docs/design.md §2a): the swept boxes of the two
// primitives in the frame of x1, where every point still moves on a line,
// so each primitive stays within the box of its points at t = 0 and t = 1.
// Apart along an axis (by more than the separation s), no contact. Tighter
// than a broad phase's world boxes wherever the primitives move together,
// and comparisons only. Written once over T (double, or an xsimd batch),
// in either frame (docs/design.md §3).
namespace batchccd::reference {

// The boxes, axis by axis: the first primitive's (VF: the face x1, x2, x3;
// EE: the edge x1, x2) and the other's (the vertex x4; the edge x3, x4),
// both in the frame of x1, so the first holds the origin. Their six gaps
// (two an axis) are reduced to the widest before one comparison: for boxes
// without a NaN the same verdict as six (the filters test NaN-free boxes
// alone).
template <class T>
struct SweptBoxes {
  T widest;  // the widest gap along an axis (negative where the boxes overlap on all three)
  // The largest coordinate magnitude of the six differences, exact: every
  // coordinate lies in its axis's boxes, which reach their extremes and,
  // holding the origin, span zero, so it is the largest of the highs and
  // of the negated lows (max, min and negation round nothing). For input
  // without a NaN the frame's `overall` (reference::largest_magnitude's
  // largest), which the lanes then need not measure before the boxes.
  T largest;

  // The gap the boxes must leave. Without a separation the comparisons are
  // exact: every coordinate of the frame is a monotonic function of the
  // input's (differences, quartering, scaling by powers of two, each
  // rounded), so fl(x - a) > fl(y - b) implies x - a > y - b. With one the
  // gap is taken with a margin: each coordinate errs by at most u of
  // `largest` plus the frame's absolute error, the gap's subtraction by u
  // of itself.
  T threshold(bool within, T separation, T absolute_error = T(0)) const {
    return within ? (separation + T(8 * kUnitRoundoff) * largest + T(4) * absolute_error) * T(SeparationErrors::grow)
                  : T(0);
  }
  auto apart(bool within, T separation, T absolute_error = T(0)) const {
    return widest > threshold(within, separation, absolute_error);
  }
};

template <class T>
SweptBoxes<T> swept_boxes(Kind kind, const Vector3<T> (&relative)[3][2]) {
  const int first_other = kind == Kind::vertex_face ? 2 : 1;
  T widest(0), highest(0), lowest(0);
  for (int axis = 0; axis < 3; ++axis) {
    const auto coordinate = [axis](const Vector3<T>& v) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
    T low_a(0), high_a(0);  // x1 itself
    for (int i = 0; i < first_other; ++i)
      for (int tau = 0; tau < 2; ++tau)
        low_a = min_of(coordinate(relative[i][tau]), low_a), high_a = max_of(coordinate(relative[i][tau]), high_a);
    T low_b = coordinate(relative[first_other][0]), high_b = low_b;
    for (int i = first_other; i < 3; ++i)
      for (int tau = i == first_other ? 1 : 0; tau < 2; ++tau)
        low_b = min_of(coordinate(relative[i][tau]), low_b), high_b = max_of(coordinate(relative[i][tau]), high_b);
    const T gap = max_of(low_b - high_a, low_a - high_b);
    widest = axis == 0 ? gap : max_of(widest, gap);
    highest = max_of(highest, max_of(high_a, high_b));
    lowest = min_of(lowest, min_of(low_a, low_b));
  }
  return {widest, max_of(highest, -lowest)};
}

template <class T>
auto swept_boxes_apart(Kind kind, const Vector3<T> (&relative)[3][2], bool within, T separation,
                       T absolute_error = T(0)) {
  return swept_boxes(kind, relative).apart(within, separation, absolute_error);
}

}  // namespace batchccd::reference

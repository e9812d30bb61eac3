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

// The boxes themselves, axis by axis: the first primitive's (VF: the face
// x1, x2, x3; EE: the edge x1, x2) and the other's (the vertex x4; the edge
// x3, x4), both in the frame of x1, so the first holds the origin.
template <class T>
struct SweptBoxes {
  T low_a[3], high_a[3], low_b[3], high_b[3];

  SweptBoxes(Kind kind, const Vector3<T> (&relative)[3][2]) {
    const int first_other = kind == Kind::vertex_face ? 2 : 1;
    for (int axis = 0; axis < 3; ++axis) {
      const auto coordinate = [axis](const Vector3<T>& v) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
      T low(0), high(0);  // x1 itself
      for (int i = 0; i < first_other; ++i)
        for (int tau = 0; tau < 2; ++tau)
          low = min_of(coordinate(relative[i][tau]), low), high = max_of(coordinate(relative[i][tau]), high);
      low_a[axis] = low, high_a[axis] = high;
      low = high = coordinate(relative[first_other][0]);
      for (int i = first_other; i < 3; ++i)
        for (int tau = i == first_other ? 1 : 0; tau < 2; ++tau)
          low = min_of(coordinate(relative[i][tau]), low), high = max_of(coordinate(relative[i][tau]), high);
      low_b[axis] = low, high_b[axis] = high;
    }
  }

  // Apart by more than `threshold` along some axis: the widest gap taken
  // first, one comparison instead of six. For boxes without a NaN the same
  // verdict as six (the filters test boxes of NaN-free differences alone).
  auto apart(T threshold) const {
    T widest = max_of(low_b[0] - high_a[0], low_a[0] - high_b[0]);
    for (int axis = 1; axis < 3; ++axis)
      widest = max_of(widest, max_of(low_b[axis] - high_a[axis], low_a[axis] - high_b[axis]));
    return widest > threshold;
  }
};

// The gap the boxes must leave. Without a separation the comparisons are
// exact: every coordinate of the frame is a monotonic function of the
// input's (differences, quartering, scaling by powers of two, each
// rounded), so fl(x - a) > fl(y - b) implies x - a > y - b. With one the
// gap is taken with a margin: each coordinate errs by at most u of
// `overall` (the largest coordinate magnitude) plus the frame's absolute
// error, the gap's subtraction by u of itself.
template <class T>
T swept_box_threshold(bool within, T separation, T overall, T absolute_error = T(0)) {
  if (!within) return T(0);
  return (separation + T(8 * kUnitRoundoff) * overall + T(4) * absolute_error) * T(SeparationErrors::grow);
}

template <class T>
auto swept_boxes_apart(Kind kind, const Vector3<T> (&relative)[3][2], T overall, bool within, T separation,
                       T absolute_error = T(0)) {
  return SweptBoxes<T>(kind, relative).apart(swept_box_threshold(within, separation, overall, absolute_error));
}

}  // namespace batchccd::reference

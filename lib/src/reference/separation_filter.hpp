#pragma once

#include <cmath>

#include "batchccd/query.hpp"
#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"

// The second lane filter (docs/design.md §4, separation against motion): a
// query cannot touch in [0, 1] when the distance between its primitives at
// t = 0 exceeds the largest relative displacement of their vertices, because
// any two points of them (fixed barycentric or edge parameters) move
// relative to each other by at most that much. Both sides are certified:
// a lower bound of the squared distance against an upper bound of the
// squared displacement. Written once over T (double, or an xsimd batch in
// the lane kernels), branch-free, in the frame of ScaledQuery (x1 at the
// origin for all t).
//
// The distance bound: along the common normal n (triangle normal, or the
// two edge directions' cross product), plus in the plane normal to n the
// largest gap along a few in-plane axes (VF: the three edges' outward
// normals; EE: both edges' in-plane normals and both directions). The two
// parts are orthogonal, so their squares add.
namespace batchccd::reference {

template <class T>
struct Bounded {
  T value;
  T magnitude;  // the same expression over absolute values (error scale)
};

// Certified-lower-bound arithmetic for the separation test: every quantity
// derived from the scaled positions has at most 21 roundings on any term's
// path (counted in separation_filter_culls' comments), bounded by 64 u.
struct SeparationErrors {
  static constexpr double relative = 64 * kUnitRoundoff;
  static constexpr double shrink = 1 - 8 * kUnitRoundoff;  // a squared ratio's rounding
  static constexpr double grow = 1 + 8 * kUnitRoundoff;
  // Absolute floor of every bound, for underflow: bounds are taken on
  // expressions of degree <= 6 with fewer than 2^10 terms, so an underflow
  // (at most 2^-1074) magnified by at most five later factors stays below
  // 2^-864 as long as the factors stay below 2^42 (four times the largest
  // difference, the largest sum of two, in either frame below).
  static constexpr double floor = 0x1p-800;
};

// The filter may run on a query's differences in its own units (no scaled
// frame: the same decisions up to the floor, as scaling by a power of two
// is exact) when the largest difference component lies in this window:
// above, factors could magnify an underflow past the floor; below, the
// floor would start to cost culls. Differences of doubles carry one
// rounding and no absolute error (a difference that underflows is exact).
inline constexpr double kSeparationDirectLowest = 0x1p-40;
inline constexpr double kSeparationDirectHighest = 0x1p40;

// A lower bound of max(0, numerator)^2 / denominator (denominator >= 0 in
// exact arithmetic), given their magnitudes, kept as its two parts: the
// division is the filter's dearest operation, and of several axes' bounds
// only the largest is divided out (largest_ratio). `floor` is the absolute
// error floor of both. With `signed_gap` false |numerator| counts instead.
template <class T>
struct RatioBound {
  T excess;  // a lower bound of the numerator, or 0
  T room;    // an upper bound of the denominator, or 1 (with excess 0)

  T value() const { return excess * excess / room * T(SeparationErrors::shrink); }
};

template <class T>
RatioBound<T> squared_ratio_bound(const Bounded<T>& numerator, const Bounded<T>& denominator, T relative,
                                  T floor, bool signed_gap) {
  using std::abs;
  const T excess = (signed_gap ? numerator.value : abs(numerator.value)) -
                   (relative * numerator.magnitude + floor);
  const T room = denominator.value + (relative * denominator.magnitude + floor);
  const auto bounded = (excess > T(0)) & (room > T(0));
  return {select(bounded, excess, T(0)), select(bounded, room, T(1))};
}

// Of two bounds, the one with the larger ratio, compared by
// cross-multiplication. A comparison that rounding gets wrong only picks
// the other bound, which holds as well.
template <class T>
RatioBound<T> larger_ratio(const RatioBound<T>& a, const RatioBound<T>& b) {
  const auto b_larger = b.excess * b.excess * a.room > a.excess * a.excess * b.room;
  return {select(b_larger, b.excess, a.excess), select(b_larger, b.room, a.room)};
}

template <class T>
T squared_ratio_lower_bound(const Bounded<T>& numerator, const Bounded<T>& denominator, T relative,
                            T floor, bool signed_gap) {
  return squared_ratio_bound(numerator, denominator, relative, floor, signed_gap).value();
}

// An upper bound of |w|^2 for a difference w of scaled positions whose
// terms add up to `magnitude` (componentwise), with absolute floor `floor`.
template <class T>
T squared_norm_upper_bound(const Vector3<T>& w, const Vector3<T>& magnitude, T relative, T floor) {
  using std::abs;
  const T x = abs(w.x) + (relative * magnitude.x + floor);
  const T y = abs(w.y) + (relative * magnitude.y + floor);
  const T z = abs(w.z) + (relative * magnitude.z + floor);
  return (x * x + y * y + z * z) * T(SeparationErrors::grow);
}

// Squared gap between the intervals spanned by two pairs of projections
// onto an axis of squared length axis2: a lower bound (0 when they overlap).
template <class T>
RatioBound<T> squared_gap_bound(const Bounded<T> (&a)[2], const Bounded<T> (&b)[2], const Bounded<T>& axis2,
                                T relative, T floor) {
  const T a_low = min_of(a[0].value, a[1].value), a_high = max_of(a[1].value, a[0].value);
  const T b_low = min_of(b[0].value, b[1].value), b_high = max_of(b[1].value, b[0].value);
  const T magnitude =
      max_of(max_of(a[0].magnitude, a[1].magnitude), max_of(b[0].magnitude, b[1].magnitude));
  // Each end may be off by its error: the gap by twice the largest.
  const Bounded<T> gap{max_of(b_low - a_high, a_low - b_high), T(2) * magnitude};
  return squared_ratio_bound(gap, axis2, relative, T(2) * floor, true);
}

template <class T>
Bounded<T> bounded_dot(const Vector3<T>& a, const Vector3<T>& a_magnitude, const Vector3<T>& b,
                       const Vector3<T>& b_magnitude) {
  return {dot(a, b), dot(a_magnitude, b_magnitude)};
}

// Squared distance at t = 0, lower bound: vertex x4 against triangle (0, x2, x3).
// bm, cm, pm: componentwise bounds of |b|, |c|, |p| that the inputs' errors
// are measured against (their absolute values, for differences of doubles).
template <class T>
T vertex_face_distance2(const Vector3<T>& b, const Vector3<T>& bm, const Vector3<T>& c, const Vector3<T>& cm,
                        const Vector3<T>& p, const Vector3<T>& pm, T relative, T floor) {
  const Vector3<T> zero{T(0), T(0), T(0)};
  const Vector3<T> n = cross(b, c), nm = cross_magnitude(bm, cm);
  const Bounded<T> n2 = bounded_dot(n, nm, n, nm);
  const T plane = squared_ratio_lower_bound(bounded_dot(n, nm, p, pm), n2, relative, floor, false);
  // Edge k from start to end; m = edge x n points away from the triangle.
  const Vector3<T>* starts[3] = {&zero, &b, &c};
  const Vector3<T>* ends[3] = {&b, &c, &zero};
  const Vector3<T>* start_magnitudes[3] = {&zero, &bm, &cm};
  const Vector3<T>* end_magnitudes[3] = {&bm, &cm, &zero};
  RatioBound<T> in_plane{T(0), T(1)};
  for (int k = 0; k < 3; ++k) {
    const Vector3<T>& start = *starts[k];
    const Vector3<T>& start_magnitude = *start_magnitudes[k];
    const Vector3<T> edge = *ends[k] - start, edge_magnitude = *end_magnitudes[k] + start_magnitude;
    const Vector3<T> m = cross(edge, n), mm = cross_magnitude(edge_magnitude, nm);
    const Bounded<T> outside = bounded_dot(p - start, pm + start_magnitude, m, mm);
    in_plane = larger_ratio(in_plane, squared_ratio_bound(outside, bounded_dot(m, mm, m, mm), relative, floor, true));
  }
  return plane + in_plane.value();
}
template <class T>
T vertex_face_distance2(const Vector3<T>& b, const Vector3<T>& c, const Vector3<T>& p, T relative,
                        T floor) {
  return vertex_face_distance2(b, absolute(b), c, absolute(c), p, absolute(p), relative, floor);
}

// Squared distance at t = 0, lower bound: edge (0, x2) against edge (x3, x4).
template <class T>
T edge_edge_distance2(const Vector3<T>& a1, const Vector3<T>& a1m, const Vector3<T>& b0, const Vector3<T>& b0m,
                      const Vector3<T>& b1, const Vector3<T>& b1m, T relative, T floor) {
  const Vector3<T> db = b1 - b0, dbm = b1m + b0m;
  const Vector3<T> n = cross(a1, db), nm = cross_magnitude(a1m, dbm);
  const T planes = squared_ratio_lower_bound(bounded_dot(n, nm, b0, b0m), bounded_dot(n, nm, n, nm),
                                             relative, floor, false);
  const Vector3<T> axes[4] = {cross(a1, n), cross(db, n), a1, db};
  const Vector3<T> axis_magnitudes[4] = {cross_magnitude(a1m, nm), cross_magnitude(dbm, nm), a1m, dbm};
  RatioBound<T> in_plane{T(0), T(1)};
  for (int k = 0; k < 4; ++k) {
    const Vector3<T>& v = axes[k];
    const Vector3<T>& vm = axis_magnitudes[k];
    const Bounded<T> a[2] = {{T(0), T(0)}, bounded_dot(a1, a1m, v, vm)};  // edge a starts at the origin
    const Bounded<T> b[2] = {bounded_dot(b0, b0m, v, vm), bounded_dot(b1, b1m, v, vm)};
    in_plane = larger_ratio(in_plane, squared_gap_bound(a, b, bounded_dot(v, vm, v, vm), relative, floor));
  }
  return planes + in_plane.value();
}
template <class T>
T edge_edge_distance2(const Vector3<T>& a1, const Vector3<T>& b0, const Vector3<T>& b1, T relative,
                      T floor) {
  return edge_edge_distance2(a1, absolute(a1), b0, absolute(b0), b1, absolute(b1), relative, floor);
}

// Squared distance at t = 0, lower bound: the point x1 (the origin; x2 is
// the same point, Query's layout) against the segment (x3, x4) of a
// vertex-edge query. Off the segment's line by |b0 x d| / |d| (d = b1 - b0),
// along it by the gap between 0 and the ends' projections onto d: parts at
// right angles, whose squares add.
template <class T>
T point_edge_distance2(const Vector3<T>& b0, const Vector3<T>& b0m, const Vector3<T>& b1, const Vector3<T>& b1m,
                       T relative, T floor) {
  using std::abs;
  const Vector3<T> d = b1 - b0, dm = b1m + b0m;
  const Bounded<T> d2 = bounded_dot(d, dm, d, dm);
  const Vector3<T> off = cross(b0, d), off_magnitude = cross_magnitude(b0m, dm);
  const auto lower = [&](const T& value, const T& magnitude) {
    return max_of(abs(value) - (relative * magnitude + floor), T(0));
  };
  const T x = lower(off.x, off_magnitude.x), y = lower(off.y, off_magnitude.y), z = lower(off.z, off_magnitude.z);
  const T room = d2.value + (relative * d2.magnitude + floor);
  const T line = select(room > T(0), (x * x + y * y + z * z) / room, T(0));
  const Bounded<T> point[2] = {{T(0), T(0)}, {T(0), T(0)}};
  const Bounded<T> ends[2] = {bounded_dot(b0, b0m, d, dm), bounded_dot(b1, b1m, d, dm)};
  // Each part rounded at most 8 times up (shrink's margin), the sum once.
  return line * T(SeparationErrors::shrink) + squared_gap_bound(point, ends, d2, relative, floor).value();
}
template <class T>
T point_edge_distance2(const Vector3<T>& b0, const Vector3<T>& b1, T relative, T floor) {
  return point_edge_distance2(b0, absolute(b0), b1, absolute(b1), relative, floor);
}

// The same for a vertex-vertex query: the origin against the point x3.
template <class T>
T point_point_distance2(const Vector3<T>& b, const Vector3<T>& bm, T relative, T floor) {
  using std::abs;
  const auto lower = [&](const T& value, const T& magnitude) {
    return max_of(abs(value) - (relative * magnitude + floor), T(0));
  };
  const T x = lower(b.x, bm.x), y = lower(b.y, bm.y), z = lower(b.z, bm.z);
  return (x * x + y * y + z * z) * T(SeparationErrors::shrink);
}
template <class T>
T point_point_distance2(const Vector3<T>& b, T relative, T floor) {
  return point_point_distance2(b, absolute(b), relative, floor);
}

// Squared largest relative displacement over the step, upper bound. moved[i]
// is x_{i+2}(1) - x_{i+2}(0) (x1 does not move in this frame).
template <class T>
T largest_displacement2(Kind kind, const Vector3<T> (&moved)[3], const Vector3<T> (&moved_magnitude)[3],
                        T relative, T floor) {
  // VF: the vertex x4 against each triangle vertex (x1, x2, x3);
  // EE: each end of edge a (x1, x2) against each end of edge b (x3, x4).
  // (-1: x1, which does not move; VF lists its third pair twice to fill the table.)
  const int pairs[2][4][2] = {{{2, -1}, {2, 0}, {2, 1}, {2, 1}},
                              {{1, -1}, {2, -1}, {0, 1}, {0, 2}}};
  T largest(0);
  for (const auto& pair : pairs[kind == Kind::vertex_face ? 0 : 1]) {
    Vector3<T> w = moved[pair[0]], magnitude = moved_magnitude[pair[0]];
    if (pair[1] >= 0) {
      w = w - moved[pair[1]];
      magnitude = magnitude + moved_magnitude[pair[1]];
    }
    largest = max_of(largest, squared_norm_upper_bound(w, magnitude, relative, floor));
  }
  return largest;
}

// Point kinds: their own distances (for edge-edge queries of a point,
// Query's layout; relative[0] is zero).
template <class T>
T distance2_at(Kind kind, const Vector3<T> (&relative)[3][2], int end, T error_relative, T floor) {
  switch (kind) {
    case Kind::vertex_face:
      return vertex_face_distance2(relative[0][end], relative[1][end], relative[2][end], error_relative, floor);
    case Kind::vertex_edge:
      return point_edge_distance2(relative[1][end], relative[2][end], error_relative, floor);
    case Kind::vertex_vertex: return point_point_distance2(relative[1][end], error_relative, floor);
    default:
      return edge_edge_distance2(relative[0][end], relative[1][end], relative[2][end], error_relative, floor);
  }
}

// The filter: true (per lane) when the primitives certainly stay apart.
// relative positions as in ScaledQuery::relative. With d0, d1 the distances
// at t = 0 and t = 1 and m the largest displacement, a contact at t needs
// d0 <= t m and d1 <= (1 - t) m, so d0 + d1 > m rules it out; squared,
// d0^2 + d1^2 + 2 sqrt(d0^2 d1^2) > m^2.
template <class T>
T largest_displacement2(Kind kind, const Vector3<T> (&relative)[3][2], T error_relative, T floor) {
  Vector3<T> moved[3], moved_magnitude[3];
  for (int i = 0; i < 3; ++i) {
    moved[i] = relative[i][1] - relative[i][0];
    moved_magnitude[i] = absolute(relative[i][1]) + absolute(relative[i][0]);
  }
  return largest_displacement2(kind, moved, moved_magnitude, error_relative, floor);
}

// The bounds the filter computed (squares: m^2 from above, d0^2 and d1^2
// from below), for the filter over pieces of the step (piecewise_filter.hpp).
template <class T>
struct SeparationMeasures {
  T displacement2, start2, end2;
};

// The same bounds computed alone, as the filters compute them.
template <class T>
SeparationMeasures<T> separation_measures(Kind kind, const Vector3<T> (&relative)[3][2], T error_relative, T floor) {
  return {largest_displacement2(kind, relative, error_relative, floor),
          distance2_at(kind, relative, 0, error_relative, floor),
          distance2_at(kind, relative, 1, error_relative, floor)};
}

// `measured`, if given, receives the bounds whenever the filter computed
// them all, which it does unless it culls every lane at d0 > m alone.
template <class T>
auto separation_filter_culls(Kind kind, const Vector3<T> (&relative)[3][2], T error_relative,
                             T floor, SeparationMeasures<T>* measured = nullptr) {
  using std::sqrt;
  const T displacement2 = largest_displacement2(kind, relative, error_relative, floor);
  const T start2 = distance2_at(kind, relative, 0, error_relative, floor);
  // d0 > m alone rules a contact out, and sum2 below is never smaller than
  // this bound of d0^2 (rounding is monotonic): most groups of lanes stop
  // here, the same decision without the distance at t = 1.
  const auto apart_at_start = start2 * T(SeparationErrors::shrink) > displacement2;
  if (all_of(apart_at_start)) return apart_at_start;
  const T end2 = distance2_at(kind, relative, 1, error_relative, floor);
  if (measured != nullptr) *measured = {displacement2, start2, end2};
  // Lower bounds throughout: each rounding (product, root, sums) costs at
  // most u, and the shrink factor takes 8 u off.
  const T sum2 = (start2 + end2 + T(2) * sqrt(start2 * end2)) * T(SeparationErrors::shrink);
  return sum2 > displacement2;
}

// The filter with a minimum separation s (docs/design.md §11), in the same frame
// as `relative`: a contact at t needs d0 <= t m + s and d1 <= (1 - t) m + s,
// so d0 + d1 > m + 2 s rules it out (d0 > m + s alone does too). The
// lengths are taken from their certified squares with a margin of 8 u for
// each root, sum and product.
template <class T>
auto separation_filter_culls_within(Kind kind, const Vector3<T> (&relative)[3][2], T error_relative, T floor,
                                    T separation, SeparationMeasures<T>* measured = nullptr) {
  using std::sqrt;
  const T shrink(SeparationErrors::shrink), grow(SeparationErrors::grow);
  const T displacement2 = largest_displacement2(kind, relative, error_relative, floor);
  const T start2 = distance2_at(kind, relative, 0, error_relative, floor);
  const T motion = sqrt(displacement2) * grow;
  const T start = sqrt(start2) * shrink;
  const auto apart_at_start = start * shrink > (motion + separation) * grow;
  if (all_of(apart_at_start)) return apart_at_start;
  const T end2 = distance2_at(kind, relative, 1, error_relative, floor);
  if (measured != nullptr) *measured = {displacement2, start2, end2};
  const T end = sqrt(end2) * shrink;
  // Either test alone rules a contact out (neither implies the other).
  using Verdict = decltype(apart_at_start);  // bool, or a mask of lanes
  return Verdict(apart_at_start | ((start + end) * shrink > (motion + T(2) * separation) * grow));
}

}  // namespace batchccd::reference

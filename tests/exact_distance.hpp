#pragma once

// An independent reference for minimum-separation tests: the exact squared
// distance between the primitives of a query at a rational time, in GMP
// rationals (every double is one). Closest points by projection and
// clamping; no code of the library is used.
#include <algorithm>
#include <array>

#include <gmpxx.h>

#include "batchccd/query.hpp"

namespace batchccd::testing {

using Rational = mpq_class;
using RationalPoint = std::array<Rational, 3>;

inline RationalPoint minus(const RationalPoint& a, const RationalPoint& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Rational dot(const RationalPoint& a, const RationalPoint& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline RationalPoint cross(const RationalPoint& a, const RationalPoint& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline RationalPoint along(const RationalPoint& a, const RationalPoint& direction, const Rational& s) {
  return {a[0] + s * direction[0], a[1] + s * direction[1], a[2] + s * direction[2]};
}

// Point k of the query at time t: (1 - t) x_k(0) + t x_k(1).
inline RationalPoint point_at(const Query& query, int k, const Rational& t) {
  RationalPoint p;
  for (int axis = 0; axis < 3; ++axis) {
    const Rational start(query.points[k][axis]), end(query.points[k + 4][axis]);
    p[axis] = start + t * (end - start);
  }
  return p;
}

inline Rational point_segment_distance2(const RationalPoint& p, const RationalPoint& a, const RationalPoint& b) {
  const RationalPoint ab = minus(b, a);
  const Rational length2 = dot(ab, ab);
  Rational s = 0;
  if (length2 > 0) s = std::clamp(Rational(dot(minus(p, a), ab) / length2), Rational(0), Rational(1));
  const RationalPoint d = minus(p, along(a, ab, s));
  return dot(d, d);
}

inline Rational point_triangle_distance2(const RationalPoint& p, const RationalPoint& a, const RationalPoint& b,
                                         const RationalPoint& c) {
  const RationalPoint n = cross(minus(b, a), minus(c, a));
  const Rational n2 = dot(n, n);
  if (n2 > 0) {
    // Inside the prism over the triangle: the distance to the plane.
    const RationalPoint ap = minus(p, a), bp = minus(p, b), cp = minus(p, c);
    const bool inside = dot(cross(minus(b, a), ap), n) >= 0 && dot(cross(minus(c, b), bp), n) >= 0 &&
                        dot(cross(minus(a, c), cp), n) >= 0;
    if (inside) {
      const Rational height = dot(ap, n);
      return height * height / n2;
    }
  }
  return std::min({point_segment_distance2(p, a, b), point_segment_distance2(p, b, c),
                   point_segment_distance2(p, c, a)});
}

inline Rational segment_segment_distance2(const RationalPoint& a0, const RationalPoint& a1,
                                          const RationalPoint& b0, const RationalPoint& b1) {
  Rational best = std::min({point_segment_distance2(a0, b0, b1), point_segment_distance2(a1, b0, b1),
                            point_segment_distance2(b0, a0, a1), point_segment_distance2(b1, a0, a1)});
  // Interior to interior: the lines' closest points, when both fall inside.
  const RationalPoint u = minus(a1, a0), v = minus(b1, b0), w = minus(a0, b0);
  const Rational uu = dot(u, u), uv = dot(u, v), vv = dot(v, v), uw = dot(u, w), vw = dot(v, w);
  const Rational determinant = uu * vv - uv * uv;
  if (determinant > 0) {
    const Rational s = (uv * vw - vv * uw) / determinant, t = (uu * vw - uv * uw) / determinant;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
      const RationalPoint d = minus(along(a0, u, s), along(b0, v, t));
      best = std::min(best, Rational(dot(d, d)));
    }
  }
  return best;
}

// The squared distance between the query's primitives at time t (vertex-face:
// the vertex against the triangle; every other kind as edge-edge, Query's layout).
inline Rational squared_distance_at(Kind kind, const Query& query, const Rational& t) {
  if (kind == Kind::vertex_face)
    return point_triangle_distance2(point_at(query, 0, t), point_at(query, 1, t), point_at(query, 2, t),
                                    point_at(query, 3, t));
  return segment_segment_distance2(point_at(query, 0, t), point_at(query, 1, t), point_at(query, 2, t),
                                   point_at(query, 3, t));
}

}  // namespace batchccd::testing

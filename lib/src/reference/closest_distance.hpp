#pragma once

// Squared distances between closed primitives at one instant: closest points
// by projection and clamping. Written over the number type T: double where
// a front needs an initial distance, exact rationals (GMP) in the tests,
// where a squared distance <= min_distance^2 at a rational time is a witness
// of a contact (docs/design.md §11).
#include <algorithm>
#include <array>

namespace batchccd::reference {

template <class T>
using Point = std::array<T, 3>;

template <class T>
Point<T> minus(const Point<T>& a, const Point<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class T>
T dot(const Point<T>& a, const Point<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class T>
Point<T> cross(const Point<T>& a, const Point<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <class T>
Point<T> along(const Point<T>& a, const Point<T>& direction, const T& s) {
  return {a[0] + s * direction[0], a[1] + s * direction[1], a[2] + s * direction[2]};
}

template <class T>
T point_segment_distance2(const Point<T>& p, const Point<T>& a, const Point<T>& b) {
  const Point<T> ab = minus(b, a);
  const T length2 = dot(ab, ab);
  T s = 0;
  if (length2 > 0) s = std::clamp(T(dot(minus(p, a), ab) / length2), T(0), T(1));
  const Point<T> d = minus(p, along(a, ab, s));
  return dot(d, d);
}

template <class T>
T point_triangle_distance2(const Point<T>& p, const Point<T>& a, const Point<T>& b, const Point<T>& c) {
  const Point<T> n = cross(minus(b, a), minus(c, a));
  const T n2 = dot(n, n);
  if (n2 > 0) {
    // Over the triangle (every edge sees p on its inner side): the height.
    const Point<T> ap = minus(p, a);
    const bool inside = dot(cross(minus(b, a), ap), n) >= 0 && dot(cross(minus(c, b), minus(p, b)), n) >= 0 &&
                        dot(cross(minus(a, c), minus(p, c)), n) >= 0;
    if (inside) {
      const T height = dot(ap, n);
      return height * height / n2;
    }
  }
  return std::min({point_segment_distance2(p, a, b), point_segment_distance2(p, b, c),
                   point_segment_distance2(p, c, a)});
}

template <class T>
T segment_segment_distance2(const Point<T>& a0, const Point<T>& a1, const Point<T>& b0, const Point<T>& b1) {
  T best = std::min({point_segment_distance2(a0, b0, b1), point_segment_distance2(a1, b0, b1),
                     point_segment_distance2(b0, a0, a1), point_segment_distance2(b1, a0, a1)});
  // Interior to interior: the lines' closest points, where both lie inside.
  const Point<T> u = minus(a1, a0), v = minus(b1, b0), w = minus(a0, b0);
  const T uu = dot(u, u), uv = dot(u, v), vv = dot(v, v), uw = dot(u, w), vw = dot(v, w);
  const T determinant = uu * vv - uv * uv;
  if (determinant > 0) {
    const T s = (uv * vw - vv * uw) / determinant, t = (uu * vw - uv * uw) / determinant;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
      const Point<T> d = minus(along(a0, u, s), along(b0, v, t));
      best = std::min(best, T(dot(d, d)));
    }
  }
  return best;
}

// The primitives of a query's layout (batchccd::Query) from its four points
// at one time: vertex-face (p, a, b, c), anything else edge-edge.
template <class T>
T squared_distance(bool vertex_face, const std::array<Point<T>, 4>& x) {
  return vertex_face ? point_triangle_distance2(x[0], x[1], x[2], x[3])
                     : segment_segment_distance2(x[0], x[1], x[2], x[3]);
}

}  // namespace batchccd::reference

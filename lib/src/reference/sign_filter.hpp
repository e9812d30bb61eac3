#pragma once

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "batchccd/query.hpp"

// The algebraic non-penetration filter (docs/design.md §2-3): a certified sign test
// on the Bernstein coefficients, branch-free so it runs unchanged in SIMD
// lanes (T = double or an xsimd batch; the result is bool-like per lane).
namespace batchccd::reference {

// All four coefficients certainly of one sign: no root on the interval.
template <class T>
auto certainly_root_free(const T (&coefficient)[4], const T (&magnitude)[4], T relative, T floor) {
  auto positive = coefficient[0] > relative * magnitude[0] + floor;
  auto negative = coefficient[0] < -(relative * magnitude[0] + floor);
  for (int k = 1; k < 4; ++k) {
    const T bound = relative * magnitude[k] + floor;
    positive = positive & (coefficient[k] > bound);
    negative = negative & (coefficient[k] < -bound);
  }
  return positive | negative;
}

// The filter's two steps on a query's six differences relative[i][tau]
// (x_{i+2}(tau) - x_1(tau), docs/design.md §1, in whichever frame), given each
// one's largest component magnitude, with the coefficients' absolute error
// floor of that frame (their relative error is coefficient_error's in
// both). The lane kernels take the steps apart: the whole interval for
// every candidate, the halves only for the few it keeps (a branch on
// whether a group of lanes needs them mispredicts too often).
template <class T>
struct SignTest {
  BernsteinCubic<T> cubic;
  T relative, floor, half_relative, half_floor;

  // V = 0 on [0, 1].
  auto whole() const { return certainly_root_free(cubic.coefficient, cubic.magnitude, relative, floor); }

  // V = 0 on both halves after one subdivision: what settles V = 2 without roots.
  auto halves() const {
    T left[4], right[4], left_magnitude[4], right_magnitude[4];
    split_at_half(cubic.coefficient, left, right);
    split_at_half(cubic.magnitude, left_magnitude, right_magnitude);
    return certainly_root_free(left, left_magnitude, half_relative, half_floor) &
           certainly_root_free(right, right_magnitude, half_relative, half_floor);
  }
};

// The test of a query's differences (uncertified: plain signs, every
// bound zero). The magnitudes are bounded either way and the bounds' scales
// zeroed when uncertified: one path, where a branch between the two made
// the lane kernels keep the whole test on the stack.
// coefficient_relative: the coefficients' relative error bound, the
// frames' differences' by default (interpolated inputs need more).
template <class T>
SignTest<T> sign_test(const Vector3<T> (&r)[3][2], const T (&largest)[3][2], T coefficient_floor,
                      bool certified, double coefficient_relative = coefficient_error(0.0).relative) {
  SignTest<T> test{bernstein_cubic(r[0][0], r[0][1], r[1][0], r[1][1], r[2][0], r[2][1]), T(0), T(0), T(0),
                   T(0)};
  const auto& n = largest;
  bernstein_magnitude_bounds(test.cubic, n[0][0], n[0][1], n[1][0], n[1][1], n[2][0], n[2][1]);
  const ErrorModel whole{coefficient_relative, 0.0}, half = half_coefficient_error(whole);
  const double scale = certified ? 1.0 : 0.0;  // 0 * a finite magnitude: a zero bound
  test.relative = T(scale * whole.relative), test.floor = T(scale) * coefficient_floor;
  test.half_relative = T(scale * half.relative), test.half_floor = T(scale * kHalfWeightSum) * coefficient_floor;
  return test;
}

// The whole filter: the whole interval, then (with `subdivide`) the halves.
// Without `subdivide`, the four signs alone: the DNF-style filter of Tang et
// al. 2010, kept for comparison.
template <class T>
auto sign_filter_culls(const Vector3<T> (&relative)[3][2], const T (&largest)[3][2], T floor,
                       bool certified, bool subdivide) {
  const SignTest<T> test = sign_test(relative, largest, floor, certified);
  const auto whole = test.whole();
  // Where every lane is settled already the halves change nothing.
  if (!subdivide || all_of(whole)) return whole;
  return whole | test.halves();
}

// The sign test with a minimum separation s (docs/design.md §11), where the
// cubic's signs alone prove nothing: primitives can come within s without
// ever being coplanar. The distance between them is at least the distance
// |d(t)| / |n(t)| to the triangle's plane (VF, n = x21 x x31) or between the
// edges' lines (EE, n = x21 x x43). Where d's Bernstein coefficients share
// a sign, |d(t)| is at least the smallest of them; |n(t)| is at most the
// largest of the quadratic n's three Bernstein control points, and a
// control point's length at most its L1 norm; so
// min |b_k| > s max |n_j|_1 rules out a contact on [0, 1]. (Where n
// vanishes so does d, and nothing is culled.) With s = 0 it is the whole
// interval's sign test. Inputs as sign_test's, s in the same frame; written
// once over T for the scalar path and the lanes.
// The bound s max |n_j|_1 that |d| must exceed, grown for the rounding of
// the thresholds made from it; test.floor is the coefficients' floor.
// `euclidean`: s max |n_j| instead, up to sqrt(3) times sharper, for the
// solver's short intervals where |d| / |n| nears s (its square root costs
// the lanes more than it culls there).
template <class T>
T plane_reach(Kind kind, const Vector3<T> (&r)[3][2], const T (&largest)[3][2], const SignTest<T>& test,
              bool certified, T separation, bool euclidean = false) {
  using std::abs;
  using std::sqrt;
  // n = a x b, both linear: VF a = x21, b = x31; EE a = x21, b = x43.
  const bool vertex_face = kind == Kind::vertex_face;
  const Vector3<T> b0 = vertex_face ? r[1][0] : r[2][0] - r[1][0];
  const Vector3<T> b1 = vertex_face ? r[1][1] : r[2][1] - r[1][1];
  const T nb0 = vertex_face ? largest[1][0] : largest[2][0] + largest[1][0];
  const T nb1 = vertex_face ? largest[1][1] : largest[2][1] + largest[1][1];
  const T na0 = largest[0][0], na1 = largest[0][1];
  const Vector3<T> control[3] = {cross(r[0][0], b0), cross(r[0][0], b1) + cross(r[0][1], b0),  // twice n_1
                                 cross(r[0][1], b1)};
  // A component adds two products of factors below na nb: inputs with 2
  // roundings (the frame's difference, EE's b), a product, a difference and
  // n_1's sum: 5 u of 2 na nb, bounded by 16 u; underflow within the floor.
  const T scale(certified ? 1.0 : 0.0);
  const T relative = scale * T(32 * kUnitRoundoff);
  const T component_error[3] = {relative * na0 * nb0 + test.floor, relative * (na0 * nb1 + na1 * nb0) + test.floor,
                                relative * na1 * nb1 + test.floor};
  T largest_normal(0);
  for (int j = 0; j < 3; ++j) {
    T length;
    if (euclidean) {
      // Each component's magnitude grown by its error; the squares, their
      // sum and the root round by less than 4 u, and where the squares
      // underflow (by at most 3 2^-1074 in all) the root by below 2^-530.
      const T x = abs(control[j].x) + component_error[j], y = abs(control[j].y) + component_error[j],
              z = abs(control[j].z) + component_error[j];
      length = sqrt(x * x + y * y + z * z) * T(1 + 4 * kUnitRoundoff) + T(0x1p-530);
    } else {
      length = abs(control[j].x) + abs(control[j].y) + abs(control[j].z) + T(3) * component_error[j];
    }
    largest_normal = max_of(largest_normal, j == 1 ? T(0.5) * length : length);
  }
  // The threshold's sums and products round by less than 8 u.
  return separation * largest_normal * T(1 + 8 * kUnitRoundoff);
}

template <class T>
auto plane_distance_culls(Kind kind, const Vector3<T> (&r)[3][2], const T (&largest)[3][2],
                          T coefficient_floor, bool certified, T separation,
                          double coefficient_relative = coefficient_error(0.0).relative, bool euclidean = false) {
  const SignTest<T> test = sign_test(r, largest, coefficient_floor, certified, coefficient_relative);
  const T reach = plane_reach(kind, r, largest, test, certified, separation, euclidean);
  // The coefficients are the Bernstein ones times (1, 3, 3, 1).
  const T weight[4] = {T(1), T(3), T(3), T(1)};
  auto positive = test.cubic.coefficient[0] > reach + test.relative * test.cubic.magnitude[0] + test.floor;
  auto negative = test.cubic.coefficient[0] < -(reach + test.relative * test.cubic.magnitude[0] + test.floor);
  for (int k = 1; k < 4; ++k) {
    const T threshold = weight[k] * reach + test.relative * test.cubic.magnitude[k] + test.floor;
    positive = positive & (test.cubic.coefficient[k] > threshold);
    negative = negative & (test.cubic.coefficient[k] < -threshold);
  }
  return positive | negative;
}

}  // namespace batchccd::reference

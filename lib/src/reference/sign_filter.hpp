#pragma once

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"

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
template <class T>
SignTest<T> sign_test(const Vector3<T> (&r)[3][2], const T (&largest)[3][2], T coefficient_floor,
                      bool certified) {
  SignTest<T> test{bernstein_cubic(r[0][0], r[0][1], r[1][0], r[1][1], r[2][0], r[2][1]), T(0), T(0), T(0),
                   T(0)};
  const auto& n = largest;
  bernstein_magnitude_bounds(test.cubic, n[0][0], n[0][1], n[1][0], n[1][1], n[2][0], n[2][1]);
  const ErrorModel whole = coefficient_error(0.0), half = half_coefficient_error(whole);
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

}  // namespace batchccd::reference

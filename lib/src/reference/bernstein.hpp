#pragma once

// The coplanarity cubic in Bernstein form, computed straight from the
// geometry (docs/design.md §2), together with the magnitudes its forward error
// bound needs. Written once over the arithmetic type T: double in the scalar
// reference path, an xsimd batch in the lane kernels, so both make the same
// decisions bit for bit.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace batchccd::reference {

template <class T>
struct Vector3 {
  T x, y, z;
};

// select for scalar lanes; xsimd's select serves batches (found by ADL).
inline double select(bool condition, double if_true, double if_false) {
  return condition ? if_true : if_false;
}

// Whether a condition holds in every lane (xsimd's all, found by ADL,
// serves batches).
inline bool all_of(bool condition) { return condition; }
template <class Mask>
  requires requires(const Mask& mask) { all(mask); }
bool all_of(const Mask& mask) {
  return all(mask);
}

// a > b ? a : b and a < b ? a : b, lane by lane. For batches xsimd's max
// and min (found by ADL): on x86 the maxpd and minpd instructions, whose
// definition these are (the second operand where either is a NaN or both
// are zero), one instruction where a compare and a blend took two.
inline double max_of(double a, double b) { return a > b ? a : b; }
inline double min_of(double a, double b) { return a < b ? a : b; }
template <class T>
T max_of(const T& a, const T& b) {
  return max(a, b);
}
template <class T>
T min_of(const T& a, const T& b) {
  return min(a, b);
}

// |x| as a bit pattern: the orders of the two agree for non-negative
// doubles, and a NaN sorts above everything, where a max of doubles could
// drop it. The lane kernels do the same with integer lanes.
inline std::uint64_t magnitude_bits(double x) {
  return std::bit_cast<std::uint64_t>(x) & 0x7fffffffffffffffull;
}

// The largest |component| of v, by magnitude_bits (a NaN component shows).
inline double largest_magnitude(const Vector3<double>& v) {
  return std::bit_cast<double>(std::max({magnitude_bits(v.x), magnitude_bits(v.y), magnitude_bits(v.z)}));
}

template <class T>
Vector3<T> operator-(const Vector3<T>& a, const Vector3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

template <class T>
Vector3<T> operator+(const Vector3<T>& a, const Vector3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}

template <class T>
Vector3<T> absolute(const Vector3<T>& v) {
  using std::abs;
  return {abs(v.x), abs(v.y), abs(v.z)};
}

template <class T>
Vector3<T> cross(const Vector3<T>& a, const Vector3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The cross product of absolute values with + in place of -: bounds every
// term the real cross product adds up.
template <class T>
Vector3<T> cross_magnitude(const Vector3<T>& a, const Vector3<T>& b) {
  return {a.y * b.z + a.z * b.y, a.z * b.x + a.x * b.z, a.x * b.y + a.y * b.x};
}

template <class T>
T dot(const Vector3<T>& a, const Vector3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// d(t) = A(t) x B(t) . C(t) with A, B, C linear over an interval, given by
// their values at its ends (A0, A1, ...). Coefficients are those of the
// Bernstein basis scaled by (1, 3, 3, 1): same signs, no division.
template <class T>
struct BernsteinCubic {
  T coefficient[4];
  T magnitude[4];  // the same sums over absolute values
};

// The coefficients, with `cross` as the cross product: since
// A x B = (1-t)^2 a0b0 + (1-t)t (a1b0 + a0b1) + t^2 a1b1, the two mixed
// products are added before the dot products (the same terms as dotting
// each, so the same error bound: 7 roundings on the longest path either
// way, error_bounds.hpp; 6 multiplications fewer).
template <class T, class Cross>
void bernstein_coefficients(const Cross& cross, const Vector3<T>& a0, const Vector3<T>& a1,
                            const Vector3<T>& b0, const Vector3<T>& b1, const Vector3<T>& c0,
                            const Vector3<T>& c1, T (&coefficient)[4]) {
  const Vector3<T> a0b0 = cross(a0, b0), a1b1 = cross(a1, b1);
  const Vector3<T> mixed = cross(a1, b0) + cross(a0, b1);
  coefficient[0] = dot(a0b0, c0);
  coefficient[1] = dot(mixed, c0) + dot(a0b0, c1);
  coefficient[2] = dot(a1b1, c0) + dot(mixed, c1);
  coefficient[3] = dot(a1b1, c1);
}

template <class T>
BernsteinCubic<T> bernstein_cubic(const Vector3<T>& a0, const Vector3<T>& a1,
                                  const Vector3<T>& b0, const Vector3<T>& b1,
                                  const Vector3<T>& c0, const Vector3<T>& c1) {
  BernsteinCubic<T> cubic;
  bernstein_coefficients(cross<T>, a0, a1, b0, b1, c0, c1, cubic.coefficient);
  return cubic;
}

// The magnitudes, given the absolute values (or upper bounds of them) of the
// factors: |a0| componentwise, and so on.
template <class T>
void bernstein_magnitudes(BernsteinCubic<T>& cubic, const Vector3<T>& a0, const Vector3<T>& a1,
                          const Vector3<T>& b0, const Vector3<T>& b1, const Vector3<T>& c0,
                          const Vector3<T>& c1) {
  bernstein_coefficients(cross_magnitude<T>, a0, a1, b0, b1, c0, c1, cubic.magnitude);
}

// Upper bounds of the magnitudes at a fifth of bernstein_magnitudes' cost,
// for the filter, from each factor's largest component magnitude (na0 =
// max |a0_i|, and so on): each of a triple product's 6 terms is at most the
// product of its factors' largest components. Grouped as the coefficients
// are, with the 6 taken into the c factors. (Rounding may leave a bound up
// to 5 u below that product, which the error models' spare room covers.)
template <class T>
void bernstein_magnitude_bounds(BernsteinCubic<T>& cubic, T na0, T na1, T nb0, T nb1, T nc0, T nc1) {
  const T a0b0 = na0 * nb0, a1b1 = na1 * nb1, mixed = na1 * nb0 + na0 * nb1;
  const T c0 = T(6) * nc0, c1 = T(6) * nc1;
  cubic.magnitude[0] = a0b0 * c0;
  cubic.magnitude[1] = mixed * c0 + a0b0 * c1;
  cubic.magnitude[2] = a1b1 * c0 + mixed * c1;
  cubic.magnitude[3] = a1b1 * c1;
}

// Bernstein coefficients of the two halves [0, 1/2] and [1/2, 1] (de
// Casteljau), each scaled by positive constants so only sums and small
// integer multiples remain: left (c0, 3c0+c1, 3c0+2c1+c2, c0+c1+c2+c3),
// right (c0+c1+c2+c3, c1+2c2+3c3, c2+3c3, c3). Applied alike to magnitudes.
template <class T>
void split_at_half(const T (&c)[4], T (&left)[4], T (&right)[4]) {
  const T sum = c[0] + c[1] + c[2] + c[3];
  left[0] = c[0];
  left[1] = T(3) * c[0] + c[1];
  left[2] = T(3) * c[0] + T(2) * c[1] + c[2];
  left[3] = sum;
  right[0] = sum;
  right[1] = c[1] + T(2) * c[2] + T(3) * c[3];
  right[2] = c[2] + T(3) * c[3];
  right[3] = c[3];
}

}  // namespace batchccd::reference

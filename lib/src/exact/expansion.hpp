#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

// Floating-point expansions (Shewchuk 1997, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates"): a real
// number held exactly as an unevaluated sum of doubles, built with
// error-free transformations (two-sum, Dekker's two-product). Exact as long
// as no operation overflows or underflows: callers check their inputs' range
// first (below) and leave the rest to the GMP stage. The terms
// are nonoverlapping, in increasing magnitude, zeros eliminated, so the sign
// of the sum is the sign of the last term. Sizes are fixed at compile time:
// no allocation, cheap enough to run before every GMP escalation.
namespace batchccd::exact {

// x = a + b rounded, error = (a + b) - x exactly.
inline void two_sum(double a, double b, double& x, double& error) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  error = (a - a_virtual) + (b - b_virtual);
}

// x = a * b rounded, error = a * b - x exactly (Dekker: each factor split
// into halves of 26 bits whose products are exact). Needs |a|, |b| < 2^996.
inline void two_product(double a, double b, double& x, double& error) {
  const auto split = [](double value, double& high, double& low) {
    const double c = 134217729.0 * value;  // 2^27 + 1
    high = c - (c - value);
    low = value - high;
  };
  x = a * b;
  double a_high, a_low, b_high, b_low;
  split(a, a_high, a_low);
  split(b, b_high, b_low);
  error = ((a_high * b_high - x) + a_high * b_low + a_low * b_high) + a_low * b_low;
}

template <std::size_t Capacity>
struct Expansion {
  std::array<double, Capacity> terms;  // the first `size` hold the value
  std::size_t size = 0;

  void push(double term) {
    if (term != 0) terms[size++] = term;
  }
  // -1, 0 or 1: the sign of the exact sum.
  int sign() const { return size == 0 ? 0 : (terms[size - 1] > 0 ? 1 : -1); }
  // The sum rounded (approximately: the largest term dominates).
  double estimate() const {
    double sum = 0;
    for (std::size_t i = 0; i < size; ++i) sum += terms[i];
    return sum;
  }
};

// a - b exactly, as two terms.
inline Expansion<2> difference(double a, double b) {
  double x, error;
  two_sum(a, -b, x, error);
  Expansion<2> result;
  result.push(error);
  result.push(x);
  return result;
}

inline Expansion<1> single(double a) {
  Expansion<1> result;
  result.push(a);
  return result;
}

// e + b (Shewchuk's Grow-Expansion with zero elimination).
template <std::size_t N>
Expansion<N + 1> grown(const Expansion<N>& e, double b) {
  Expansion<N + 1> result;
  double carry = b;
  for (std::size_t i = 0; i < e.size; ++i) {
    double error;
    two_sum(carry, e.terms[i], carry, error);
    result.push(error);
  }
  result.push(carry);
  return result;
}

// e + f: both merged by magnitude, then summed from the smallest up
// (Shewchuk's Fast-Expansion-Sum with zero elimination; two-sum throughout,
// which needs no ordering of its operands).
template <std::size_t M, std::size_t N>
Expansion<M + N> operator+(const Expansion<M>& e, const Expansion<N>& f) {
  Expansion<M + N> result;
  if (e.size + f.size == 0) return result;
  std::size_t i = 0, j = 0;
  const auto next_smallest = [&] {
    const bool take_e = j == f.size || (i < e.size && std::fabs(e.terms[i]) <= std::fabs(f.terms[j]));
    return take_e ? e.terms[i++] : f.terms[j++];
  };
  double carry = next_smallest();
  while (i < e.size || j < f.size) {
    double error;
    two_sum(carry, next_smallest(), carry, error);
    result.push(error);
  }
  result.push(carry);
  return result;
}

template <std::size_t N>
Expansion<N> operator-(Expansion<N> e) {
  for (std::size_t i = 0; i < e.size; ++i) e.terms[i] = -e.terms[i];
  return e;
}

template <std::size_t M, std::size_t N>
Expansion<M + N> operator-(const Expansion<M>& e, const Expansion<N>& f) {
  return e + (-f);
}

// e * b (Shewchuk's Scale-Expansion with zero elimination).
template <std::size_t N>
Expansion<2 * N> scaled(const Expansion<N>& e, double b) {
  Expansion<2 * N> result;
  if (e.size == 0 || b == 0) return result;
  double carry, error;
  two_product(e.terms[0], b, carry, error);
  result.push(error);
  for (std::size_t i = 1; i < e.size; ++i) {
    double product, product_error, sum, sum_error;
    two_product(e.terms[i], b, product, product_error);
    two_sum(carry, product_error, sum, sum_error);
    result.push(sum_error);
    two_sum(product, sum, carry, error);
    result.push(error);
  }
  result.push(carry);
  return result;
}

// e * f: e scaled by each term of f, summed.
template <std::size_t M, std::size_t N>
Expansion<2 * M * N> operator*(const Expansion<M>& e, const Expansion<N>& f) {
  if constexpr (N == 1) {
    if (f.size == 0) return {};
    return scaled(e, f.terms[0]);
  } else {
    Expansion<2 * M * N> result;
    result.size = 0;
    for (std::size_t j = 0; j < f.size; ++j) {
      // The sum of j parts holds at most 2Mj terms: it fits in 2MN.
      const auto sum = result + scaled(e, f.terms[j]);
      std::copy_n(sum.terms.begin(), sum.size, result.terms.begin());
      result.size = sum.size;
    }
    return result;
  }
}

// Products of three differences of values of magnitude 0 or within
// [2^-200, 2]: no overflow, and every such value is a multiple of 2^-252,
// so every product term is a multiple of 2^-756 and no error term
// underflows. Callers scale their inputs into that range first.

}  // namespace batchccd::exact

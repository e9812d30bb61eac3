#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

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

// e + f into `out` (anything with push(double)): both merged by magnitude,
// then summed from the smallest up (Shewchuk's Fast-Expansion-Sum with zero
// elimination; two-sum throughout, which needs no ordering of its
// operands). m + n terms at most.
template <class Out>
void add_terms(const double* e, std::size_t m, const double* f, std::size_t n, Out& out) {
  if (m + n == 0) return;
  std::size_t i = 0, j = 0;
  const auto next_smallest = [&] {
    const bool take_e = j == n || (i < m && std::fabs(e[i]) <= std::fabs(f[j]));
    return take_e ? e[i++] : f[j++];
  };
  double carry = next_smallest();
  while (i < m || j < n) {
    double error;
    two_sum(carry, next_smallest(), carry, error);
    out.push(error);
  }
  out.push(carry);
}

// e * b into `out` (Shewchuk's Scale-Expansion with zero elimination): 2 n
// terms at most.
template <class Out>
void scale_terms(const double* e, std::size_t n, double b, Out& out) {
  if (n == 0 || b == 0) return;
  double carry, error;
  two_product(e[0], b, carry, error);
  out.push(error);
  for (std::size_t i = 1; i < n; ++i) {
    double product, product_error, sum, sum_error;
    two_product(e[i], b, product, product_error);
    two_sum(carry, product_error, sum, sum_error);
    out.push(sum_error);
    two_sum(product, sum, carry, error);
    out.push(error);
  }
  out.push(carry);
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

// e + f (add_terms).
template <std::size_t M, std::size_t N>
Expansion<M + N> operator+(const Expansion<M>& e, const Expansion<N>& f) {
  Expansion<M + N> result;
  add_terms(e.terms.data(), e.size, f.terms.data(), f.size, result);
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

// e * b (scale_terms).
template <std::size_t N>
Expansion<2 * N> scaled(const Expansion<N>& e, double b) {
  Expansion<2 * N> result;
  scale_terms(e.terms.data(), e.size, b, result);
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

// An expansion of any length up to kCapacity terms, compressed after every
// operation (Shewchuk's Compress: nonoverlapping, increasing magnitude, the
// largest term within an ulp of the sum), for computations whose lengths
// are not known at compile time: polynomials in t. An operation whose
// result needs more terms throws TooLong, and the caller leaves the
// question to exact integers. Exact under the same range conditions as
// above, which the caller establishes.
class BoundedExpansion {
 public:
  static constexpr std::size_t kCapacity = 24;
  struct TooLong {};

  BoundedExpansion() = default;
  // Copies move the terms in use only: most values hold a few of them.
  BoundedExpansion(const BoundedExpansion& other) : size_(other.size_) {
    std::copy_n(other.terms_.begin(), size_, terms_.begin());
  }
  BoundedExpansion& operator=(const BoundedExpansion& other) {
    size_ = other.size_;
    std::copy_n(other.terms_.begin(), size_, terms_.begin());
    return *this;
  }
  explicit BoundedExpansion(double value) {
    if (value != 0) terms_[size_++] = value;
  }
  static BoundedExpansion difference(double a, double b) {
    double x, error;
    two_sum(a, -b, x, error);
    Scratch pair;  // compressed, so that every value is strongly nonoverlapping
    pair.push(error);
    pair.push(x);
    return compressed(pair);
  }

  int sign() const { return size_ == 0 ? 0 : (terms_[size_ - 1] > 0 ? 1 : -1); }
  bool is_zero() const { return size_ == 0; }
  // The magnitudes of the largest and the smallest term (0 for zero).
  double largest_term() const { return size_ == 0 ? 0 : std::fabs(terms_[size_ - 1]); }
  double smallest_term() const { return size_ == 0 ? 0 : std::fabs(terms_[0]); }
  std::span<const double> terms() const { return {terms_.data(), size_}; }  // increasing magnitude
  // The sum, rounded: within a few ulps of it (the terms are compressed).
  double estimate() const {
    double sum = 0;
    for (std::size_t i = 0; i < size_; ++i) sum += terms_[i];
    return sum;
  }

  friend BoundedExpansion operator+(const BoundedExpansion& e, const BoundedExpansion& f) {
    if (e.size_ == 0) return f;  // already compressed
    if (f.size_ == 0) return e;
    Scratch sum;
    add_terms(e.terms_.data(), e.size_, f.terms_.data(), f.size_, sum);
    return compressed(sum);
  }
  friend BoundedExpansion operator-(BoundedExpansion e) {
    for (std::size_t i = 0; i < e.size_; ++i) e.terms_[i] = -e.terms_[i];
    return e;
  }
  friend BoundedExpansion operator-(const BoundedExpansion& e, const BoundedExpansion& f) { return e + (-f); }
  // e * b for a double b.
  friend BoundedExpansion operator*(const BoundedExpansion& e, double b) {
    Scratch product;
    scale_terms(e.terms_.data(), e.size_, b, product);
    return compressed(product);
  }
  // e scaled by each term of the shorter factor, summed.
  friend BoundedExpansion operator*(const BoundedExpansion& e, const BoundedExpansion& f) {
    if (e.size_ < f.size_) return f * e;
    if (f.size_ == 0) return {};
    BoundedExpansion product = e * f.terms_[0];
    for (std::size_t j = 1; j < f.size_; ++j) product = product + e * f.terms_[j];
    return product;
  }

 private:
  struct Scratch {  // an uncompressed intermediate: twice the capacity
    std::array<double, 2 * kCapacity> terms;
    std::size_t size = 0;
    void push(double term) {
      if (term != 0) terms[size++] = term;
    }
  };

  // Shewchuk's Compress: sum from the top down, then from the bottom up.
  static BoundedExpansion compressed(const Scratch& e) {
    BoundedExpansion result;
    if (e.size == 0) return result;
    std::array<double, 2 * kCapacity> g;
    std::size_t bottom = e.size - 1;
    double q = e.terms[e.size - 1];
    for (std::size_t i = e.size - 1; i-- > 0;) {
      const double sum = q + e.terms[i];  // Fast-Two-Sum: |q| >= |e_i| here
      const double small = e.terms[i] - (sum - q);
      if (small != 0) {
        g[bottom--] = sum;
        q = small;
      } else {
        q = sum;
      }
    }
    g[bottom] = q;
    std::size_t top = 0;
    std::array<double, 2 * kCapacity> h;
    for (std::size_t i = bottom + 1; i < e.size; ++i) {
      const double sum = g[i] + q;
      const double small = q - (sum - g[i]);
      if (small != 0) h[top++] = small;
      q = sum;
    }
    if (q != 0) h[top++] = q;
    if (top > kCapacity) throw TooLong{};
    std::copy_n(h.begin(), top, result.terms_.begin());
    result.size_ = top;
    return result;
  }

  std::array<double, kCapacity> terms_;
  std::size_t size_ = 0;
};

}  // namespace batchccd::exact

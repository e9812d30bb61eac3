#include "exact/polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace batchccd::exact {

void Polynomial::trim() {
  while (!coefficients.empty() && coefficients.back().is_zero()) coefficients.pop_back();
}

Polynomial linear_polynomial(Integer constant, Integer slope) {
  Polynomial p;
  p.coefficients.push_back(std::move(constant));
  p.coefficients.push_back(std::move(slope));
  p.trim();
  return p;
}

Polynomial operator+(const Polynomial& a, const Polynomial& b) {
  const Polynomial& longer = a.coefficients.size() >= b.coefficients.size() ? a : b;
  const Polynomial& shorter = &longer == &a ? b : a;
  Polynomial sum = longer;
  for (std::size_t i = 0; i < shorter.coefficients.size(); ++i)
    sum.coefficients[i] += shorter.coefficients[i];
  sum.trim();
  return sum;
}

Polynomial operator-(Polynomial a) {
  for (Integer& c : a.coefficients) c.negate();
  return a;
}

Polynomial operator-(const Polynomial& a, const Polynomial& b) { return a + (-b); }

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  Polynomial product;
  if (a.is_zero() || b.is_zero()) return product;
  product.coefficients.resize(a.coefficients.size() + b.coefficients.size() - 1);
  for (std::size_t i = 0; i < a.coefficients.size(); ++i)
    for (std::size_t j = 0; j < b.coefficients.size(); ++j)
      product.coefficients[i + j].add_product(a.coefficients[i], b.coefficients[j]);
  product.trim();  // integer products never cancel a leading term, but stay safe
  return product;
}

Polynomial derivative(const Polynomial& p) {
  Polynomial result;
  for (std::size_t i = 1; i < p.coefficients.size(); ++i)
    result.coefficients.push_back(p.coefficients[i] * Integer(static_cast<long>(i)));
  result.trim();
  return result;
}

int sign_at_dyadic(const Polynomial& p, const Integer& numerator, unsigned long exponent) {
  // 2^(exponent * n) p(k / 2^exponent) = sum_i c_i k^i 2^(exponent (n - i)), by Horner.
  if (p.is_zero()) return 0;
  Integer value = p.leading();
  Integer scale = 1;
  for (int i = p.degree() - 1; i >= 0; --i) {
    value *= numerator;
    scale.shift_left(exponent);
    value.add_product(p.coefficients[static_cast<std::size_t>(i)], scale);
  }
  return value.sign();
}

namespace {

Integer content(const Polynomial& p) {
  Integer divisor;
  for (const Integer& c : p.coefficients) {
    divisor = greatest_common_divisor(divisor, c);
    if (divisor == Integer(1)) break;
  }
  return divisor;
}

// |lc(b)|^k a - q b for some k >= 0 and polynomial q, of degree below b's:
// the remainder times a positive constant, with integer coefficients (its
// signs are the remainder's: what Sturm sequences need).
Polynomial pseudo_remainder(Polynomial a, const Polynomial& b) {
  const int divisor_degree = b.degree();
  const bool negative = b.leading().sign() < 0;
  const Integer scale = negative ? -b.leading() : b.leading();
  while (!a.is_zero() && a.degree() >= divisor_degree) {
    const Integer lead = negative ? -a.leading() : a.leading();
    const std::size_t shift = static_cast<std::size_t>(a.degree() - divisor_degree);
    a.coefficients.pop_back();  // cancels: scale lead - lead lc(b) = 0
    for (Integer& c : a.coefficients) c *= scale;
    for (std::size_t i = 0; i + 1 < b.coefficients.size(); ++i)
      a.coefficients[i + shift].subtract_product(lead, b.coefficients[i]);
    a.trim();
  }
  return a;
}

}  // namespace

Polynomial primitive_part(const Polynomial& p) {
  if (p.is_zero()) return p;
  Integer divisor = content(p);
  if (p.leading().sign() < 0) divisor.negate();
  Polynomial result;
  result.coefficients.reserve(p.coefficients.size());
  for (const Integer& c : p.coefficients) result.coefficients.push_back(exact_quotient(c, divisor));
  return result;
}

Polynomial greatest_common_divisor(const Polynomial& a, const Polynomial& b) {
  Polynomial larger = primitive_part(a), smaller = primitive_part(b);
  if (larger.degree() < smaller.degree()) std::swap(larger, smaller);
  // Primitive remainder sequence: each step lowers the degree, so at most
  // deg(a) + 1 steps.
  while (!smaller.is_zero()) {
    Polynomial remainder = pseudo_remainder(std::move(larger), smaller);
    larger = std::move(smaller);
    smaller = primitive_part(remainder);
  }
  return larger;
}

std::optional<int> sign_at_isolated_root(const Polynomial& defining, int sign_below, const Polynomial& p,
                                         const Integer& low, const Integer& high, unsigned long exponent) {
  // Sturm and Sylvester: with R = p mod defining (times a positive constant),
  // the sign variations of the signed remainder sequence defining, R, ...
  // lost from low to high count the Cauchy index of R / defining there,
  // sign(R(r) defining'(r)) at its one root r, where defining' has the sign
  // -sign_below. The index is 0 where R(r) = 0 (the pole cancels).
  std::vector<Polynomial> sequence{defining, pseudo_remainder(p, defining)};
  while (!sequence.back().is_zero())
    sequence.push_back(-pseudo_remainder(sequence[sequence.size() - 2], sequence.back()));
  const auto variations = [&](const Integer& t) -> std::optional<int> {
    int count = 0, previous = 0;
    for (const Polynomial& q : sequence) {
      const int sign = sign_at_dyadic(q, t, exponent);
      if (&q == &sequence.front() && sign == 0) return std::nullopt;
      if (sign == 0) continue;
      count += previous != 0 && sign != previous;
      previous = sign;
    }
    return count;
  };
  const std::optional<int> at_low = variations(low), at_high = variations(high);
  if (!at_low || !at_high) return std::nullopt;
  return (*at_low - *at_high) * -sign_below;
}

bool divides(const Polynomial& b, const Polynomial& a) {
  return pseudo_remainder(a, b).is_zero();
}

Polynomial exact_quotient(const Polynomial& a, const Polynomial& b) {
  Polynomial remainder = a, quotient;
  if (a.degree() < b.degree()) return quotient;
  quotient.coefficients.resize(static_cast<std::size_t>(a.degree() - b.degree() + 1));
  while (!remainder.is_zero() && remainder.degree() >= b.degree()) {
    const std::size_t shift = static_cast<std::size_t>(remainder.degree() - b.degree());
    const Integer factor = exact_quotient(remainder.leading(), b.leading());
    for (std::size_t i = 0; i < b.coefficients.size(); ++i)
      remainder.coefficients[i + shift].subtract_product(factor, b.coefficients[i]);
    quotient.coefficients[shift] = factor;
    remainder.trim();
  }
  quotient.trim();
  return quotient;
}

Polynomial square_free_part(const Polynomial& p) {
  if (p.degree() <= 0) return primitive_part(p);
  const Polynomial repeated = greatest_common_divisor(p, derivative(p));
  return primitive_part(exact_quotient(primitive_part(p), repeated));
}

Polynomial square_free_union(const Polynomial& a, const Polynomial& b) {
  if (a.degree() <= 0) return b;
  if (b.degree() <= 0 || a.coefficients == b.coefficients) return a;
  return a * exact_quotient(b, greatest_common_divisor(a, b));
}

double log2_norm_bound(const Polynomial& p) {
  std::size_t bits = 1;
  for (const Integer& c : p.coefficients) bits = std::max(bits, c.bits());
  return static_cast<double>(bits) +
         0.5 * std::log2(static_cast<double>(p.coefficients.size()) + 1.0);
}

PolynomialVector operator+(const PolynomialVector& a, const PolynomialVector& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

PolynomialVector operator-(const PolynomialVector& a, const PolynomialVector& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

PolynomialVector operator-(const PolynomialVector& a) { return {-a[0], -a[1], -a[2]}; }

PolynomialVector cross(const PolynomialVector& a, const PolynomialVector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Polynomial dot(const PolynomialVector& a, const PolynomialVector& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace batchccd::exact

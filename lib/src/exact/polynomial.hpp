#pragma once

#include <array>
#include <optional>
#include <vector>

#include "exact/integer.hpp"

// Polynomials in the time t with integer coefficients: the exact stage's
// coplanarity cubic, normals, barycentric numerators (docs/design.md §2, §6) and
// the algebra root isolation needs (gcd, square-free part).
namespace batchccd::exact {

// coefficients[i] multiplies t^i; never a zero leading coefficient (the zero
// polynomial has none).
struct Polynomial {
  std::vector<Integer> coefficients;

  int degree() const { return static_cast<int>(coefficients.size()) - 1; }  // -1 for zero
  bool is_zero() const { return coefficients.empty(); }
  const Integer& leading() const { return coefficients.back(); }
  void trim();  // drops zero leading coefficients
};

Polynomial linear_polynomial(Integer constant, Integer slope);

Polynomial operator+(const Polynomial& a, const Polynomial& b);
Polynomial operator-(const Polynomial& a, const Polynomial& b);
Polynomial operator*(const Polynomial& a, const Polynomial& b);
Polynomial operator-(Polynomial a);

Polynomial derivative(const Polynomial& p);

// The sign of p(numerator / 2^exponent), computed exactly.
int sign_at_dyadic(const Polynomial& p, const Integer& numerator, unsigned long exponent);

// The sign of p at the one root r of `defining` in the open interval
// (low, high) 2^-exponent, a simple root, where defining has the sign
// `sign_below` on (low, r); exact, zero included, with no narrowing.
// nullopt when defining vanishes at an end.
std::optional<int> sign_at_isolated_root(const Polynomial& defining, int sign_below, const Polynomial& p,
                                         const Integer& low, const Integer& high, unsigned long exponent);

// p divided by the gcd of its coefficients, leading coefficient positive.
Polynomial primitive_part(const Polynomial& p);

// The gcd over the rationals, as a primitive polynomial with a positive
// leading coefficient (the zero polynomial when both are zero).
Polynomial greatest_common_divisor(const Polynomial& a, const Polynomial& b);

// Whether b divides a over the rationals (b nonzero).
bool divides(const Polynomial& b, const Polynomial& a);

// a / b where b is primitive and divides a (the quotient then has integer
// coefficients, Gauss's lemma).
Polynomial exact_quotient(const Polynomial& a, const Polynomial& b);

// The product of p's distinct irreducible factors, primitive: the same real
// roots, each simple.
Polynomial square_free_part(const Polynomial& p);

// A square-free polynomial whose roots are those of a and of b (a and b
// square-free and primitive).
Polynomial square_free_union(const Polynomial& a, const Polynomial& b);

// An upper bound of log2 of p's Euclidean coefficient norm, hence of its
// Mahler measure (Landau's inequality): what root separation bounds need.
double log2_norm_bound(const Polynomial& p);

// Vectors of polynomials: positions and normals that move with t.
using PolynomialVector = std::array<Polynomial, 3>;

PolynomialVector operator+(const PolynomialVector& a, const PolynomialVector& b);
PolynomialVector operator-(const PolynomialVector& a, const PolynomialVector& b);
PolynomialVector operator-(const PolynomialVector& a);
PolynomialVector cross(const PolynomialVector& a, const PolynomialVector& b);
Polynomial dot(const PolynomialVector& a, const PolynomialVector& b);

}  // namespace batchccd::exact

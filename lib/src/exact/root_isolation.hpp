#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "exact/polynomial.hpp"

// Exact real roots in [0, 1] (docs/design.md §2, §6: Descartes' rule after the
// Möbius map, Bernstein subdivision on dyadic intervals), and the exact sign
// of another polynomial at such a root. Every loop is bounded by the
// Davenport-Mahler root separation bound of the polynomials involved, so no
// call runs without limit; a result of std::nullopt means a bound was
// reached, which the mathematics says cannot happen.
namespace batchccd::exact {

// A root of a square-free polynomial q: exactly numerator / 2^exponent when
// `exact`, otherwise the only root of q in the open interval
// (numerator / 2^exponent, (numerator + 1) / 2^exponent), a simple one.
struct IsolatedRoot {
  Integer numerator;
  unsigned long exponent = 0;
  bool exact = false;
  int sign_after_low = 0;  // q's sign just above the interval's low end (not exact)
};

// 2^(exponent n) p((numerator + s) / 2^exponent): p on the dyadic interval,
// as a polynomial in s over [0, 1].
Polynomial on_dyadic_interval(const Polynomial& p, const Integer& numerator,
                              unsigned long exponent);

struct DescartesCount {
  // Sign changes of the Möbius transform (1 + x)^n p(1 / (1 + x)): at least
  // the number of roots in (0, 1) counted with multiplicity, of the same parity.
  int variations = 0;
  int sign_after_low = 0;  // p's sign just above 0
};
DescartesCount descartes_count(const Polynomial& local);

// Bisections after which a dyadic interval is narrower than the distance
// between any two distinct roots of a square-free polynomial of this degree
// whose Mahler measure is at most 2^log2_mahler (Davenport-Mahler).
unsigned long separation_bits(int degree, double log2_mahler);

// The roots of a square-free q in the open interval (0, 1), or in the open
// dyadic interval (numerator / 2^exponent, (numerator + 1) / 2^exponent),
// in increasing order.
std::optional<std::vector<IsolatedRoot>> isolate_roots(const Polynomial& square_free);

// The same roots of (0, 1) handed to `visit` one at a time in increasing
// order as they are isolated, until it returns true (stopped): a caller
// after the first root with some property isolates no later ones.
enum class RootVisit { finished, stopped, bound_reached };
RootVisit visit_roots(const Polynomial& square_free, const std::function<bool(IsolatedRoot&)>& visit);
std::optional<std::vector<IsolatedRoot>> isolate_roots(const Polynomial& square_free,
                                                       const Integer& numerator,
                                                       unsigned long exponent);

// Halves the root's interval (it may become exact).
void halve(IsolatedRoot& root, const Polynomial& square_free);

// gcd(p, square_free), which decides whether p vanishes at a root: asked
// for only when cheaper tests do not settle the sign (callers may cache it).
using CommonFactor = std::function<const Polynomial&()>;

// The exact sign of p at the root (of `square_free`), refining the root's
// interval as far as it takes.
std::optional<int> sign_at_root(const Polynomial& p, const CommonFactor& common, IsolatedRoot& root,
                                const Polynomial& square_free);

// A double not above the low end of the root's interval (the root itself when
// exact) and within 2^-63 of it: a certified lower bound of the root.
double lower_bound(const IsolatedRoot& root);

}  // namespace batchccd::exact

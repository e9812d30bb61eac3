#include "exact/exact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "exact/exact_motion.hpp"
#include "exact/expansion_stage.hpp"
#include "exact/origin_in_triangle.hpp"
#include "exact/root_isolation.hpp"

namespace batchccd::exact {
namespace {

IsolatedRoot exact_time(long value) { return {Integer(value), 0, true, 0}; }

// One square-free polynomial with every critical polynomial's roots.
Polynomial critical_union(const std::vector<TriangleConditions>& triangles) {
  Polynomial all;
  all.coefficients.push_back(Integer(1));
  for (const TriangleConditions& triangle : triangles)
    for (const Polynomial& p : critical_polynomials(triangle))
      all = square_free_union(all, square_free_part(p));
  return all;
}

// Signs of the conditions' polynomials at roots of the critical polynomial.
// Each polynomial's gcd with it (what decides a zero) is formed once.
class SignsAtRoots {
 public:
  explicit SignsAtRoots(const Polynomial& critical) : critical_(critical) {}

  std::optional<int> operator()(const Polynomial& p, IsolatedRoot& time) {
    const CommonFactor common = [&]() -> const Polynomial& {
      auto [entry, missing] = common_factors_.try_emplace(&p);
      if (missing) {
        // Where the critical polynomial divides p (the coplanarity cubic at
        // its own roots), a division is cheaper than a gcd.
        entry->second = divides(critical_, p) ? critical_ : greatest_common_divisor(p, critical_);
      }
      return entry->second;
    };
    return sign_at_root(p, common, time, critical_);
  }

 private:
  const Polynomial& critical_;
  std::map<const Polynomial*, Polynomial> common_factors_;  // polynomials outlive this
};

// x = numerator / 2^exponent exactly, for a finite x > 0.
IsolatedRoot as_dyadic(double x) {
  int binary_exponent = 0;
  const double mantissa = std::frexp(x, &binary_exponent);  // x = mantissa 2^e, mantissa in [1/2, 1)
  IsolatedRoot dyadic{Integer(), static_cast<unsigned long>(53 - binary_exponent), true, 0};
  mpz_set_d(dyadic.numerator.get(), std::ldexp(mantissa, 53));
  return dyadic;
}

// numerator * 2^(exponent - from): the same dyadic on a finer grid.
Integer on_grid(const Integer& numerator, unsigned long from, unsigned long exponent) {
  return shifted_left(numerator, exponent - from);
}

// Whether the root lies after `limit` (exact, from as_dyadic). A root's
// open interval is halved until the limit lies outside it: once the
// interval is no wider than the limit's grid, the limit is at most one of
// its ends, and halving is bounded by that grid's bits.
bool lies_after(IsolatedRoot& root, const IsolatedRoot& limit, const Polynomial& critical) {
  while (true) {
    const unsigned long grid = std::max(root.exponent, limit.exponent);
    const Integer low = on_grid(root.numerator, root.exponent, grid);
    const Integer bound = on_grid(limit.numerator, limit.exponent, grid);
    const int low_versus_limit = mpz_cmp(low.get(), bound.get());
    if (root.exact) return low_versus_limit > 0;
    if (low_versus_limit >= 0) return true;  // the root is above its interval's low end
    const Integer high = on_grid(root.numerator + Integer(1), root.exponent, grid);
    if (mpz_cmp(high.get(), bound.get()) <= 0) return false;
    halve(root, critical);
  }
}

}  // namespace

ExactOutcome solve_exactly(Kind kind, const Query& query, bool need_toi, double tmax) {
  if (const std::optional<ExactOutcome> outcome = solve_with_expansions(kind, query, need_toi, tmax)) return *outcome;
  return solve_with_integers(kind, query, need_toi, tmax);
}

ExactOutcome solve_with_integers(Kind kind, const Query& query, bool need_toi, double tmax) {
  std::vector<TriangleConditions> triangles;
  for (const MovingTriangle& triangle : difference_triangles(kind, exact_relative_motion(kind, query)))
    triangles.emplace_back(triangle);

  const Polynomial critical = critical_union(triangles);
  SignsAtRoots signs(critical);
  const IsolatedRoot limit = as_dyadic(tmax);
  // Candidate times in increasing order: 0, the critical polynomial's roots
  // as they are isolated, 1. The first one in contact is the TOI; past it,
  // or past tmax, nothing more is isolated.
  std::optional<ExactOutcome> outcome;
  const auto decide = [&](IsolatedRoot& time) {
    if (lies_after(time, limit, critical)) {
      outcome = ExactOutcome{};
      return true;
    }
    const SignAtTime sign = [&](const Polynomial& p) { return signs(p, time); };
    for (const TriangleConditions& triangle : triangles) {
      const std::optional<bool> inside = contains_origin(triangle, sign);
      if (!inside) {
        outcome = ExactOutcome{true, 0.0, true};
        return true;
      }
      if (*inside) {
        // Refine the root to the asked width: each halving keeps it inside.
        while (need_toi && !time.exact && time.exponent < kToiBits) halve(time, critical);
        outcome = ExactOutcome{true, lower_bound(time), false};
        return true;
      }
    }
    return false;
  };
  IsolatedRoot start = exact_time(0);
  if (decide(start)) return *outcome;
  if (visit_roots(critical, decide) == RootVisit::bound_reached) return {true, 0.0, true};
  if (outcome) return *outcome;
  IsolatedRoot end = exact_time(1);
  decide(end);
  return outcome.value_or(ExactOutcome{});
}

}  // namespace batchccd::exact

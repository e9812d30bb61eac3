#include "exact/root_isolation.hpp"

#include <cmath>
#include <utility>

namespace batchccd::exact {
namespace {

// p(x + shift), in place (repeated synthetic division, n^2 / 2 steps).
void taylor_shift(Polynomial& p, const Integer& shift) {
  auto& c = p.coefficients;
  const std::size_t n = c.size();
  if (n < 2 || shift.is_zero()) return;
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = n - 1; j-- > i;) c[j].add_product(shift, c[j + 1]);
}

// 2^n p(s / 2): p on the left half of its interval.
Polynomial left_half(const Polynomial& local) {
  Polynomial half = local;
  const std::size_t n = half.coefficients.size();
  for (std::size_t i = 0; i < n; ++i) half.coefficients[i].shift_left(n - 1 - i);
  return half;
}

struct Node {
  Polynomial local;  // the polynomial on this node's interval (unused for an exact root)
  Integer numerator;
  unsigned long exponent;
  bool exact_root;
};

}  // namespace

Polynomial on_dyadic_interval(const Polynomial& p, const Integer& numerator,
                              unsigned long exponent) {
  Polynomial local = p;
  const std::size_t n = local.coefficients.size();
  // c_i 2^(exponent (n-1-i)): p(x / 2^exponent) times 2^(exponent degree) ...
  for (std::size_t i = 0; i < n; ++i) local.coefficients[i].shift_left(exponent * (n - 1 - i));
  taylor_shift(local, numerator);  // ... then x = numerator + s
  return local;
}

DescartesCount descartes_count(const Polynomial& local) {
  DescartesCount count;
  for (const Integer& c : local.coefficients)
    if (!c.is_zero()) {
      count.sign_after_low = c.sign();
      break;
    }
  // (1 + x)^n p(1 / (1 + x)): reversed coefficients shifted by one.
  Polynomial transformed;
  transformed.coefficients.assign(local.coefficients.rbegin(), local.coefficients.rend());
  taylor_shift(transformed, Integer(1));
  int previous = 0;
  for (const Integer& c : transformed.coefficients) {
    const int sign = c.sign();
    if (sign == 0) continue;
    if (previous != 0 && sign != previous) ++count.variations;
    previous = sign;
  }
  return count;
}

unsigned long separation_bits(int degree, double log2_mahler) {
  // sep > sqrt(3) n^(-(n+2)/2) M^(1-n) for square-free integer polynomials
  // (Davenport-Mahler; the discriminant is a nonzero integer).
  if (degree < 2) return 1;
  const double n = degree;
  const double bits = 0.5 * (n + 2) * std::log2(n) + (n - 1) * log2_mahler;
  return static_cast<unsigned long>(std::ceil(bits)) + 1;
}

std::optional<std::vector<IsolatedRoot>> isolate_roots(const Polynomial& square_free) {
  return isolate_roots(square_free, Integer(0), 0);
}

namespace {

RootVisit visit_roots_in(const Polynomial& square_free, const Integer& numerator, unsigned long exponent,
                         const std::function<bool(IsolatedRoot&)>& visit) {
  if (square_free.degree() < 1) return RootVisit::finished;
  // Below this width an interval holds at most one root and its count says
  // so (one- and two-circle theorems): a deeper node cannot occur.
  const unsigned long depth_limit =
      separation_bits(square_free.degree(), log2_norm_bound(square_free)) + 4;
  std::vector<Node> stack;
  stack.push_back({on_dyadic_interval(square_free, numerator, exponent), numerator, exponent, false});
  while (!stack.empty()) {
    Node node = std::move(stack.back());
    stack.pop_back();
    if (node.exact_root) {
      IsolatedRoot root{std::move(node.numerator), node.exponent, true, 0};
      if (visit(root)) return RootVisit::stopped;
      continue;
    }
    const DescartesCount count = descartes_count(node.local);
    if (count.variations == 0) continue;
    if (count.variations == 1) {
      IsolatedRoot root{std::move(node.numerator), node.exponent, false, count.sign_after_low};
      if (visit(root)) return RootVisit::stopped;
      continue;
    }
    if (node.exponent >= depth_limit) return RootVisit::bound_reached;
    Polynomial left = left_half(node.local);
    Polynomial right = left;
    taylor_shift(right, Integer(1));
    const bool middle_is_root = right.coefficients.empty() || right.coefficients[0].is_zero();
    Integer middle = shifted_left(node.numerator, 1) + Integer(1);
    // Pushed right to left so they come off the stack in increasing order.
    stack.push_back({std::move(right), middle, node.exponent + 1, false});
    if (middle_is_root) stack.push_back({Polynomial{}, middle, node.exponent + 1, true});
    stack.push_back({std::move(left), shifted_left(node.numerator, 1), node.exponent + 1, false});
  }
  return RootVisit::finished;
}

}  // namespace

RootVisit visit_roots(const Polynomial& square_free, const std::function<bool(IsolatedRoot&)>& visit) {
  return visit_roots_in(square_free, Integer(0), 0, visit);
}

std::optional<std::vector<IsolatedRoot>> isolate_roots(const Polynomial& square_free,
                                                       const Integer& numerator,
                                                       unsigned long exponent) {
  std::vector<IsolatedRoot> roots;
  const auto collect = [&](IsolatedRoot& root) {
    roots.push_back(std::move(root));
    return false;
  };
  if (visit_roots_in(square_free, numerator, exponent, collect) == RootVisit::bound_reached) return std::nullopt;
  return roots;
}

void halve(IsolatedRoot& root, const Polynomial& square_free) {
  Integer middle = shifted_left(root.numerator, 1) + Integer(1);
  const int sign = sign_at_dyadic(square_free, middle, root.exponent + 1);
  ++root.exponent;
  if (sign == 0) {
    root.numerator = std::move(middle);
    root.exact = true;
  } else if (sign == root.sign_after_low) {  // no sign change on the left half
    root.numerator = std::move(middle);
  } else {
    root.numerator.shift_left(1);
  }
}

std::optional<int> sign_at_root(const Polynomial& p, const CommonFactor& common, IsolatedRoot& root,
                                const Polynomial& square_free) {
  if (p.is_zero()) return 0;
  // No root of p left in the interval: p has the one sign there.
  auto settled_sign = [&]() -> std::optional<int> {
    if (root.exact) return sign_at_dyadic(p, root.numerator, root.exponent);
    const DescartesCount count = descartes_count(on_dyadic_interval(p, root.numerator, root.exponent));
    if (count.variations == 0) return count.sign_after_low;
    return std::nullopt;
  };
  if (root.exact) return settled_sign();
  // Most nonzero signs settle at once or after a halving or two.
  constexpr int kQuickHalvings = 2;
  for (int attempt = 0;; ++attempt) {
    if (auto sign = settled_sign()) return sign;
    if (attempt == kQuickHalvings) break;
    halve(root, square_free);
  }
  // p(root) = 0 exactly when gcd(p, q) vanishes there. The gcd divides q, so
  // its only possible root in the interval is this one, and simple: a count
  // that is odd finds it (and a gcd of q's own degree is q).
  const Polynomial& divisor = common();
  if (divisor.degree() == square_free.degree()) return 0;
  if (divisor.degree() >= 1 &&
      descartes_count(on_dyadic_interval(divisor, root.numerator, root.exponent)).variations % 2 == 1)
    return 0;
  // p(root) != 0: once the interval is narrower than the distance from the
  // root to p's nearest root (bounded below by the separation of p q, whose
  // Mahler measure is at most ||p|| ||q||), the count is zero.
  const unsigned long limit =
      root.exponent + separation_bits(p.degree() + square_free.degree(),
                                      log2_norm_bound(p) + log2_norm_bound(square_free)) + 2;
  while (root.exponent <= limit) {
    if (auto sign = settled_sign()) return sign;
    halve(root, square_free);
  }
  return std::nullopt;
}

double lower_bound(const IsolatedRoot& root) {
  // Keep 64 fraction bits (floor), then truncate to a double: both round down.
  constexpr unsigned long kFractionBits = 64;
  Integer numerator = root.numerator;
  unsigned long exponent = root.exponent;
  if (exponent > kFractionBits) {
    mpz_fdiv_q_2exp(numerator.get(), numerator.get(), exponent - kFractionBits);
    exponent = kFractionBits;
  }
  return std::ldexp(mpz_get_d(numerator.get()), -static_cast<int>(exponent));
}

}  // namespace batchccd::exact

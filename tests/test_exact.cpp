// Exact mode (docs/design.md §6-7): decisions equal to exact arithmetic, a TOI
// within 1e-12 before the first contact, bounded work. The exact stage's
// algebra on its own; every degenerate class with answers worked out by
// hand (each coordinate exact in binary, so each answer is the exact one);
// TOIs known in closed form; the whole of ../shared/data, also transformed in
// ways that keep the exact answer; and the TOI promise of the other modes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "exact_distance.hpp"
#include "exact/exact_solver.hpp"
#include "exact/polynomial.hpp"
#include "exact/root_isolation.hpp"
#include "reference/inclusion_solver.hpp"
#include "reference/reference.hpp"
#include "query_builders.hpp"
#include "reference/scaled_query.hpp"
#include "same_answers.hpp"
#include "shared_data.hpp"

namespace batchccd {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kExactToiSlack = 1e-12;  // the promise of Mode::exact

// ---- the exact stage's algebra -----------------------------------------------

using exact::Integer;
using exact::IsolatedRoot;
using exact::Polynomial;

// (numerator t - denominator) for each pair, multiplied out.
Polynomial product_of_roots(const std::vector<std::pair<long, long>>& roots) {
  Polynomial p;
  p.coefficients.push_back(Integer(1));
  for (const auto& [numerator, denominator] : roots)
    p = p * exact::linear_polynomial(Integer(-numerator), Integer(denominator));
  return p;
}

double root_value_lower(const IsolatedRoot& root) { return exact::lower_bound(root); }
double root_value_upper(const IsolatedRoot& root) {
  return root.exact ? exact::lower_bound(root)
                    : std::ldexp(mpz_get_d(root.numerator.get()) + 1, -static_cast<int>(root.exponent));
}

TEST(ExactAlgebra, SquareFreePartKeepsEachRootOnce) {
  // (2t - 1)^2 (3t - 1)^3 (4t - 3)
  const Polynomial p = product_of_roots({{1, 2}, {1, 2}, {1, 3}, {1, 3}, {1, 3}, {3, 4}});
  const Polynomial square_free = exact::square_free_part(p);
  EXPECT_EQ(square_free.degree(), 3);
  EXPECT_TRUE(exact::divides(square_free, p));
  EXPECT_TRUE(exact::divides(product_of_roots({{1, 2}, {1, 3}, {3, 4}}), square_free));
}

TEST(ExactAlgebra, GcdFindsTheCommonRoots) {
  const Polynomial a = product_of_roots({{1, 3}, {1, 2}, {5, 7}});
  const Polynomial b = product_of_roots({{1, 2}, {5, 7}, {9, 10}});
  const Polynomial common = exact::greatest_common_divisor(a, b);
  EXPECT_EQ(common.degree(), 2);
  EXPECT_TRUE(exact::divides(common, a));
  EXPECT_TRUE(exact::divides(common, b));
  EXPECT_EQ(exact::greatest_common_divisor(a, product_of_roots({{1, 5}})).degree(), 0);
}

TEST(ExactAlgebra, RootsInTheUnitIntervalInOrderDyadicOnesExact) {
  // Roots 1/3, 1/2, 5/7, 3/4 in (0, 1); 7/5 and -1 outside.
  const Polynomial p = product_of_roots({{3, 4}, {1, 3}, {7, 5}, {5, 7}, {-1, 1}, {1, 2}});
  auto roots = exact::isolate_roots(p);
  ASSERT_TRUE(roots.has_value());
  ASSERT_EQ(roots->size(), 4u);
  const double expected[] = {1.0 / 3, 0.5, 5.0 / 7, 0.75};
  for (std::size_t i = 0; i < 4; ++i) {
    IsolatedRoot& root = (*roots)[i];
    while (!root.exact && root.exponent < 50) exact::halve(root, p);
    EXPECT_LE(root_value_lower(root), expected[i] + 1e-15) << i;
    EXPECT_GE(root_value_upper(root), expected[i] - 1e-15) << i;
    EXPECT_LT(root_value_upper(root) - root_value_lower(root), 1e-14) << i;
  }
  EXPECT_TRUE((*roots)[1].exact);  // 1/2 is found exactly, at a midpoint
  EXPECT_TRUE((*roots)[3].exact);
}

TEST(ExactAlgebra, RootsCloserThanDoublePrecisionAreSeparated) {
  // (2^62 t - 2^61)(2^62 t - 2^61 - 1): roots 1/2 and 1/2 + 2^-62.
  Polynomial p = exact::linear_polynomial(-exact::shifted_left(Integer(1), 61),
                                          exact::shifted_left(Integer(1), 62));
  p = p * exact::linear_polynomial(-(exact::shifted_left(Integer(1), 61) + Integer(1)),
                                   exact::shifted_left(Integer(1), 62));
  auto roots = exact::isolate_roots(p);
  ASSERT_TRUE(roots.has_value());
  EXPECT_EQ(roots->size(), 2u);
}

TEST(ExactAlgebra, SignAtARootIsExactZeroOrRefinedUntilSure) {
  const Polynomial q = product_of_roots({{1, 3}, {2, 3}});  // square-free
  auto roots = exact::isolate_roots(q);
  ASSERT_TRUE(roots.has_value());
  ASSERT_EQ(roots->size(), 2u);
  auto sign = [&](const Polynomial& p, IsolatedRoot& root) {
    const Polynomial common = exact::greatest_common_divisor(p, q);
    return exact::sign_at_root(p, [&]() -> const Polynomial& { return common; }, root, q);
  };
  IsolatedRoot third = (*roots)[0];
  EXPECT_EQ(sign(product_of_roots({{1, 3}}), third), 0);            // 3t - 1 vanishes
  EXPECT_EQ(sign(product_of_roots({{1, 3}, {9, 10}}), third), 0);   // so does a multiple
  // t - (1/3 + 2^-60) < 0 at 1/3: settled only after refining far.
  const Polynomial just_above = exact::linear_polynomial(
      -(exact::shifted_left(Integer(1), 60) + Integer(3)), Integer(3) * exact::shifted_left(Integer(1), 60));
  EXPECT_EQ(sign(just_above, third), -1);
  IsolatedRoot two_thirds = (*roots)[1];
  EXPECT_EQ(sign(just_above, two_thirds), 1);
  EXPECT_EQ(sign(product_of_roots({{1, 3}}), two_thirds), 1);
}

// The sign of p at a root of q from the remainder sequence alone, with no
// narrowing: every root rational, so that each sign is known from the
// factors, zeros included (p sharing the root's factor) and signs of p
// whose own root lies within the interval's width of q's.
TEST(ExactAlgebra, SignAtAnIsolatedRootFromTheRemainderSequence) {
  std::mt19937 random(7);
  std::uniform_int_distribution<long> small(-9, 9), denominator(1, 9);
  constexpr unsigned long kExponent = 20;  // intervals [k, k + 1] 2^-20
  int zeros = 0, near = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // q: three distinct rational roots in (0, 1), either overall sign.
    std::vector<std::pair<long, long>> roots;  // root = first / second
    while (roots.size() < 3) {
      const long d = denominator(random), n = std::uniform_int_distribution<long>(1, d)(random);
      const bool repeated =
          std::any_of(roots.begin(), roots.end(), [&](const auto& r) { return r.first * d == n * r.second; });
      if (n < d && !repeated) roots.push_back({n, d});
    }
    Polynomial q = product_of_roots(roots);
    if ((trial / 4) % 2) q = -q;  // not in step with the factor count below
    const auto [n, d] = roots[trial % 3];
    // [k, k + 1] 2^-20 holds n / d and no other root (roots differ by 1/81
    // at least), and q vanishes at neither end unless n / d is dyadic: then
    // it would be low itself, and the trial is skipped.
    if (const long reduced = d / std::gcd(n, d); (reduced & (reduced - 1)) == 0) continue;
    const Integer low(static_cast<long>(std::floor(std::ldexp(static_cast<double>(n) / d, kExponent))));
    const Integer high = low + Integer(1);
    const int sign_below = exact::sign_at_dyadic(q, low, kExponent);  // q's sign on (low, n / d)
    // p: up to four factors (a t - b), the first of them d t - n itself
    // for a third of the trials, or one whose root lies 2^-24 / d from n / d
    // for another third.
    std::vector<std::pair<long, long>> factors;
    const int count = 1 + trial % 4;
    int expected = 1;
    for (int f = 0; f < count; ++f) {
      long a = 0, b = 0;
      if (f == 0 && trial % 3 == 0) {
        a = d, b = n;
        ++zeros;
      } else if (f == 0 && trial % 3 == 1) {
        a = d << 24, b = (n << 24) + (trial % 2 ? 1 : -1);
        ++near;
      } else {
        while (a == 0) a = small(random);
        b = small(random);
      }
      factors.push_back({b, a});  // product_of_roots' (numerator t - denominator) is (a t - b)
      expected *= (a * n - b * d > 0) - (a * n - b * d < 0);  // sign of a (n / d) - b, d > 0
    }
    Polynomial p = product_of_roots(factors);
    const std::optional<int> sign = exact::sign_at_isolated_root(q, sign_below, p, low, high, kExponent);
    ASSERT_TRUE(sign.has_value()) << "trial " << trial;
    EXPECT_EQ(*sign, expected) << "trial " << trial << ": root " << n << "/" << d;
  }
  EXPECT_GT(zeros, 50);
  EXPECT_GT(near, 50);
}

TEST(ExactAlgebra, SignAtAnIsolatedRootDeclinesWhereTheIntervalEndsOnARoot) {
  const Polynomial q = product_of_roots({{1, 2}, {1, 3}, {3, 4}});
  // (1/4, 1/2) holds 1/3 alone, but q vanishes at 1/2.
  EXPECT_FALSE(exact::sign_at_isolated_root(q, -1, product_of_roots({{1, 5}}), Integer(1), Integer(2), 2));
}

TEST(ExactAlgebra, LowerBoundNeverAboveTheRoot) {
  IsolatedRoot half{Integer(1), 1, true, 0};
  EXPECT_EQ(exact::lower_bound(half), 0.5);
  // (2^70 + 1) / 2^71 just above 1/2: the bound rounds down.
  IsolatedRoot above{exact::shifted_left(Integer(1), 70) + Integer(1), 71, true, 0};
  EXPECT_EQ(exact::lower_bound(above), 0.5);
  IsolatedRoot below{exact::shifted_left(Integer(1), 70) - Integer(1), 71, true, 0};
  EXPECT_LT(exact::lower_bound(below), 0.5);
}

// ---- degenerate classes, exactly -------------------------------------------------

Vec3 V(double x, double y, double z) { return Vec3(x, y, z); }

using testing::at_rest;
using testing::from_points;

Options exact_options(bool need_toi = true) {
  Options options;
  options.mode = Mode::exact;
  options.need_toi = need_toi;
  return options;
}

// true_toi: the exact first contact (nullopt: never touching). The whole of
// exact mode and the exact stage alone must both get it.
// Near misses such as those below pass by 2^-50, each along an axis: the swept boxes
// (exact comparisons) cull them before any solver. Without the boxes they
// reach the solvers.
const lab::Settings kNoSweptBoxes{.swept_box_filter = false};
// The generic search alone: planar motion (several cases below) not decided
// in its plane, so the search's own tolerance shows.
const lab::Settings kGenericSearch{.swept_box_filter = false, .planar_path = false};

void check_exact(Kind kind, const Query& q, std::optional<long double> true_toi) {
  const QueryResult r = query_ccd(kind, q, exact_options());
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.hit, true_toi.has_value()) << "toi " << r.toi;
  if (r.hit && true_toi) {
    EXPECT_LE(static_cast<long double>(r.toi), *true_toi) << "toi after the first contact";
    EXPECT_LE(*true_toi - r.toi, kExactToiSlack) << "toi = " << r.toi;
  }
  if (!r.hit) {
    EXPECT_EQ(r.toi, kInfinity);
  }
  EXPECT_EQ(query_ccd(kind, q, exact_options(false)).hit, true_toi.has_value());
  EXPECT_EQ(lab::query_ccd(kind, q, exact_options(), kNoSweptBoxes).hit, true_toi.has_value()) << "solvers";

  const exact::ExactOutcome alone = exact::solve_exactly(kind, q, true);
  EXPECT_FALSE(alone.bound_reached);
  EXPECT_EQ(alone.hit, true_toi.has_value()) << "exact stage alone";
  if (alone.hit && true_toi) {
    EXPECT_LE(static_cast<long double>(alone.toi), *true_toi) << "exact stage alone";
    EXPECT_LE(*true_toi - alone.toi, kExactToiSlack) << "exact stage alone";
  }
}
void check_vf(const Query& q, std::optional<long double> true_toi) {
  check_exact(Kind::vertex_face, q, true_toi);
}
void check_ee(const Query& q, std::optional<long double> true_toi) {
  check_exact(Kind::edge_edge, q, true_toi);
}
const std::optional<long double> kMiss = std::nullopt;

// Conservative mode's floating-point search alone (no exact stage within
// its iterations) on the near misses below: it may report them, as its
// promise allows, but only with the primitives within tolerance of each
// other at the reported TOI (the exact distance there, against 4 tolerance
// times the widest extent of the query's points); exact mode must not.
void expect_conservative_only_within_tolerance(Kind kind, const Query& q) {
  Options options;
  options.exact_stage_iterations = options.max_iterations;
  const QueryResult r = lab::query_ccd(kind, q, options, kGenericSearch);
  if (!r.hit) return;
  double extent = 0;
  for (const Vec3& a : q.points)
    for (const Vec3& b : q.points) extent = std::max(extent, (a - b).cwiseAbs().maxCoeff());
  const testing::Rational reach = 4 * options.tolerance * extent;
  EXPECT_LE(testing::squared_distance_at(kind, q, r.toi), reach * reach) << "a hit at " << r.toi;
}

// The right triangle x, y >= 0, x + y <= 4 in the plane z = 0.
const Vec3 A = V(0, 0, 0), B = V(4, 0, 0), C = V(0, 4, 0);
const double kTiny = 0x1p-50;  // far below conservative mode's tolerance (1e-9 of ~4)

// Coplanar motion: d(t) == 0 for all t.

TEST(ExactCoplanarMotion, VertexSlidesIntoTriangle) {
  // p(t) = (-2 + 4t, 1, 0) reaches the edge x = 0 at t = 1/2.
  check_vf(from_points(V(-2, 1, 0), A, B, C, V(2, 1, 0), A, B, C), 0.5L);
}

TEST(ExactCoplanarMotion, VertexSlidesPastApexByATinyGap) {
  // p(t) = (-2 + 4t, 4 + 2^-50, 0) passes 2^-50 above the apex (0, 4, 0).
  const Query q = from_points(V(-2, 4 + kTiny, 0), A, B, C, V(2, 4 + kTiny, 0), A, B, C);
  expect_conservative_only_within_tolerance(Kind::vertex_face, q);
  check_vf(q, kMiss);
}

TEST(ExactCoplanarMotion, VertexSlidesExactlyThroughApex) {
  check_vf(from_points(V(-2, 4, 0), A, B, C, V(2, 4, 0), A, B, C), 0.5L);
}

TEST(ExactCoplanarMotion, TriangleSlidesOntoStaticVertex) {
  // The hypotenuse x + y = 4 + 4t reaches (5, 1, 0) at t = 1/2.
  check_vf(from_points(V(5, 1, 0), A, B, C, V(5, 1, 0), V(4, 0, 0), V(8, 0, 0), V(4, 4, 0)), 0.5L);
}

TEST(ExactCoplanarMotion, EdgesSlideIntoCrossing) {
  // Edge b's endpoint (3, -1 + 4t) reaches edge a (x axis, [0, 4]) at t = 1/4.
  check_ee(from_points(A, B, V(1, -2, 0), V(3, -1, 0), A, B, V(1, 2, 0), V(3, 3, 0)), 0.25L);
}

TEST(ExactCoplanarMotion, EdgesSlidePastByATinyGap) {
  // Edge b's endpoint (4 + 2^-50, -1 + 4t) passes just beyond edge a's end.
  const double x = 4 + kTiny;
  const Query q = from_points(A, B, V(x, -2, 0), V(6, -1, 0), A, B, V(x, 2, 0), V(6, 3, 0));
  check_ee(q, kMiss);
}

TEST(ExactCoplanarMotion, CollinearEdgesSlideIntoOverlap) {
  // Edge b = [2 - 4t, 3 - 4t] on edge a's line reaches edge a = [0, 1] at t = 1/4.
  check_ee(from_points(A, V(1, 0, 0), V(2, 0, 0), V(3, 0, 0), A, V(1, 0, 0), V(-2, 0, 0), V(-1, 0, 0)),
           0.25L);
}

TEST(ExactCoplanarMotion, RationalToiOfAThird) {
  // p(t) = (-1 + 3t, 1, 0) reaches the edge x = 0 at t = 1/3 (not dyadic).
  check_vf(from_points(V(-1, 1, 0), A, B, C, V(2, 1, 0), A, B, C), 1.0L / 3);
}

// A triangle that is degenerate at the root.

TEST(ExactDegenerateTriangle, CollapsesToASegmentWhereTheVertexLands) {
  // c(t) = (2, 4 - 8t, 0): the triangle is the segment [0, 4] of the x axis at
  // t = 1/2, when p(t) = (1, 0, 1 - 2t) reaches z = 0 on it.
  check_vf(from_points(V(1, 0, 1), A, B, V(2, 4, 0), V(1, 0, -1), A, B, V(2, -4, 0)), 0.5L);
}

TEST(ExactDegenerateTriangle, CollapsesToASegmentBesideTheVertex) {
  // The same with p 2^-50 beside the segment when it lands.
  const Query q = from_points(V(1, kTiny, 1), A, B, V(2, 4, 0), V(1, kTiny, -1), A, B, V(2, -4, 0));
  expect_conservative_only_within_tolerance(Kind::vertex_face, q);
  check_vf(q, kMiss);
}

TEST(ExactDegenerateTriangle, ZeroAreaInGeneralPosition) {
  // a = 0, b = c = (4, 2, 1): p(t) = (1 + 2t, 2 - 2t, -1/2 + 2t) meets the
  // segment at (2, 1, 1/2) at t = 1/2 only.
  const Vec3 b = V(4, 2, 1);
  check_vf(from_points(V(1, 2, -0.5), A, b, b, V(3, 0, 1.5), A, b, b), 0.5L);
}

TEST(ExactDegenerateTriangle, AllCornersOnePoint) {
  const Vec3 point = V(1, 1, 1);
  check_vf(from_points(V(1, 1, 0), point, point, point, V(1, 1, 2), point, point, point), 0.5L);
  check_vf(from_points(V(1, 1 + kTiny, 0), point, point, point, V(1, 1 + kTiny, 2), point, point, point),
           kMiss);
}

// Parallel and collinear edges.

TEST(ExactParallelEdges, BecomeCollinearOverlapping) {
  check_ee(from_points(A, B, V(2, 0, 1), V(6, 0, 1), A, B, V(2, 0, -1), V(6, 0, -1)), 0.5L);
}

TEST(ExactParallelEdges, BecomeCollinearInGeneralPosition) {
  check_ee(from_points(A, V(4, 2, 1), V(1, 2, 1.5), V(5, 4, 2.5), A, V(4, 2, 1), V(3, 0, -0.5),
                V(7, 2, 0.5)),
           0.5L);
}

TEST(ExactParallelEdges, TouchEndToEnd) {
  check_ee(from_points(A, B, V(4, 0, 1), V(6, 0, 1), A, B, V(4, 0, -1), V(6, 0, -1)), 0.5L);
}

TEST(ExactParallelEdges, CollinearWithATinyGap) {
  // Edge b = [4 + 2^-50, 6] lands on edge a's line just past its end.
  const double x = 4 + kTiny;
  const Query q = from_points(A, B, V(x, 0, 1), V(6, 0, 1), A, B, V(x, 0, -1), V(6, 0, -1));
  expect_conservative_only_within_tolerance(Kind::edge_edge, q);
  check_ee(q, kMiss);
}

TEST(ExactParallelEdges, PassOffset) {
  check_ee(from_points(A, B, V(2, 1, 1), V(6, 1, 1), A, B, V(2, 1, -1), V(6, 1, -1)), kMiss);
}

TEST(ExactParallelEdges, ZeroLengthEdgeThroughEdge) {
  check_ee(from_points(V(2, 0, 1), V(2, 0, 1), A, B, V(2, 0, -1), V(2, 0, -1), A, B), 0.5L);
  check_ee(from_points(V(2, kTiny, 1), V(2, kTiny, 1), A, B, V(2, kTiny, -1), V(2, kTiny, -1), A, B),
           kMiss);
}

// Double and triple roots of the coplanarity cubic.

TEST(ExactMultipleRoots, DoubleRootGrazingInsideFace) {
  // Plane z = (t - 1/2) y, p(t) = (1, 2t, t - 1/2): d = -2 (t - 1/2)^2, p at
  // (1, 1, 0) inside at t = 1/2.
  check_vf(from_points(V(1, 0, -0.5), A, B, V(0, 4, -2), V(1, 2, 0.5), A, B, V(0, 4, 2)), 0.5L);
}

TEST(ExactMultipleRoots, DoubleRootGrazingExactlyOnAnEdge) {
  // The same motion at x = 0: p(1/2) = (0, 1, 0) lies on edge ca.
  check_vf(from_points(V(0, 0, -0.5), A, B, V(0, 4, -2), V(0, 2, 0.5), A, B, V(0, 4, 2)), 0.5L);
}

TEST(ExactMultipleRoots, DoubleRootGrazingJustOutsideAnEdge) {
  // At x = -2^-50 the grazing point is 2^-50 outside edge ca, within the
  // floating-point search's tolerance; the vertex stays in x = -2^-50 and
  // the edge in x = 0, so an outside proof can exclude it at every time.
  const Query q =
      from_points(V(-kTiny, 0, -0.5), A, B, V(0, 4, -2), V(-kTiny, 2, 0.5), A, B, V(0, 4, 2));
  expect_conservative_only_within_tolerance(Kind::vertex_face, q);
  check_vf(q, kMiss);
}

TEST(ExactMultipleRoots, DoubleRootEdgesCrossingAndApart) {
  check_ee(from_points(A, V(0, 4, -2), B, V(-4, 0, -0.5), A, V(0, 4, 2), B, V(-4, 2, 0.5)), 0.5L);
  check_ee(from_points(V(0, 2, -1), V(0, 4, -2), B, V(-4, 0, -0.5), V(0, 2, 1), V(0, 4, 2), B,
                V(-4, 2, 0.5)),
           kMiss);
}

TEST(ExactMultipleRoots, TripleRootsLocatedToTheAskedWidth) {
  // d = (2t - 1)^3 (see test_degenerate.cpp): conservative mode may stop up
  // to 1e-3 early here; exact mode must be within 1e-12.
  const Vec3 origin = V(0, 0, 0);
  check_vf(from_points(V(-0.25, 0, -0.75), origin, V(-1, 1, 0), V(0, -1, 1), V(0.25, 0.5, 1.25), origin,
                V(1, 1, 0), V(0, 1, 1)),
           0.5L);
  check_vf(from_points(V(-1, 0, 0), origin, V(-1, 1, 0), V(0, -1, 1), V(1, 2, 2), origin, V(1, 1, 0),
                V(0, 1, 1)),
           kMiss);
  check_ee(from_points(origin, V(-1, 1, 0), V(0, -1, 1), V(-1, 2, -2), origin, V(1, 1, 0), V(0, 1, 1),
                V(1, 0, 0)),
           0.5L);
  check_ee(from_points(origin, V(-1, 1, 0), V(0, -1, 1), V(-3, 4, -2), origin, V(1, 1, 0), V(0, 1, 1),
                V(3, 2, 0)),
           kMiss);
}

// Contact exactly at t = 0 or t = 1.

TEST(ExactStepEnds, ContactAtTimeZeroAndOne) {
  check_vf(from_points(V(1, 1, 0), A, B, C, V(1, 1, 1), A, B, C), 0.0L);
  check_vf(from_points(V(1, 1, 1), A, B, C, V(1, 1, 0), A, B, C), 1.0L);
  check_vf(from_points(V(4, 0, 2), A, B, C, V(4, 0, 0), A, B, C), 1.0L);  // onto corner b
  check_ee(from_points(A, B, V(2, -1, 0), V(2, 1, 0), A, B, V(2, -1, 1), V(2, 1, 1)), 0.0L);
  check_ee(from_points(A, B, V(2, -1, 1), V(2, 1, 1), A, B, V(2, -1, 0), V(2, 1, 0)), 1.0L);
}

TEST(ExactStepEnds, StopsATinyGapShortAtTimeOne) {
  check_vf(from_points(V(1, 1, 1), A, B, C, V(1, 1, kTiny), A, B, C), kMiss);
  check_ee(from_points(A, B, V(2, -1, 1), V(2, 1, 1), A, B, V(2, -1, kTiny), V(2, 1, kTiny)), kMiss);
}

TEST(ExactStepEnds, StartsATinyGapAwayAndLeaves) {
  check_vf(from_points(V(1, 1, kTiny), A, B, C, V(1, 1, 1), A, B, C), kMiss);
}

// Vertices shared between the two primitives.

TEST(ExactSharedVertices, EdgesShareAnEndpointThroughout) {
  check_ee(from_points(A, B, A, V(0, 4, 1), A, V(4, 1, 0), A, V(1, 4, 0)), 0.0L);
}

TEST(ExactSharedVertices, VertexIsATriangleCorner) {
  check_vf(from_points(A, A, B, C, V(1, 1, 1), V(1, 1, 1), V(5, 1, 0), V(0, 4, 3)), 0.0L);
}

TEST(ExactSharedVertices, EndpointRunsIntoTheOtherEdgesEndpointAtTheEnd) {
  check_ee(from_points(A, B, V(2, 2, 2), V(2, 4, 2), A, B, A, V(2, 4, 2)), 1.0L);
}

TEST(ExactSharedVertices, AdjacentTrianglesEdgeAgainstTheirSharedEdge) {
  // Edges (0,0,0)-(4,0,0) of two triangles that share it, moving together.
  check_ee(from_points(A, B, B, A, V(1, 1, 1), V(5, 1, 1), V(5, 1, 1), V(1, 1, 1)), 0.0L);
}

// Coincident points and extreme magnitudes.

TEST(ExactMagnitudes, EverythingOnePointTouches) {
  const Vec3 point = V(1, 1, 1);
  check_vf(at_rest(point, point, point, point), 0.0L);
  check_ee(from_points(point, point, point, point, V(3, 2, 1), V(3, 2, 1), V(3, 2, 1), V(3, 2, 1)), 0.0L);
}

TEST(ExactMagnitudes, DifferenceBelowWhatScalingKeeps) {
  // Corners at 2^1000 on the x axis, the vertex 2^-1000 beside them: the
  // scaled floating-point frame flushes the gap to zero, exact arithmetic
  // does not.
  const double far = 0x1p1000, gap = 0x1p-1000;
  const Vec3 corner = V(far, 0, 0);
  check_vf(at_rest(V(far, gap, 0), corner, corner, corner), kMiss);
  check_vf(at_rest(corner, corner, corner, corner), 0.0L);
}

TEST(ExactMagnitudes, HugeAndTinyScalesGiveTheSameAnswer) {
  for (int exponent : {-1000, -500, 0, 500, 960}) {
    const double s = std::ldexp(1.0, exponent);
    SCOPED_TRACE(exponent);
    check_vf(from_points(V(1, 1, 1) * s, A * s, B * s, C * s, V(1, 1, -2) * s, A * s, B * s, C * s),
             1.0L / 3);
    check_vf(from_points(V(-2, 4 + kTiny, 0) * s, A * s, B * s, C * s, V(2, 4 + kTiny, 0) * s, A * s,
                  B * s, C * s),
             kMiss);
  }
}

// ---- TOI in closed form --------------------------------------------------------

TEST(ExactToi, ThirdFifthAndThreeSevenths) {
  // p(t) = (1, 1, z0 + t (z1 - z0)) reaches the static face at -z0 / (z1 - z0).
  check_vf(from_points(V(1, 1, 1), A, B, C, V(1, 1, -2), A, B, C), 1.0L / 3);
  check_vf(from_points(V(1, 1, 1), A, B, C, V(1, 1, -4), A, B, C), 1.0L / 5);
  check_vf(from_points(V(1, 1, 3), A, B, C, V(1, 1, -4), A, B, C), 3.0L / 7);
}

TEST(ExactToi, IrrationalOneOverSquareRootOfTwo) {
  // Plane z = (t - 1/2) y through a, b and c(t) = (0, 4, 4t - 2); p(t) =
  // (1, 2 - 2t, -2 + 3t): pz - (t - 1/2) py = 2 (t^2 - 1/2), zero at
  // t = 1/sqrt(2), where p = (1, 0.59, .) projects inside the triangle.
  check_vf(from_points(V(1, 2, -2), A, B, V(0, 4, -2), V(1, 0, 1), A, B, V(0, 4, 2)),
           0.70710678118654752440084436210485L);
}

TEST(ExactToi, SlowMotionNeedsTheExactRootOfACertainContact) {
  // Triangle a = 0, b = (4, 1, 2), c = (1, 4, 3), normal 5 (-1, -2, 3); the
  // vertex crosses it at q = (b + c) / 4 along the normal, 2^-16 of the size
  // per step: p(t) = q + 2^-16 (1 - 3t) (-1, -2, 3), at q when t = 1/3. The
  // cubic's floating-point signs prove the contact but cannot narrow it to
  // 1e-12 (the terms of d are ~1e5 times d' there); its exact root can.
  const double h = 0x1p-16;
  const Vec3 a = V(0, 0, 0), b = V(4, 1, 2), c = V(1, 4, 3), q_point = V(1.25, 1.25, 1.25);
  const Vec3 normal = V(-1, -2, 3);
  const Query q = from_points(q_point + h * normal, a, b, c, q_point - 2 * h * normal, a, b, c);
  check_vf(q, 1.0L / 3);
  const reference::Evaluation e = reference::evaluate_query(Kind::vertex_face, q, exact_options(), {});
  EXPECT_EQ(e.exact_stage, reference::ExactStage::toi);
  // The certified path's own verdict: a certain contact, a TOI bracket wider
  // than 2^-40 (so only the root was left to exact arithmetic).
  reference::SolverSettings settings;
  settings.refined_toi_width = 0x1p-40;
  const reference::SolverOutcome outcome = reference::solve_inclusion(
      Kind::vertex_face, reference::scale_query(Kind::vertex_face, q), settings);
  EXPECT_TRUE(outcome.hit);
  EXPECT_TRUE(outcome.certain);
  EXPECT_GT(outcome.toi_upper - outcome.toi, 0x1p-40);
  EXPECT_LE(outcome.toi, 1.0 / 3);
  EXPECT_GE(outcome.toi_upper, 1.0 / 3);
}

TEST(ExactToi, CleanCrossingNeedsNoExactArithmetic) {
  const Query q = from_points(V(1, 1, 1), A, B, C, V(1, 1, -2), A, B, C);
  const reference::Evaluation e = reference::evaluate_query(Kind::vertex_face, q, exact_options(), {});
  EXPECT_TRUE(e.result.hit);
  EXPECT_EQ(e.exact_stage, reference::ExactStage::none);
  EXPECT_LE(e.result.toi, 1.0 / 3);
  EXPECT_LE(1.0 / 3 - e.result.toi, kExactToiSlack);
}

// ---- the exact stage against the certified path ---------------------------------

// Queries on a coarse integer grid: coplanar, collinear, coincident and
// touching configurations are common there. Where the certified path is
// certain, the exact stage (a different method) must agree with it; the
// whole exact mode must agree with the exact stage; conservative mode must
// report every exact contact, never after it.
TEST(ExactAgainstCertified, RandomGridQueriesAgree) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(-2, 2);
  int certain = 0, hits = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Query q;
    for (Vec3& p : q.points) p = V(coordinate(random), coordinate(random), coordinate(random));
    if (trial % 3 == 0)  // some points that do not move
      for (int k = 0; k < 4; ++k)
        if (random() % 2) q.points[k + 4] = q.points[k];
    for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << " " << to_string(kind));
      const exact::ExactOutcome alone = exact::solve_exactly(kind, q, true);
      ASSERT_FALSE(alone.bound_reached);
      hits += alone.hit;
      const QueryResult whole = query_ccd(kind, q, exact_options());
      EXPECT_EQ(whole.hit, alone.hit);
      if (whole.hit) {
        EXPECT_LE(std::fabs(whole.toi - alone.toi), 0x1p-40);
      }
      const QueryResult conservative = query_ccd(kind, q);
      if (alone.hit) {
        EXPECT_TRUE(conservative.hit);
        EXPECT_LE(conservative.toi, alone.toi + 0x1p-40);
      }
      const reference::ScaledQuery scaled = reference::scale_query(kind, q);
      if (scaled.coincident) continue;
      reference::SolverSettings settings;
      settings.refined_toi_width = 0x1p-40;
      const reference::SolverOutcome outcome = reference::solve_inclusion(kind, scaled, settings);
      if (!outcome.certain) continue;
      ++certain;
      EXPECT_EQ(outcome.hit, alone.hit);
      if (outcome.hit && alone.hit) {
        EXPECT_LE(outcome.toi, alone.toi + 0x1p-40);
        EXPECT_GE(outcome.toi_upper, alone.toi);
      }
    }
  }
  EXPECT_GT(certain, 1000);
  EXPECT_GT(hits, 1000);
}

// ---- counters ----------------------------------------------------------------------

// The batch counters against what each query did on the scalar reference
// path (which stage settled it, reference::evaluate_query), whatever the
// certified path can settle today; and the answers against exact truth.
TEST(ExactCounters, BatchCountsEscalationsAndTimesQueriesOnlyWhenAsked) {
  const double x = 4 + kTiny;
  const std::vector<Query> queries = {
      from_points(A, B, V(2, -1, 1), V(2, 1, 1), A, B, V(2, -1, -2), V(2, 1, -2)),  // clean, at 1/3
      from_points(A, B, V(x, 0, 1), V(6, 0, 1), A, B, V(x, 0, -1), V(6, 0, -1)),    // near miss
  };
  const auto expect_counted = [&](const Options& options, const lab::Settings& stages, const std::string& what) {
    const BatchResult batch = lab::batch_ccd(Kind::edge_edge, queries, options, stages);
    std::int64_t escalated = 0, hits = 0, undecided = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const reference::Evaluation alone = reference::evaluate_query(Kind::edge_edge, queries[i], options, stages);
      escalated += alone.exact_stage != reference::ExactStage::none;
      hits += alone.result.hit;
      undecided += alone.undecided;
      EXPECT_EQ(batch.results[i].hit, alone.result.hit) << what << " query " << i;
      // Exact arithmetic's answer is the truth: the near miss never touches.
      if (i == 1 && alone.exact_stage != reference::ExactStage::none) {
        EXPECT_FALSE(alone.result.hit) << what;
      }
    }
    EXPECT_EQ(batch.counters.exact_escalations, escalated) << what;
    EXPECT_EQ(batch.counters.hits, hits) << what;
    EXPECT_EQ(batch.counters.undecided, undecided) << what;
    EXPECT_TRUE(batch.results[0].hit) << what;  // never a false negative
    EXPECT_LE(batch.results[0].toi, 1.0 / 3) << what;
    return batch;
  };
  Options options = exact_options();
  BatchResult batch = expect_counted(options, kNoSweptBoxes, "exact");
  EXPECT_FALSE(batch.results[1].hit);
  EXPECT_EQ(batch.counters.max_query_seconds, 0.0);
  EXPECT_EQ(batch.counters.solved_seconds, 0.0);
  EXPECT_EQ(batch.counters.escalated_seconds, 0.0);
  // Timing the queries changes no answer and no count.
  options.time_queries = true;
  const BatchResult timed = expect_counted(options, kNoSweptBoxes, "exact, timed");
  testing::expect_same_answers(timed, batch, "timed");
  EXPECT_EQ(timed.counters.exact_escalations, batch.counters.exact_escalations);
  // The near miss's swept boxes are apart along x (edge b in x >= 4 + 2^-50
  // throughout, edge a in [0, 4]): the first filter culls it, by exact comparisons.
  EXPECT_EQ(batch_ccd(Kind::edge_edge, queries, exact_options()).counters.culled_by_swept_box, 1);
  // Both lie in the plane y = 0; the generic search with a long budget and
  // with a short one before the exact stage.
  options.time_queries = false;
  options.mode = Mode::conservative;
  std::int64_t escalated = 0;
  for (const std::int64_t budget : {options.max_iterations, std::int64_t{16}, std::int64_t{0}}) {
    options.exact_stage_iterations = budget;
    escalated += expect_counted(options, kGenericSearch, "conservative, budget " + std::to_string(budget))
                     .counters.exact_escalations;
  }
  // Some budget leaves the near miss to exact arithmetic, else the counts above compare zeros.
  EXPECT_GT(escalated, 0);
}

// ---- the shared data ---------------------------------------------------------------

struct LabeledQuery {
  Kind kind;
  Query query;
  bool truth;
};

// Every sample query, and every stride-th candidate of each scene.
std::vector<LabeledQuery> shared_queries(std::size_t scene_stride) {
  std::vector<LabeledQuery> all;
  for (const std::filesystem::path& path : testing::shared_query_files()) {
    const std::optional<Kind> kind = kind_from_path(path);
    if (!kind) continue;
    const QueryFile file = read_query_csv(path, *kind);
    for (std::size_t i = 0; i < file.queries.size(); ++i)
      all.push_back({*kind, file.queries[i], file.truth.value().at(i)});
  }
  for (const std::filesystem::path& directory : testing::shared_scene_directories()) {
    const Scene scene = read_scene(directory);
    const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
    const auto& vf = scene.candidates.vertex_face;
    for (std::size_t i = 0; i < vf.size(); i += scene_stride)
      all.push_back({Kind::vertex_face, vertex_face_query(mesh, vf[i]), scene.vertex_face_truth.value().at(i)});
    const auto& ee = scene.candidates.edge_edge;
    for (std::size_t i = 0; i < ee.size(); i += scene_stride)
      all.push_back({Kind::edge_edge, edge_edge_query(mesh, ee[i]), scene.edge_edge_truth.value().at(i)});
  }
  return all;
}

// Every input of ../shared/data with one thread by `method`, run once per
// method for the tests below.
const std::vector<testing::DataRun>& run_shared_data(const lab::Method& method) {
  static std::map<std::string, std::vector<testing::DataRun>> runs;
  auto run = runs.find(lab::to_string(method));
  if (run == runs.end()) {
    Options options;
    options.threads = 1;
    run = runs.emplace(lab::to_string(method), testing::run_shared_data(method, options)).first;
  }
  return run->second;
}

class ExactSharedData : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!testing::shared_data_present()) GTEST_SKIP() << testing::kSharedData << " is absent";
  }
};

// Exact mode over every input: no error against the files' truth.
// Throughput against conservative mode and the escalations are printed for
// the record (README, Results).
TEST_F(ExactSharedData, NoFalsePositiveAndNoFalseNegative) {
  const auto& exact_run = run_shared_data(lab::kExact);
  const auto& conservative_run = run_shared_data(lab::kConservative);
  ASSERT_FALSE(exact_run.empty());
  std::int64_t queries = 0, escalations = 0;
  double exact_seconds = 0, conservative_seconds = 0, slowest = 0;
  for (const testing::DataRun& run : exact_run) {
    ASSERT_TRUE(run.truth.has_value()) << run.input;
    EXPECT_EQ(run.false_negatives(), 0) << run.input << " " << to_string(run.kind);
    EXPECT_EQ(run.false_positives(), 0) << run.input << " " << to_string(run.kind);
    queries += static_cast<std::int64_t>(run.results.size());
    escalations += run.counters.exact_escalations;
    exact_seconds += run.seconds;
    slowest = std::max(slowest, run.counters.max_query_seconds);
  }
  ASSERT_EQ(conservative_run.size(), exact_run.size());
  for (std::size_t r = 0; r < conservative_run.size(); ++r) {
    const testing::DataRun& run = conservative_run[r];
    conservative_seconds += run.seconds;
    // Conservative mode escalates what exact mode does but the contacts
    // within tolerance.
    EXPECT_LE(run.counters.exact_escalations, exact_run[r].counters.exact_escalations) << run.input;
  }
  std::printf("[ record   ] exact: %lld queries, %lld escalations (%.2f %%), %.3f s vs "
              "conservative %.3f s (throughput %.2fx), slowest query %.2f ms (wall)\n",
              static_cast<long long>(queries), static_cast<long long>(escalations),
              100.0 * static_cast<double>(escalations) / static_cast<double>(queries),
              exact_seconds, conservative_seconds, conservative_seconds / exact_seconds,
              1e3 * slowest);
}

// The TOI promise of conservative mode, against the exact first contact
// (within 2^-40): never a contact after it; the fast and cubic baselines
// promise nothing but well-formed results.
TEST_F(ExactSharedData, OtherMethodsToiAgainstTheExactFirstContact) {
  const auto& exact_run = run_shared_data(lab::kExact);
  for (const lab::Method& method : {lab::kConservative, lab::kFast, lab::kCubic}) {
    const auto& run = run_shared_data(method);
    ASSERT_EQ(run.size(), exact_run.size());
    double latest_lead = 0;  // how much before the first contact conservative reports
    for (std::size_t r = 0; r < run.size(); ++r) {
      const auto& results = run[r].results;
      const auto& exact_results = exact_run[r].results;
      ASSERT_EQ(results.size(), exact_results.size());
      for (std::size_t i = 0; i < results.size(); ++i) {
        const QueryResult& result = results[i];
        if (!result.hit) {
          EXPECT_EQ(result.toi, kInfinity);
          continue;
        }
        EXPECT_GE(result.toi, 0.0);
        EXPECT_LE(result.toi, 1.0);
        if (method == lab::kConservative && exact_results[i].hit) {
          EXPECT_LE(result.toi, exact_results[i].toi + 0x1p-40)
              << run[r].input << " query " << i;
          latest_lead = std::max(latest_lead, exact_results[i].toi - result.toi);
        }
      }
    }
    if (method == lab::kConservative)
      std::printf("[ record   ] conservative toi at most %.3g before the exact first contact\n",
                  latest_lead);
  }
}

// ---- transforms that keep the exact answer ------------------------------------------

using Transform = Query (*)(Kind, const Query&);

template <int Exponent>
Query scaled(Kind, const Query& q) {
  return testing::scaled(q, Exponent);
}

template <int X, int Y, int Z>
Query axes_permuted(Kind, const Query& q) {
  return testing::axes_permuted(q, {X, Y, Z});
}

template <int SX, int SY, int SZ>
Query signs_flipped(Kind, const Query& q) {
  return testing::axes_flipped(q, (SX < 0 ? 1 : 0) | (SY < 0 ? 2 : 0) | (SZ < 0 ? 4 : 0));
}

Query time_reversed(Kind, const Query& q) { return testing::time_reversed(q); }

using testing::reordered;

// VF (p, a, b, c): the triangle rotated, or mirrored. EE (ea0, ea1, eb0,
// eb1): the edges swapped, or one reversed.
Query first_reorder(Kind kind, const Query& q) {
  return reordered(q, kind == Kind::vertex_face ? std::array<int, 4>{0, 2, 3, 1}
                                                : std::array<int, 4>{2, 3, 0, 1});
}
Query second_reorder(Kind kind, const Query& q) {
  return reordered(q, kind == Kind::vertex_face ? std::array<int, 4>{0, 3, 1, 2}
                                                : std::array<int, 4>{1, 0, 2, 3});
}
Query third_reorder(Kind kind, const Query& q) {
  return reordered(q, kind == Kind::vertex_face ? std::array<int, 4>{0, 1, 3, 2}
                                                : std::array<int, 4>{0, 1, 3, 2});
}

struct NamedTransform {
  const char* name;
  Transform apply;
};

const NamedTransform kTransforms[] = {
    {"scale 2^-500", scaled<-500>},
    {"scale 2^-37", scaled<-37>},
    {"scale 2^61", scaled<61>},
    {"scale 2^500", scaled<500>},
    {"axes yzx", axes_permuted<1, 2, 0>},
    {"axes zxy", axes_permuted<2, 0, 1>},
    {"axes xzy", axes_permuted<0, 2, 1>},
    {"flip x", signs_flipped<-1, 1, 1>},
    {"flip y", signs_flipped<1, -1, 1>},
    {"flip z", signs_flipped<1, 1, -1>},
    {"flip xyz", signs_flipped<-1, -1, -1>},
    {"time reversed", time_reversed},
    {"vertex order 1", first_reorder},
    {"vertex order 2", second_reorder},
    {"vertex order 3", third_reorder},
};

// Every sample query and every 8th scene candidate under each transform
// alone, then all of them under one random combination each (a fixed seed).
TEST_F(ExactSharedData, TransformsThatKeepTheAnswerKeepIt) {
  const std::vector<LabeledQuery> queries = shared_queries(8);
  ASSERT_FALSE(queries.empty());
  for (const NamedTransform& transform : kTransforms) {
    std::int64_t wrong = 0;
    for (const LabeledQuery& q : queries) {
      const QueryResult r = query_ccd(q.kind, transform.apply(q.kind, q.query), exact_options());
      wrong += r.hit != q.truth;
    }
    EXPECT_EQ(wrong, 0) << transform.name << ": wrong decisions among " << queries.size();
  }
  std::mt19937 random(20240611);
  std::int64_t wrong = 0;
  for (const LabeledQuery& q : queries) {
    Query query = q.query;
    constexpr std::size_t kScales = 4;  // the first four; one scale comes last instead
    for (int step = 0; step < 4; ++step) {
      const std::size_t pick = kScales + random() % (std::size(kTransforms) - kScales);
      query = kTransforms[pick].apply(q.kind, query);
    }
    // Any power of two in [2^-500, 2^500] last (the scale transforms compose).
    const int exponent = static_cast<int>(random() % 1001) - 500;
    for (Vec3& p : query.points) p *= std::ldexp(1.0, exponent);
    wrong += query_ccd(q.kind, query, exact_options()).hit != q.truth;
  }
  EXPECT_EQ(wrong, 0) << "random combinations";
}

}  // namespace
}  // namespace batchccd

// The scalar reference path's building blocks: scaling, Bernstein form,
// sign filter, solvers.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include <gmpxx.h>

#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"
#include "reference/bernstein.hpp"
#include "reference/cubic_solver.hpp"
#include "reference/filter.hpp"
#include "reference/inclusion_solver.hpp"
#include "reference/inside_proof.hpp"
#include "reference/sign_filter.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::reference {
namespace {

Query vertex_falling_through_triangle() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return {{Vec3(0.25, 0.25, 1), a, b, c, Vec3(0.25, 0.25, -1), a, b, c}};
}

Query far_apart_vertex_face() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return {{Vec3(0.25, 0.25, 3), a, b, c, Vec3(0.25, 0.25, 2), a, b, c}};
}

TEST(ScaledQuery, LargestDifferenceIsNormalised) {
  const ScaledQuery scaled = scale_query(Kind::vertex_face, vertex_falling_through_triangle());
  double largest = 0;
  for (const auto& pair : scaled.relative)
    for (const Vec3& v : pair) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  EXPECT_GE(largest, 1.0);
  EXPECT_LT(largest, 2.0);
  EXPECT_TRUE(scaled.finite);
  EXPECT_FALSE(scaled.coincident);
}

TEST(ScaledQuery, PowerOfTwoScalingGivesTheSameFrame) {
  const Query query = vertex_falling_through_triangle();
  const ScaledQuery reference = scale_query(Kind::vertex_face, query);
  for (int exponent : {-1000, -500, -3, 5, 500, 1000}) {
    Query scaled_input = query;
    for (Vec3& p : scaled_input.points) p *= std::ldexp(1.0, exponent);
    const ScaledQuery scaled = scale_query(Kind::vertex_face, scaled_input);
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau)
        EXPECT_EQ(scaled.relative[i][tau], reference.relative[i][tau]) << "exponent " << exponent;
  }
}

TEST(ScaledQuery, HugeCoordinatesDoNotOverflow) {
  Query query = vertex_falling_through_triangle();
  query.points[0] = Vec3(1.5e308, -1.7e308, 1e308);
  const ScaledQuery scaled = scale_query(Kind::vertex_face, query);
  for (const auto& pair : scaled.relative)
    for (const Vec3& v : pair) EXPECT_TRUE(v.allFinite());
}

TEST(ScaledQuery, FlagsNonFiniteAndCoincidentInput) {
  Query query = vertex_falling_through_triangle();
  query.points[5][1] = std::nan("");
  EXPECT_FALSE(scale_query(Kind::vertex_face, query).finite);
  Query point{};
  for (Vec3& p : point.points) p = Vec3(3, 3, 3);
  EXPECT_TRUE(scale_query(Kind::edge_edge, point).coincident);
}

// The Bernstein coefficients from the geometry give the same cubic as the
// geometry: d(t) = (a(t) x b(t)) . c(t), compared in rationals at four
// times (two cubics equal at four points are equal). On small integers the
// double coefficients are exact, so any error in the form shows.
TEST(Bernstein, MatchesTheGeometryExactly) {
  using Rational = mpq_class;
  std::mt19937_64 random(7);
  std::uniform_int_distribution<int> small(-8, 8);
  for (int trial = 0; trial < 200; ++trial) {
    Vector3<double> p[6];
    for (auto& v : p) v = {double(small(random)), double(small(random)), double(small(random))};
    const BernsteinCubic<double> cubic = bernstein_cubic(p[0], p[1], p[2], p[3], p[4], p[5]);
    for (const Rational& t : {Rational(0), Rational(1, 3), Rational(5, 7), Rational(1)}) {
      const auto at = [&t](const Vector3<double>& a, const Vector3<double>& b) {
        return std::array<Rational, 3>{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
      };
      const auto a = at(p[0], p[1]), b = at(p[2], p[3]), c = at(p[4], p[5]);
      const Rational direct = (a[1] * b[2] - a[2] * b[1]) * c[0] + (a[2] * b[0] - a[0] * b[2]) * c[1] +
                              (a[0] * b[1] - a[1] * b[0]) * c[2];
      const Rational s = 1 - t;
      const Rational bernstein = cubic.coefficient[0] * s * s * s + cubic.coefficient[1] * s * s * t +
                                 cubic.coefficient[2] * s * t * t + cubic.coefficient[3] * t * t * t;
      EXPECT_EQ(direct, bernstein) << "trial " << trial << ", t = " << t;
    }
  }
}

TEST(SignFilter, CullsSeparatedQueries) {
  EXPECT_TRUE(sign_filter_culls(scale_query(Kind::vertex_face, far_apart_vertex_face()), true));
  EXPECT_TRUE(sign_filter_culls(scale_query(Kind::vertex_face, far_apart_vertex_face()), false));
}

TEST(SignFilter, KeepsCrossingsAndCoplanarMotion) {
  EXPECT_FALSE(sign_filter_culls(scale_query(Kind::vertex_face, vertex_falling_through_triangle()), true));
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Query coplanar{{Vec3(-1, 0.25, 0), a, b, c, Vec3(0.5, 0.25, 0), a, b, c}};
  EXPECT_FALSE(sign_filter_culls(scale_query(Kind::vertex_face, coplanar), true));
  EXPECT_FALSE(sign_filter_culls(scale_query(Kind::vertex_face, coplanar), false));
}

// V = 2 without a root: only the subdivision at 1/2 culls it.
TEST(SignFilter, SubdivisionSettlesVEqualsTwo) {
  // 8 d(t) with d = (2t - 1)^2 + 1/8: scaled Bernstein coefficients (9, -5, -5, 9).
  const SignTest<double> test{{{9, -5, -5, 9}, {9, 5, 5, 9}}, 0.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(test.whole());
  EXPECT_TRUE(test.halves());
  // (2t - 1)^2 touches zero at 1/2: never culled.
  const SignTest<double> touching{{{1, -1, -1, 1}, {1, 1, 1, 1}}, 0.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(touching.whole());
  EXPECT_FALSE(touching.halves());
}

TEST(SignFilter, CertifiedCullsAreASubsetOfPlainCulls) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int certified_culls = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Query query;
    for (Vec3& p : query.points) p = Vec3(coordinate(random), coordinate(random), coordinate(random));
    for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const ScaledQuery scaled = scale_query(kind, query);
      const bool certified = sign_filter_culls(scaled, true);
      certified_culls += certified;
      if (certified) {
        EXPECT_TRUE(sign_filter_culls(scaled, false));
      }
    }
  }
  EXPECT_GT(certified_culls, 0);
}

// Each filter works in its direct frame (differences in the input's units)
// inside its window and in the scaled frame outside it: scaling a query by a
// power of two moves it across both edges of the window, and generic
// queries keep their verdicts at every scale. Vertices move by up to
// `motion` (coordinates in [-1, 1]).
void expect_verdicts_independent_of_units(const FilterSettings& settings, double motion,
                                          std::initializer_list<int> exponents) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int culled = 0, kept = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Query query;
    for (int k = 0; k < 4; ++k) {
      query.points[k] = Vec3(coordinate(random), coordinate(random), coordinate(random));
      query.points[k + 4] =
          query.points[k] + motion * Vec3(coordinate(random), coordinate(random), coordinate(random));
    }
    for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const bool verdict = run_filters(kind, query, settings).culled();
      (verdict ? culled : kept) += 1;
      for (int exponent : exponents) {
        Query scaled = query;
        for (Vec3& p : scaled.points) p *= std::ldexp(1.0, exponent);
        EXPECT_EQ(run_filters(kind, scaled, settings).culled(), verdict)
            << "trial " << trial << ", 2^" << exponent;
      }
    }
  }
  EXPECT_GT(culled, 1000);
  EXPECT_GT(kept, 1000);
}

TEST(SignFilter, VerdictsDoNotDependOnUnitsAcrossTheDirectFramesWindow) {
  // Differences up to 6, most of them above 1: scales 2^197 to 2^200 put
  // the largest about the window's top, 2^-202 to 2^-199 about its bottom;
  // 2^600 and 2^-600 well outside. (Fails when the direct frame's floor is
  // too large for the bottom of the window.)
  expect_verdicts_independent_of_units({.sign = true, .separation = false, .swept_box = false}, 2.0,
                                       {-1000, -600, -202, -201, -200, -199, 197, 198, 199, 200, 600, 1000});
}

TEST(SeparationFilter, VerdictsDoNotDependOnUnitsAcrossTheDirectFramesWindow) {
  // Its window is [2^-40, 2^40] (differences up to 3.2); 2^-190 and 2^190
  // would underflow or overflow in it.
  expect_verdicts_independent_of_units({.sign = false, .separation = true, .pieces = 1, .swept_box = false}, 0.6,
                                       {-1000, -600, -190, -100, -42, -41, -40, -39, 37, 38, 39, 40, 100, 190, 600, 1000});
}

// The swept boxes run in the sign filter's frames, direct and scaled.
TEST(SweptBoxFilter, VerdictsDoNotDependOnUnitsAcrossTheDirectFramesWindow) {
  expect_verdicts_independent_of_units({.sign = false, .separation = false, .pieces = 1, .swept_box = true}, 2.0,
                                       {-1000, -600, -202, -201, -200, -199, 197, 198, 199, 200, 600, 1000});
}

// The pieces run in the separation filter's direct frame only (outside it
// the whole-step filters decide alone), where scaling by a power of two
// changes nothing either.
TEST(PiecewiseFilter, VerdictsDoNotDependOnUnitsWithinTheDirectWindow) {
  for (const int pieces : {2, 4, 8})
    for (const bool swept_box : {false, true})
      expect_verdicts_independent_of_units({.sign = true, .separation = true, .pieces = pieces, .swept_box = swept_box},
                                           1.5, {-38, -30, -12, 12, 30, 37});
}

// Queries that touch exactly at t = 1/2, and near misses beside them: on a
// grid of 2^-10 with dyadic weights, x(1/2) = (x0 + x1) / 2 is the chosen
// contact configuration in exact arithmetic; a near miss moves the vertex
// (VF) or one edge (EE) at both ends by a small random offset.
struct MidStepQueries {
  std::mt19937_64 random{18};
  double grid() {
    return std::ldexp(static_cast<double>(std::uniform_int_distribution<int>(-1024, 1024)(random)), -10);
  }
  Vec3 point() { return Vec3(grid(), grid(), grid()); }
  int eighths() { return std::uniform_int_distribution<int>(1, 6)(random); }

  // Vertex p or edge b moved by `offset` at t = 0 and t = 1 (0: touching).
  Query next(Kind kind, const Vec3& offset, double speed) {
    Vec3 at_half[4];  // the points in the order x1..x4 at t = 1/2
    at_half[0] = point(), at_half[1] = point(), at_half[2] = point();
    if (kind == Kind::vertex_face) {
      const int alpha = eighths(), beta = std::uniform_int_distribution<int>(1, 7 - alpha)(random);
      at_half[3] = (alpha * at_half[0] + beta * at_half[1] + (8 - alpha - beta) * at_half[2]) / 8 + offset;
    } else {
      const int lambda = eighths();  // the edges cross at x1 + lambda/8 (x2 - x1), the middle of x3 x4
      const Vec3 crossing = ((8 - lambda) * at_half[0] + lambda * at_half[1]) / 8;
      at_half[2] += offset;
      at_half[3] = 2 * crossing - at_half[2] + 2 * offset;
    }
    Query q;
    for (int k = 1; k <= 4; ++k) {
      const Vec3 velocity = speed * point();
      q.points[point_index(kind, k)] = at_half[k - 1] - velocity;
      q.points[point_index(kind, k) + 4] = at_half[k - 1] + velocity;
    }
    return q;
  }
};

// No cull of a contact in the middle of the step, by any stage, with or
// without a separation; near misses there are culled by the pieces, and
// every query any stage culls is a miss by the unfiltered exact path.
TEST(PiecewiseFilter, CullsNoContactInTheMiddleOfTheStep) {
  MidStepQueries queries;
  int culled_by_pieces = 0, near_misses_culled = 0;
  for (int trial = 0; trial < 600; ++trial) {
    for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const double speed = std::ldexp(1.0, -(trial % 8));  // motion from grid-sized to tiny
      const Vec3 direction = queries.point().normalized();
      const double gap = std::ldexp(1.0, -4 - trial % 12);
      const Query touching = queries.next(kind, Vec3::Zero(), speed);
      const Query near_miss = queries.next(kind, gap * direction, speed);
      for (const int pieces : {1, 2, 4, 8})
        for (const bool swept_box : {false, true})
          for (const double separation : {0.0, 0.5 * gap, gap}) {
            const FilterSettings settings{.pieces = pieces, .swept_box = swept_box, .within = separation > 0,
                                          .min_distance = separation};
            EXPECT_FALSE(run_filters(kind, touching, settings).culled())
                << to_string(kind) << " trial " << trial << " pieces " << pieces << " separation " << separation;
            const FilterVerdict verdict = run_filters(kind, near_miss, settings);
            culled_by_pieces += verdict.pieces;
            if (verdict.culled() && pieces >= 4 && swept_box && separation < gap) {
              ++near_misses_culled;
              const Options exact{.mode = Mode::exact, .min_distance = separation};
              const lab::Settings unfiltered{.sign_filter = false, .separation_filter = false, .swept_box_filter = false};
              EXPECT_FALSE(lab::query_ccd(kind, near_miss, exact, unfiltered).hit)
                  << to_string(kind) << " trial " << trial << " separation " << separation;
            }
          }
    }
  }
  EXPECT_GT(culled_by_pieces, 10);
  EXPECT_GT(near_misses_culled, 100);
}

TEST(InclusionSolver, FindsTheCrossingTime) {
  const ScaledQuery scaled = scale_query(Kind::vertex_face, vertex_falling_through_triangle());
  const SolverOutcome outcome = solve_inclusion(Kind::vertex_face, scaled, {});
  EXPECT_TRUE(outcome.hit);
  EXPECT_LE(outcome.toi, 0.5);
  EXPECT_GE(outcome.toi, 0.5 - 1e-7);
  EXPECT_FALSE(outcome.undecided);
}

TEST(InclusionSolver, StopsAtTheIterationLimitConservatively) {
  const ScaledQuery scaled = scale_query(Kind::vertex_face, vertex_falling_through_triangle());
  SolverSettings settings;
  settings.max_iterations = 3;
  const SolverOutcome outcome = solve_inclusion(Kind::vertex_face, scaled, settings);
  EXPECT_TRUE(outcome.hit);
  EXPECT_TRUE(outcome.undecided);
  EXPECT_LE(outcome.toi, 0.5);
}

// Edge x1x2 stands on the plane of the still edge x3x4, and x1 crosses
// x3x4 next to x3 at t = 1/3: a contact at an edge's end (u = 0), where no
// inside test is certain. The cubic narrows time to its root first; a
// search at every halving used to spend a thousand boxes and escalate.
// (The modes now hand such a query to the exact stage after 32 boxes,
// Options::exact_stage_iterations: its expansions settle it for less.)
TEST(InclusionSolver, SettlesAContactAtAnEdgesEndWithinTheExactStagesBudget) {
  Query query;
  const Vec3 x1(0.01, 0, -0.1), x1_end(0.017, 0, 0.2), up(0.3, 1, 0.2);
  query.points = {x1, x1 + up, Vec3(0, 0, 0), Vec3(1, 0, 0), x1_end, x1_end + up, Vec3(0, 0, 0), Vec3(1, 0, 0)};
  SolverSettings settings;
  settings.max_iterations = 1 << 10;
  const SolverOutcome outcome = solve_inclusion(Kind::edge_edge, scale_query(Kind::edge_edge, query), settings);
  EXPECT_TRUE(outcome.hit);
  EXPECT_FALSE(outcome.undecided);
  EXPECT_LE(outcome.toi, 1.0 / 3);
  EXPECT_GE(outcome.toi, 1.0 / 3 - settings.toi_tolerance);
}

// Positions relative to x1 held still (zero-radius balls), in the order of
// PositionBalls: x2, x3, x4.
PositionBalls still(const Vec3& x2, const Vec3& x3, const Vec3& x4) {
  PositionBalls balls;
  const Vec3 points[3] = {x2, x3, x4};
  for (int i = 0; i < 3; ++i) balls[i] = {Ball{points[i][0], 0}, Ball{points[i][1], 0}, Ball{points[i][2], 0}};
  return balls;
}

TEST(InsideProof, InsideOutsideAndNeither) {
  const Vec3 b(1, 0, 0), c(0, 1, 0);
  // Vertex-face, a at the origin: inside, outside past edge bc, on edge bc, degenerate triangle.
  EXPECT_TRUE(certainly_inside(Kind::vertex_face, still(b, c, Vec3(0.25, 0.25, 0))));
  EXPECT_FALSE(certainly_outside(Kind::vertex_face, still(b, c, Vec3(0.25, 0.25, 0))));
  EXPECT_TRUE(certainly_outside(Kind::vertex_face, still(b, c, Vec3(2, 2, 0))));
  EXPECT_TRUE(certainly_outside(Kind::vertex_face, still(b, c, Vec3(-0.5, 0.25, 0))));
  EXPECT_FALSE(certainly_inside(Kind::vertex_face, still(b, c, Vec3(2, 2, 0))));
  for (const Vec3& p : {Vec3(0.5, 0.5, 0), Vec3(0, 0.5, 0)}) {
    EXPECT_FALSE(certainly_inside(Kind::vertex_face, still(b, c, p)));
    EXPECT_FALSE(certainly_outside(Kind::vertex_face, still(b, c, p)));
  }
  EXPECT_FALSE(certainly_outside(Kind::vertex_face, still(b, b, Vec3(5, 5, 0))));
  // Edge-edge, edge a from the origin to x2, edge b from x3 to x4: crossing,
  // missing past a's end, touching at a's end, parallel.
  EXPECT_TRUE(certainly_inside(Kind::edge_edge, still(b, Vec3(0.5, -1, 0), Vec3(0.5, 1, 0))));
  EXPECT_FALSE(certainly_outside(Kind::edge_edge, still(b, Vec3(0.5, -1, 0), Vec3(0.5, 1, 0))));
  EXPECT_TRUE(certainly_outside(Kind::edge_edge, still(b, Vec3(2, -1, 0), Vec3(2, 1, 0))));
  EXPECT_TRUE(certainly_outside(Kind::edge_edge, still(b, Vec3(0.5, 1, 0), Vec3(0.5, 3, 0))));
  EXPECT_FALSE(certainly_outside(Kind::edge_edge, still(b, Vec3(1, -1, 0), Vec3(1, 1, 0))));
  EXPECT_FALSE(certainly_outside(Kind::edge_edge, still(b, Vec3(5, 1, 0), Vec3(6, 1, 0))));
  // A point as a zero-length edge: never proven either way.
  EXPECT_FALSE(certainly_outside(Kind::edge_edge, still(Vec3(0, 0, 0), Vec3(5, -1, 0), Vec3(5, 1, 0))));
}

// Intervals the outside proof drops never held a contact: the solver's
// decisions with it equal exact mode's on crossings that pass near a
// triangle's edges and corners in the middle of the step.
TEST(InsideProof, SolverDecisionsMatchExactNearEdges) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> offset(-1e-3, 1e-3);
  int hits = 0, misses = 0;
  for (int i = 0; i < 2000; ++i) {
    // The vertex crosses the plane z = 0 at t = 1/2 near edge bc or corner b.
    const double x = (i % 2 ? 0.5 : 1.0) + offset(random), y = (i % 2 ? 0.5 : 0.0) + offset(random);
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), drift(offset(random), offset(random), 0);
    const Query query{{Vec3(x, y, 1) - drift, a, b, c, Vec3(x, y, -1) + drift, a, b, c}};
    const QueryResult exact = query_ccd(Kind::vertex_face, query, {.mode = Mode::exact});
    const QueryResult conservative = query_ccd(Kind::vertex_face, query, {});
    EXPECT_EQ(conservative.hit, exact.hit) << i;
    (exact.hit ? hits : misses) += 1;
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 500);
}

TEST(CubicSolver, FindsACleanCrossing) {
  const QueryResult result = solve_cubic(Kind::vertex_face, vertex_falling_through_triangle());
  EXPECT_TRUE(result.hit);
  EXPECT_NEAR(result.toi, 0.5, 1e-12);
  EXPECT_FALSE(solve_cubic(Kind::vertex_face, far_apart_vertex_face()).hit);
}

TEST(Methods, AgreeOnCleanQueries) {
  for (const lab::Method& method : {lab::kConservative, lab::kExact, lab::kFast, lab::kCubic}) {
    const Options options = method.applied_to({});
    EXPECT_TRUE(lab::query_ccd(Kind::vertex_face, vertex_falling_through_triangle(), options, method.settings()).hit)
        << lab::to_string(method);
    EXPECT_FALSE(lab::query_ccd(Kind::vertex_face, far_apart_vertex_face(), options, method.settings()).hit)
        << lab::to_string(method);
  }
}

}  // namespace
}  // namespace batchccd::reference

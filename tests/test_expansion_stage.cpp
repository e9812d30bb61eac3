// The exact stage's floating-point expansions (docs/design.md §6a): the
// arithmetic against GMP rationals, and the stage's decisions against the
// same queries decided with integers alone, on families that reach every
// branch: generic crossings, contacts exactly on an edge or at a corner
// (zeros at the root, from the remainder sequence), near misses a few ulps off them (the filter's margins),
// contacts at t = 0 and t = 1, tmax, and scales 2^+-400.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include <gmpxx.h>

#include "batchccd/batchccd.hpp"
#include "exact/exact_solver.hpp"
#include "exact/expansion.hpp"
#include "exact/expansion_stage.hpp"
#include "exact/first_root.hpp"
#include "query_builders.hpp"

namespace batchccd {
namespace {

using exact::BoundedExpansion;
using exact::ExactOutcome;

mpq_class rational(double value) { return mpq_class(value); }

// --- The arithmetic -------------------------------------------------------

double random_double(std::mt19937_64& random) {
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-60, 60);
  return std::ldexp(mantissa(random), exponent(random));
}

TEST(BoundedExpansion, SignsOfRandomExpressionsEqualRationalArithmetic) {
  std::mt19937_64 random(1);
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = random_double(random), b = random_double(random), c = random_double(random),
                 d = random_double(random);
    // a b - c d, and (a - b)(c - d) - (a c - a d - b c + b d): the second
    // is exactly zero, which only exact arithmetic finds.
    const BoundedExpansion x = BoundedExpansion(a) * BoundedExpansion(b) - BoundedExpansion(c) * BoundedExpansion(d);
    const mpq_class exact_x = rational(a) * rational(b) - rational(c) * rational(d);
    ASSERT_EQ(x.sign(), sgn(exact_x)) << a << " " << b << " " << c << " " << d;
    ASSERT_NEAR(x.estimate(), exact_x.get_d(), 1e-15 * std::fabs(exact_x.get_d()));
    const BoundedExpansion product = BoundedExpansion::difference(a, b) * BoundedExpansion::difference(c, d);
    const BoundedExpansion expanded = BoundedExpansion(a) * BoundedExpansion(c) - BoundedExpansion(a) * BoundedExpansion(d) -
                                      BoundedExpansion(b) * BoundedExpansion(c) + BoundedExpansion(b) * BoundedExpansion(d);
    ASSERT_EQ((product - expanded).sign(), 0);
    ASSERT_EQ(product.sign(), sgn((rational(a) - rational(b)) * (rational(c) - rational(d))));
  }
}

TEST(BoundedExpansion, ScalingByADoubleIsExact) {
  std::mt19937_64 random(2);
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = random_double(random), b = random_double(random), c = random_double(random);
    const BoundedExpansion scaled = BoundedExpansion::difference(a, b) * c;
    const mpq_class exact = (rational(a) - rational(b)) * rational(c);
    ASSERT_EQ(scaled.sign(), sgn(exact));
    ASSERT_EQ((scaled - BoundedExpansion(a) * BoundedExpansion(c) + BoundedExpansion(b) * BoundedExpansion(c)).sign(), 0);
  }
}

TEST(BoundedExpansion, AResultLongerThanItsCapacityThrowsInsteadOfRounding) {
  // Terms 2^60 apart never merge into one double: 30 terms.
  BoundedExpansion sum;
  EXPECT_THROW(
      {
        for (int k = 0; k < 30; ++k) sum = sum + BoundedExpansion(std::ldexp(1.0, 900 - 60 * k));
      },
      BoundedExpansion::TooLong);
}

// --- The stage ------------------------------------------------------------

Query make_query(const std::array<Vec3, 4>& start, const std::array<Vec3, 4>& end) {
  Query query;
  for (int i = 0; i < 4; ++i) {
    query.points[i] = start[i];
    query.points[i + 4] = end[i];
  }
  return query;
}

struct Tally {
  int decided = 0, hits = 0;  // by the expansions, with the TOI asked for
};

// The expansion stage, where it answers, answers as integers do: the same
// decision, and a TOI within 2^-40 of theirs (both are lower bounds of the
// contact within 2^-40 of it); without the TOI asked for, a lower bound.
void expect_as_integers(Kind kind, const Query& query, double tmax, Tally& tally) {
  const ExactOutcome integers = exact::solve_with_integers(kind, query, true, tmax);
  ASSERT_FALSE(integers.bound_reached);
  for (const bool need_toi : {true, false}) {
    const std::optional<ExactOutcome> expansions = exact::solve_with_expansions(kind, query, need_toi, tmax);
    if (!expansions) continue;
    ASSERT_EQ(expansions->hit, integers.hit) << to_string(kind) << " tmax " << tmax;
    if (need_toi) {
      ++tally.decided;
      tally.hits += integers.hit;
    }
    if (!integers.hit) continue;
    EXPECT_LE(expansions->toi, tmax);
    EXPECT_LE(expansions->toi, integers.toi + 0x1p-40) << to_string(kind);
    if (need_toi) {
      EXPECT_GE(expansions->toi, integers.toi - 0x1p-40) << to_string(kind);
    }
  }
}

// Random points on a 2^-8 grid: contacts whose parameters are exact
// dyadics (on an edge, at a corner) come often, and so do exact roots.
Vec3 grid_point(std::mt19937_64& random) {
  std::uniform_int_distribution<int> coordinate(-64, 64);
  return Vec3(coordinate(random), coordinate(random), coordinate(random)) / 256.0;
}

Query random_grid_query(std::mt19937_64& random) {
  std::array<Vec3, 4> start, end;
  for (int i = 0; i < 4; ++i) {
    start[i] = grid_point(random);
    end[i] = grid_point(random);
  }
  return make_query(start, end);
}

// A contact placed exactly on an edge or at a corner at t = 1/q, q in
// {2, 3, 5}: the vertex (or edge b's first point) meets edge a at parameter
// s in {0, 1/2, 1}. Every coordinate stays exact; for q = 3 and 5 the root
// is no dyadic, and only the remainder sequence can tell the contact is on
// the boundary.
Query boundary_contact(Kind kind, std::mt19937_64& random) {
  std::uniform_int_distribution<int> pick(0, 2);
  const double s = pick(random) / 2.0, q = std::array{2.0, 3.0, 5.0}[pick(random)];
  std::array<Vec3, 4> start, end;
  for (int i = 0; i < 4; ++i) {
    start[i] = grid_point(random);
    end[i] = grid_point(random);
  }
  const int a0 = kind == Kind::vertex_face ? 1 : 0, a1 = a0 + 1;  // file order: VF p, a, b, c
  const int mover = kind == Kind::vertex_face ? 0 : 2;
  // q times the meeting point, then the mover's end that reaches it at 1/q.
  const Vec3 meet_q = (1 - s) * ((q - 1) * start[a0] + end[a0]) + s * ((q - 1) * start[a1] + end[a1]);
  end[mover] = meet_q - (q - 1) * start[mover];
  return make_query(start, end);
}

// One coordinate moved by a few ulps: a near miss or near hit beside an
// exact boundary contact, where the filter's bounds decide.
Query jittered(Query query, std::mt19937_64& random) {
  std::uniform_int_distribution<int> point(0, 7), axis(0, 2), ulps(-3, 3);
  double& value = query.points[point(random)][axis(random)];
  for (int k = ulps(random); k != 0; k += k > 0 ? -1 : 1)
    value = std::nextafter(value, k > 0 ? 1e300 : -1e300);
  return query;
}

using testing::scaled;

TEST(ExpansionStage, DecidesAsIntegersOnRandomGridQueries) {
  std::mt19937_64 random(3);
  Tally tally;
  for (int trial = 0; trial < 1500; ++trial)
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
      expect_as_integers(kind, random_grid_query(random), 1.0, tally);
  EXPECT_GT(tally.hits, 50);  // the family does reach contacts
}

TEST(ExpansionStage, DecidesAsIntegersOnContactsOnAnEdgeOrACornerAndBesideThem) {
  std::mt19937_64 random(4);
  constexpr int kQueries = 1200;
  Tally exact_contacts, near_contacts;
  for (int trial = 0; trial < kQueries / 2; ++trial)
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const Query query = boundary_contact(kind, random);
      expect_as_integers(kind, query, 1.0, exact_contacts);
      expect_as_integers(kind, jittered(query, random), 1.0, near_contacts);
    }
  // Every query of the first family is a contact; the remainder sequence
  // settles most without the integer stage, and the slope tests most of
  // the second.
  EXPECT_EQ(exact_contacts.hits, exact_contacts.decided);
  EXPECT_GT(exact_contacts.decided, kQueries * 3 / 4);
  EXPECT_GT(near_contacts.decided, kQueries * 2 / 3);
  std::printf("[ record   ] boundary contacts: %d of %d decided by expansions; a few ulps off them: %d (%d hits)\n",
              exact_contacts.decided, kQueries, near_contacts.decided, near_contacts.hits);
}

// expect_as_integers (tmax 1) on `queries` queries of a family, half of
// each kind: family(kind, random, trial) makes one.
template <class Family>
Tally decide_family(std::uint64_t seed, int queries, Family family) {
  std::mt19937_64 random(seed);
  Tally tally;
  for (int trial = 0; trial < queries / 2; ++trial)
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
      expect_as_integers(kind, family(kind, random, trial), 1.0, tally);
  return tally;
}

// One axis scaled by 2^exponent: exact, and an affine map, so a contact on
// an edge stays exactly there while the coordinates spread over binades.
Query axis_scaled(Query query, int axis, int exponent) {
  for (Vec3& point : query.points) point[axis] = std::ldexp(point[axis], exponent);
  return query;
}

TEST(ExpansionStage, DecidesContactsOnAnEdgeWithCoordinatesSpreadOverManyBinades) {
  // A remainder sequence outgrows expansions here (terms of the
  // coefficients 2^100 and more apart); in integers it must still settle
  // the contact without leaving the query to the integer stage.
  constexpr int kQueries = 200;
  const Tally tally = decide_family(7, kQueries, [](Kind kind, std::mt19937_64& random, int trial) {
    return axis_scaled(boundary_contact(kind, random), trial % 3, -50);
  });
  EXPECT_EQ(tally.decided, kQueries);
  EXPECT_EQ(tally.hits, kQueries);
}

TEST(ExpansionStage, TellsASharedFactorElsewhereFromAZeroAtTheRoot) {
  // A vertex placed on a corner at t = 1/5, then one coordinate moved by
  // an ulp: a miss, where the cubic and a contact numerator still share a
  // factor, whose zero is not the root in question. A sign test that took
  // any common factor for a zero at the root reported a contact at 1/5.
  // (Found by fuzz_expansion_stage.)
  const Query query = make_query({Vec3(0, -0x1.b8p+23, -0x1.4p+20), Vec3(-0x1.4p+22, 0x1.2cp+24, 0x1.ccp+24),
                                  Vec3(0x1.9p+24, 0x1.4p+24, 0x1.98p+24), Vec3(0x1p+22, 0x1p+22, -0x1.7p+22)},
                                 {Vec3(-0x1.44p+24, 0x1.038p+27, 0x1.dfp+26),
                                  Vec3(-0x1.ffffffffffffep+17, -0x1p+18, -0x1p+18),
                                  Vec3(-0x1p+18, -0x1p+18, -0x1p+18), Vec3(-0x1p+21, -0x1p+18, -0x1p+18)});
  Tally tally;
  for (const double tmax : {1.0, 0.25}) expect_as_integers(Kind::vertex_face, query, tmax, tally);
  EXPECT_EQ(tally.hits, 0);
  EXPECT_GE(tally.decided, 1);  // at tmax = 1/4 the expansions decide
}

// Flat at t = 0: parallel edges (collinear or not, overlapping or apart,
// one of them a point) or a triangle flat on a line with the vertex on a
// side or off it; random ends at t = 1. The cubic then vanishes at 0,
// where n = A x B does too and the contact numerators say nothing.
Query flat_at_start(Kind kind, std::mt19937_64& random) {
  std::uniform_int_distribution<int> step(-2, 2), pick(0, 3);
  const Vec3 origin = grid_point(random), direction = grid_point(random);
  std::array<Vec3, 4> start, end;
  for (Vec3& point : end) point = grid_point(random);
  if (kind == Kind::edge_edge) {  // ea0, ea1 = ea0 + k d; eb0 on a's line or beside it, eb1 = eb0 + m d
    start[0] = origin;
    start[1] = origin + step(random) * direction;
    start[2] = origin + step(random) * direction + (pick(random) == 0 ? grid_point(random) : Vec3::Zero());
    start[3] = start[2] + step(random) * direction;
  } else {  // the vertex, then the three corners on one line
    for (int i = 1; i < 4; ++i) start[i] = origin + step(random) * direction;
    start[0] = origin + step(random) * 0.5 * direction + (pick(random) == 0 ? grid_point(random) : Vec3::Zero());
  }
  return make_query(start, end);
}

TEST(ExpansionStage, DecidesFlatConfigurationsAtAnExactTimeAsIntegers) {
  constexpr int kQueries = 600;
  const Tally tally =
      decide_family(9, kQueries, [](Kind kind, std::mt19937_64& random, int) { return flat_at_start(kind, random); });
  // Once flat at 0 was left to the integers; now only what else needs them.
  EXPECT_GT(tally.decided, kQueries * 9 / 10);
  EXPECT_GT(tally.hits, kQueries / 4);
  std::printf("[ record   ] flat at the start: %d of %d decided by expansions (%d hits)\n", tally.decided, kQueries,
              tally.hits);
}

TEST(ExpansionStage, DecidesAsIntegersWithTmaxAndAtEveryScale) {
  std::mt19937_64 random(5);
  Tally tally;
  std::uniform_real_distribution<double> any_tmax(0.01, 1.0);
  for (int trial = 0; trial < 400; ++trial)
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const Query query = boundary_contact(kind, random);
      for (const double tmax : {0.5, 0.25, 0.75, any_tmax(random)})
        expect_as_integers(kind, query, tmax, tally);
      for (const int exponent : {-400, 400}) expect_as_integers(kind, scaled(query, exponent), 1.0, tally);
    }
  EXPECT_GT(tally.hits, 200);
}

TEST(ExpansionStage, SettlesAGenericCrossingAndAnEdgeContact) {
  // A vertex falling through a triangle's interior at t = 1/2.
  const std::array<Vec3, 4> face{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0)};
  Query through = make_query({Vec3(0.25, 0.25, 1), face[0], face[1], face[2]},
                             {Vec3(0.25, 0.25, -1), face[0], face[1], face[2]});
  const std::optional<ExactOutcome> crossing = exact::solve_with_expansions(Kind::vertex_face, through, true, 1.0);
  ASSERT_TRUE(crossing);
  EXPECT_TRUE(crossing->hit);
  EXPECT_EQ(crossing->toi, 0.5);
  // Edges crossing at an endpoint of one, at t = 1/3: a root no dyadic
  // equals, where a parameter is exactly 1 (the remainder sequence).
  const Query endpoint = make_query({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, -1, 1), Vec3(1, 1, 1)},
                                    {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, -1, -2), Vec3(1, 1, -2)});
  const std::optional<ExactOutcome> at_endpoint = exact::solve_with_expansions(Kind::edge_edge, endpoint, true, 1.0);
  ASSERT_TRUE(at_endpoint);
  EXPECT_TRUE(at_endpoint->hit);
  EXPECT_LE(at_endpoint->toi, 1.0 / 3);
  EXPECT_GE(at_endpoint->toi, 1.0 / 3 - 0x1p-40);
  // Coordinates spread over more than 2^80 are left to integers.
  Query spread = through;
  spread.points[0].x() = 0x1p-90;
  EXPECT_FALSE(exact::solve_with_expansions(Kind::vertex_face, spread, true, 1.0));
}

// --- Planar motion (the cubic identically zero) ----------------------------

// Where a plane family puts the grid point (x, y) at time tau: z = 0; the
// tilted plane z = x + 2y (exact on the grid); z = 1/4 at t0 and -3/8 at t1
// (a plane moving along its axis: the points of each time share z).
enum class PlaneFamily { z0, tilted, moving };

Vec3 in_plane(PlaneFamily family, double x, double y, int tau) {
  if (family == PlaneFamily::tilted) return Vec3(x, y, x + 2 * y);
  if (family == PlaneFamily::moving) return Vec3(x, y, tau == 0 ? 0.25 : -0.375);
  return Vec3(x, y, 0);
}

Query planar_grid_query(PlaneFamily family, std::mt19937_64& random) {
  std::array<Vec3, 4> start, end;
  for (int i = 0; i < 4; ++i) {
    const Vec3 a = grid_point(random), b = grid_point(random);
    start[i] = in_plane(family, a.x(), a.y(), 0);
    end[i] = in_plane(family, b.x(), b.y(), 1);
  }
  return make_query(start, end);
}

// In the plane: an exact contact on an edge or at a corner at t = 1/q
// (boundary_contact's construction, which keeps each time's points in the
// plane), or the start copied to the end (a static pair).
Query planar_boundary_contact(Kind kind, PlaneFamily family, std::mt19937_64& random) {
  std::uniform_int_distribution<int> pick(0, 2);
  const double s = pick(random) / 2.0, q = std::array{2.0, 3.0, 5.0}[pick(random)];
  Query query = planar_grid_query(family, random);
  const int a0 = kind == Kind::vertex_face ? 1 : 0, a1 = a0 + 1;
  const int mover = kind == Kind::vertex_face ? 0 : 2;
  const auto& p = query.points;
  const Vec3 meet_q = (1 - s) * ((q - 1) * p[a0] + p[a0 + 4]) + s * ((q - 1) * p[a1] + p[a1 + 4]);
  query.points[mover + 4] = meet_q - (q - 1) * p[mover];
  return query;
}

TEST(ExpansionStage, DecidesPlanarMotionAsIntegersInAxisTiltedAndMovingPlanes) {
  std::mt19937_64 random(8);
  for (const PlaneFamily family : {PlaneFamily::z0, PlaneFamily::tilted, PlaneFamily::moving}) {
    Tally random_queries, contacts, static_pairs;
    constexpr int kQueries = 300;
    for (int trial = 0; trial < kQueries; ++trial)
      for (const Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
        expect_as_integers(kind, planar_grid_query(family, random), 1.0, random_queries);
        const Query contact = planar_boundary_contact(kind, family, random);
        expect_as_integers(kind, contact, 1.0, contacts);
        expect_as_integers(kind, contact, 0.25, contacts);
        Query still = contact;
        for (int i = 0; i < 4; ++i) still.points[i + 4] = still.points[i];
        if (family != PlaneFamily::moving) expect_as_integers(kind, still, 1.0, static_pairs);
      }
    const int family_index = static_cast<int>(family);
    // Grid queries are full of exact zeros (contacts on edges, parallel
    // edges): most are still decided without integers.
    EXPECT_GT(random_queries.decided, 2 * kQueries * 9 / 10) << family_index;
    EXPECT_GT(random_queries.hits, 2 * kQueries / 10) << family_index;
    EXPECT_GT(contacts.decided, 2 * 2 * kQueries * 3 / 4) << family_index;
    EXPECT_GT(contacts.hits, kQueries) << family_index;
    std::printf("[ record   ] plane %d: random %d of %d decided (%d hits), contacts %d of %d (%d hits), static %d\n",
                family_index, random_queries.decided, 2 * kQueries, random_queries.hits, contacts.decided,
                4 * kQueries, contacts.hits, static_pairs.decided);
  }
}

TEST(ExpansionStage, DecidesPlanarContactsAtTheEndsOfTheStepAndLeavesFlatTrianglesToIntegers) {
  const std::array<Vec3, 3> face{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  // In z = 0, the vertex inside the face at t = 0.
  const Query inside = make_query({Vec3(0.25, 0.25, 0), face[0], face[1], face[2]},
                                  {Vec3(2, 2, 0), face[0], face[1], face[2]});
  const std::optional<ExactOutcome> at_start = exact::solve_with_expansions(Kind::vertex_face, inside, true, 1.0);
  ASSERT_TRUE(at_start);
  EXPECT_TRUE(at_start->hit);
  EXPECT_EQ(at_start->toi, 0.0);
  // Reaching the hypotenuse exactly at t = 1, and with tmax before that.
  const Query at_end = make_query({Vec3(2, 2, 0), face[0], face[1], face[2]},
                                  {Vec3(0.5, 0.5, 0), face[0], face[1], face[2]});
  const std::optional<ExactOutcome> last = exact::solve_with_expansions(Kind::vertex_face, at_end, true, 1.0);
  ASSERT_TRUE(last);
  EXPECT_TRUE(last->hit);
  EXPECT_EQ(last->toi, 1.0);
  const std::optional<ExactOutcome> cut = exact::solve_with_expansions(Kind::vertex_face, at_end, true, 0.75);
  ASSERT_TRUE(cut);
  EXPECT_FALSE(cut->hit);
  // A face flat on a line throughout: the rule does not hold there; integers decide.
  const Query flat = make_query({Vec3(0.5, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)},
                                {Vec3(0.5, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)});
  EXPECT_FALSE(exact::solve_with_expansions(Kind::vertex_face, flat, true, 1.0));
  // Flat for an instant (t = 1/2, the corner (1/2, +-1) crossing the base's
  // line) with the vertex on that line beyond the base: every orientation
  // vanishes there, yet nothing touches.
  const Query flat_once = make_query({Vec3(3, 0, 0), face[0], face[1], Vec3(0.5, 1, 0)},
                                     {Vec3(3, 0, 0), face[0], face[1], Vec3(0.5, -1, 0)});
  EXPECT_FALSE(exact::solve_with_integers(Kind::vertex_face, flat_once, true, 1.0).hit);
  const std::optional<ExactOutcome> never = exact::solve_with_expansions(Kind::vertex_face, flat_once, true, 1.0);
  if (never) {
    EXPECT_FALSE(never->hit);
  }
}

TEST(ExpansionStage, DecidesAVertexPassingJustOutsideACorner) {
  // From the stiff and extreme suite (fast motion, 1e3): the vertex passes
  // 1.8e-14 of the face's size outside a corner, two numerators' roots
  // within 2^-52 of the cubic's. Remainders in expansions once outgrew the
  // double range here and "found" a zero and a contact; the slope test on
  // the root narrowed to 2^-76 now settles both signs.
  const std::array<double, 24> hex{
      -0x1.1a9693762d7f6p+8, -0x1.797276b42be0ep+9, 0x1.cf11389d0edbdp+4, 0x1.cc8a113451b7ap-1,
      0x1.3a1707c165e1ap-1,  0x1.383f50eeb959cp-1,  -0x1.7d93db032f46p-4, -0x1.ed2fd9aeef948p-3,
      0x1.34a9c2b12bb6ap-1,  0x1.d3433a917ab84p-2,  0x1.a1a5bdd8b929p-3,  0x1.420c7132dd4afp+0,
      0x1.f721075db8a6cp+8,  -0x1.d702aa6b02f9p+5,  0x1.979caa03f1a6p+8,  0x1.4c2cca3c6c18ap+8,
      -0x1.013d057d8c19cp+9, 0x1.a8b279c6e7b43p+8,  0x1.4b2eabf621bcdp+8, -0x1.01aa5e3d17623p+9,
      0x1.a8b0aeffc8ed6p+8,  0x1.4bbb5602764e7p+8,  -0x1.017170e39ee7ap+9, 0x1.a958668fa334dp+8};
  Query query;
  for (int i = 0; i < 8; ++i) query.points[i] = Vec3(hex[3 * i], hex[3 * i + 1], hex[3 * i + 2]);
  EXPECT_FALSE(exact::solve_with_integers(Kind::vertex_face, query, true, 1.0).hit);
  const std::optional<ExactOutcome> expansions = exact::solve_with_expansions(Kind::vertex_face, query, true, 1.0);
  ASSERT_TRUE(expansions);
  EXPECT_FALSE(expansions->hit);
}

TEST(ExpansionStage, FirstRootAsIntegersLocateIt) {
  std::mt19937_64 random(6);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Query query = random_grid_query(random);
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
      for (int k = 0; k < 8; ++k) {  // [k, k + 1] / 8: a bracket as the search hands over
        const double low = k / 8.0, high = (k + 1) / 8.0;
        const std::optional<double> integers = exact::first_root_with_integers(kind, query, low, high);
        const std::optional<double> expansions = exact::first_root_with_expansions(kind, query, low, high);
        // A root exactly at low: the integers look in the open interval.
        if (!integers || !expansions || *expansions == low) continue;
        ++compared;
        EXPECT_GE(*expansions, low);
        EXPECT_LE(std::fabs(*expansions - *integers), 0x1p-40);
      }
  }
  EXPECT_GT(compared, 500);
}

}  // namespace
}  // namespace batchccd

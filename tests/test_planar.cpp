// Planar motion (docs/design.md §5a): queries whose eight points stay in one
// plane, decided in that plane. Every answer is checked against the exact
// stage run on its own (GMP integers, an independent decision procedure),
// in both modes, through the batch call (lanes, then the scalar path) and
// the scalar path alone.

#include <cmath>
#include <filesystem>
#include <random>
#include <span>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "exact/exact_solver.hpp"
#include "exact/plane_axis.hpp"
#include "exact_distance.hpp"
#include "query_builders.hpp"
#include "reference/planar_solver.hpp"
#include "reference/scaled_query.hpp"
#include "shared_data.hpp"

namespace batchccd {
namespace {

const double kExactToiWidth = std::ldexp(1.0, -static_cast<int>(exact::kToiBits));

// An exactly representable plane: points (s, t) of the plane map to
// origin + s * u + t * v with small integer u, v and dyadic s, t, so every
// coordinate is exact.
struct Plane {
  Vec3 origin, u, v;
  Vec3 operator()(double s, double t) const { return origin + s * u + t * v; }
};

const Plane kFloor{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
const Plane kRaisedFloor{{0, 0, 0.75}, {1, 0, 0}, {0, 1, 0}};
const Plane kWall{{0.5, 0, 0}, {0, 0, 1}, {0, 1, 0}};
const Plane kTilted{{0.25, -0.5, 1}, {1, 0, 1}, {0, 1, 2}};  // z = x + 2y + 1.75
const Plane kDiagonal{{0, 0, 0}, {1, 1, 0}, {0, 0, 1}};       // x = y

struct PlanarFamily {
  Kind kind;
  Plane plane;
};

// Random dyadic in-plane coordinates (16 fractional bits) in [-1, 1].
class PlanarGenerator {
 public:
  explicit PlanarGenerator(unsigned seed) : random_(seed) {}

  double coordinate() { return std::ldexp(static_cast<double>(integer_(random_)), -16); }

  // The query's points at t0 and t1 in plane coordinates (p, a, b, c or
  // ea0, ea1, eb0, eb1), about a third of them in contact: the moving point
  // or an edge is pushed toward the other primitive.
  Query query(Kind kind, const Plane& plane) {
    std::array<std::array<double, 2>, 8> in_plane;
    for (auto& point : in_plane) point = {coordinate(), coordinate()};
    if (kind == Kind::vertex_edge) {  // p, p, e0, e1
      in_plane[1] = in_plane[0];
      in_plane[5] = in_plane[4];
    }
    if (kind == Kind::vertex_vertex) {
      in_plane[1] = in_plane[0];
      in_plane[5] = in_plane[4];
      in_plane[3] = in_plane[2];
      in_plane[7] = in_plane[6];
    }
    Query query;
    for (int i = 0; i < 8; ++i) query.points[i] = plane(in_plane[i][0], in_plane[i][1]);
    return query;
  }

 private:
  std::mt19937_64 random_;
  std::uniform_int_distribution<int> integer_{-(1 << 16), 1 << 16};
};

// The exact stage alone: hit, and its TOI (within 2^-40 below the first contact).
exact::ExactOutcome truth(Kind kind, const Query& query, double tmax = 1) {
  return exact::solve_exactly(reference::evaluated_kind(kind), query, true, tmax);
}

Options options_for(Mode mode, double tmax = 1) {
  Options options;
  options.mode = mode;
  options.tmax = tmax;
  options.per_candidate_results = true;
  return options;
}

// The answer agrees with exact arithmetic: the same decision; a TOI never
// after the first contact and within the mode's width before it.
void expect_agrees(const QueryResult& result, const exact::ExactOutcome& exact, Mode mode, const Query& query) {
  ASSERT_EQ(result.status, Status::ok);
  ASSERT_EQ(result.hit, exact.hit) << "query " << ::testing::PrintToString(query.points);
  if (!exact.hit) return;
  const double width = mode == Mode::exact ? kExactToiWidth : Options{}.toi_tolerance;
  EXPECT_LE(result.toi, exact.toi + 2 * kExactToiWidth);
  EXPECT_GE(result.toi, exact.toi - width - kExactToiWidth);
}

TEST(PlanarAxis, FindsAxisAndTiltedPlanes) {
  PlanarGenerator generator(1);
  for (const Plane& plane : {kFloor, kRaisedFloor, kWall, kTilted, kDiagonal})
    for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const std::optional<int> axis = exact::exact_plane_axis(generator.query(kind, plane));
      ASSERT_TRUE(axis.has_value());
      // The plane's normal has a nonzero component along the axis.
      EXPECT_NE(plane.u.cross(plane.v)[*axis], 0);
    }
}

TEST(PlanarAxis, RefusesAPointOneUlpOffThePlane) {
  PlanarGenerator generator(2);
  for (const Plane& plane : {kFloor, kTilted, kDiagonal}) {
    Query query = generator.query(Kind::vertex_face, plane);
    ASSERT_TRUE(exact::exact_plane_axis(query).has_value());
    const Vec3 normal = plane.u.cross(plane.v);
    int axis = 0;
    normal.cwiseAbs().maxCoeff(&axis);
    query.points[6][axis] = std::nextafter(query.points[6][axis], 10.0);
    EXPECT_FALSE(exact::exact_plane_axis(query).has_value());
  }
}

// Coordinates on a grid finer than 2^-39 (below 40 bits of the largest):
// the exact test in expansions rather than in 128-bit integers.
TEST(PlanarAxis, FineGridPlanesAreTestedInExpansions) {
  Query query;
  for (int i = 0; i < 8; ++i) {
    const double s = 1 + std::ldexp(static_cast<double>(i * i + 1), -50), t = 0.5 - std::ldexp(i, -48);
    query.points[i] = kTilted(s, i % 2 ? t : -t);
  }
  const std::optional<int> axis = exact::exact_plane_axis(query);
  ASSERT_TRUE(axis.has_value());
  EXPECT_NE(kTilted.u.cross(kTilted.v)[*axis], 0);
  query.points[5][*axis] = std::nextafter(query.points[5][*axis], 10.0);
  EXPECT_FALSE(exact::exact_plane_axis(query).has_value());
}

TEST(PlanarAxis, RefusesGenericAndCollinearQueries) {
  Query generic;
  for (int i = 0; i < 8; ++i) generic.points[i] = Vec3(i % 3, i * i % 5, (i * 7) % 4);
  EXPECT_FALSE(exact::exact_plane_axis(generic).has_value());
  Query collinear;  // all on the line x = y = z: in every plane through it
  for (int i = 0; i < 8; ++i) collinear.points[i] = Vec3(i, i, i) * 0.125;
  EXPECT_FALSE(exact::exact_plane_axis(collinear).has_value());
}

class PlanarRandom : public ::testing::TestWithParam<PlanarFamily> {};

// Random in-plane motions in every plane and kind: every decision equal to
// exact arithmetic in both modes, and nearly none left to the exact stage
// (the planar path is what decides them).
TEST_P(PlanarRandom, AgreesWithExactArithmetic) {
  const PlanarFamily family = GetParam();
  PlanarGenerator generator(7 + static_cast<unsigned>(family.kind));
  std::vector<Query> queries;
  for (int i = 0; i < 600; ++i) queries.push_back(generator.query(family.kind, family.plane));
  std::vector<exact::ExactOutcome> expected;
  int contacts = 0;
  for (const Query& query : queries) {
    expected.push_back(truth(family.kind, query));
    contacts += expected.back().hit;
  }
  if (family.kind != Kind::vertex_vertex) {
    EXPECT_GT(contacts, 30) << "the family should hold contacts";
  }
  for (Mode mode : {Mode::conservative, Mode::exact}) {
    const BatchResult batch = batch_ccd(family.kind, queries, options_for(mode));
    for (std::size_t i = 0; i < queries.size(); ++i) {
      expect_agrees(batch.results[i], expected[i], mode, queries[i]);
      expect_agrees(query_ccd(family.kind, queries[i], options_for(mode)), expected[i], mode, queries[i]);
    }
    // Point-point contacts need both coordinates to agree at once, which no
    // sign test certifies: those few go to the exact stage by design.
    const std::int64_t allowed = family.kind == Kind::vertex_vertex ? contacts : queries.size() / 100;
    EXPECT_LE(batch.counters.exact_escalations, allowed) << to_string(mode);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Planes, PlanarRandom,
    ::testing::Values(PlanarFamily{Kind::vertex_face, kFloor}, PlanarFamily{Kind::edge_edge, kFloor},
                      PlanarFamily{Kind::vertex_face, kRaisedFloor}, PlanarFamily{Kind::edge_edge, kRaisedFloor},
                      PlanarFamily{Kind::vertex_face, kWall}, PlanarFamily{Kind::edge_edge, kWall},
                      PlanarFamily{Kind::vertex_face, kTilted}, PlanarFamily{Kind::edge_edge, kTilted},
                      PlanarFamily{Kind::vertex_face, kDiagonal}, PlanarFamily{Kind::edge_edge, kDiagonal},
                      PlanarFamily{Kind::vertex_edge, kFloor}, PlanarFamily{Kind::vertex_edge, kTilted},
                      PlanarFamily{Kind::vertex_vertex, kFloor}));

// One query in both modes and at tmax, against exact arithmetic.
void expect_exact_answers(Kind kind, const Query& query, double tmax = 1) {
  const exact::ExactOutcome expected = truth(kind, query, tmax);
  for (Mode mode : {Mode::conservative, Mode::exact}) {
    expect_agrees(query_ccd(kind, query, options_for(mode, tmax)), expected, mode, query);
    expect_agrees(batch_ccd(kind, std::vector<Query>{query}, options_for(mode, tmax)).results[0], expected,
                  mode, query);
  }
}

Query vertex_face(const Plane& plane, std::array<std::array<double, 2>, 4> start,
                  std::array<std::array<double, 2>, 4> end) {
  Query query;
  for (int i = 0; i < 4; ++i) {
    query.points[i] = plane(start[i][0], start[i][1]);
    query.points[i + 4] = plane(end[i][0], end[i][1]);
  }
  return query;
}

// The hand-made cases: first contacts at the ends of the step, corners
// grazed, edges on one line, pairs that do not move, extreme scales.
TEST(PlanarCases, VertexFaceEvents) {
  const std::array<std::array<double, 2>, 3> triangle{{{0, 0}, {1, 0}, {0, 1}}};
  const auto moving_vertex = [&](const Plane& plane, std::array<double, 2> from, std::array<double, 2> to) {
    return vertex_face(plane, {from, triangle[0], triangle[1], triangle[2]},
                       {to, triangle[0], triangle[1], triangle[2]});
  };
  for (const Plane& plane : {kFloor, kTilted, kDiagonal}) {
    SCOPED_TRACE(::testing::PrintToString(plane.u));
    const std::vector<Query> cases{
        moving_vertex(plane, {0.25, 0.25}, {3, 3}),     // inside at t = 0
        moving_vertex(plane, {-1, 0.25}, {0, 0.25}),    // reaches the edge at t = 1
        moving_vertex(plane, {-1, 0.25}, {-0.5, 0.25}), // stops short
        moving_vertex(plane, {-1, -1}, {1, 1}),         // through the corner (0, 0)
        moving_vertex(plane, {-1, 1}, {1, -1}),         // grazes the corner (0, 0) from outside
        moving_vertex(plane, {-1, 0}, {2, 0}),          // along the edge's line
        moving_vertex(plane, {2, 2}, {-1, 2}),          // passes above
        moving_vertex(plane, {0.5, 0.5}, {0.5, 0.5}),   // static, on the hypotenuse
        moving_vertex(plane, {0.5, 0.75}, {0.5, 0.75}), // static, outside
        vertex_face(plane, {{{0.25, 0.25}, {1, 1}, {2, 1}, {1, 2}}},  // the triangle slides onto the vertex
                    {{{0.25, 0.25}, {0, 0}, {1, 0}, {0, 1}}}),
        vertex_face(plane, {{{0.2, 0.2}, {0, 0}, {1, 0}, {0, 1}}},    // the triangle flips through a segment
                    {{{0.2, 0.2}, {0, 0}, {1, 0}, {1, -1}}}),
    };
    for (const Query& query : cases) {
      expect_exact_answers(Kind::vertex_face, query);
      expect_exact_answers(Kind::vertex_face, query, 0.5);
      expect_exact_answers(Kind::vertex_face, testing::scaled(query, -400));
      expect_exact_answers(Kind::vertex_face, testing::scaled(query, 400));
    }
  }
}

TEST(PlanarCases, EdgeEdgeEvents) {
  const auto edges = [](const Plane& plane, std::array<std::array<double, 2>, 4> start,
                        std::array<std::array<double, 2>, 4> end) { return vertex_face(plane, start, end); };
  for (const Plane& plane : {kFloor, kTilted}) {
    const std::vector<Query> cases{
        edges(plane, {{{0, 0}, {1, 0}, {0.5, -1}, {0.5, 1}}}, {{{0, 0}, {1, 0}, {0.5, -1}, {0.5, 1}}}),  // crossing, static
        edges(plane, {{{0, 0}, {1, 0}, {2, -1}, {2, 1}}}, {{{0, 0}, {1, 0}, {0.5, -1}, {0.5, 1}}}),      // slides in
        edges(plane, {{{0, 0}, {1, 0}, {2, -1}, {2, 1}}}, {{{0, 0}, {1, 0}, {1, -1}, {1, 1}}}),          // touches the end at t = 1
        edges(plane, {{{0, 0}, {1, 0}, {3, 0}, {4, 0}}}, {{{0, 0}, {1, 0}, {0.5, 0}, {1.5, 0}}}),        // collinear, into overlap
        edges(plane, {{{0, 0}, {1, 0}, {3, 0}, {4, 0}}}, {{{0, 0}, {1, 0}, {2, 0}, {3, 0}}}),            // collinear, short
        edges(plane, {{{0, 0}, {1, 0}, {0, 1}, {1, 1}}}, {{{0, 0}, {1, 0}, {0, 1}, {1, 1}}}),            // parallel, static
        edges(plane, {{{0, 0}, {1, 0}, {1, 1}, {2, 0}}}, {{{0, 0}, {1, 0}, {0, -1}, {1, 0}}}),          // corner to corner
    };
    for (const Query& query : cases) {
      expect_exact_answers(Kind::edge_edge, query);
      expect_exact_answers(Kind::edge_edge, query, 0.75);
      expect_exact_answers(Kind::edge_edge, testing::scaled(query, -400));
    }
  }
}

TEST(PlanarCases, PointKinds) {
  for (const Plane& plane : {kFloor, kTilted}) {
    const auto point_edge = [&](std::array<double, 2> p0, std::array<double, 2> p1) {
      return make_query(Kind::vertex_edge, std::vector<Vec3>{plane(p0[0], p0[1]), plane(0, 0), plane(1, 0)},
                        std::vector<Vec3>{plane(p1[0], p1[1]), plane(0, 0), plane(1, 0)});
    };
    expect_exact_answers(Kind::vertex_edge, point_edge({0.5, 1}, {0.5, -1}));  // crosses
    expect_exact_answers(Kind::vertex_edge, point_edge({2, 1}, {2, -1}));      // passes beyond the end
    expect_exact_answers(Kind::vertex_edge, point_edge({1, 1}, {1, -1}));      // through the end point
    expect_exact_answers(Kind::vertex_edge, point_edge({0.5, 1}, {0.5, 0}));   // reaches it at t = 1
    const auto point_point = [&](std::array<double, 2> q0, std::array<double, 2> q1) {
      return make_query(Kind::vertex_vertex, std::vector<Vec3>{plane(0, 0), plane(q0[0], q0[1])},
                        std::vector<Vec3>{plane(1, 1), plane(q1[0], q1[1])});
    };
    expect_exact_answers(Kind::vertex_vertex, point_point({1, 0}, {0, 1}));  // meet at t = 1/2
    expect_exact_answers(Kind::vertex_vertex, point_point({1, 0}, {0, 2}));  // miss
  }
}

// With a separation, motion in an axis plane is decided there
// (solve_planar_within). Every answer is held to exact labels (a witness
// with exact squared distance <= D^2, or a certified Lipschitz miss) and
// to the generic search over (t, u, v) in exact mode, an independent
// certified procedure: the same decisions, TOIs within 2^-40 of each other.
TEST(PlanarWithin, AgreesWithExactLabelsAndTheGenericSearch) {
  lab::Settings generic;
  generic.planar_path = false;
  int hits = 0, labelled = 0, queries = 0, certain = 0;
  for (const Plane& plane : {kFloor, kRaisedFloor, kWall})
    for (Kind kind : {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex}) {
      PlanarGenerator generator(41 + static_cast<unsigned>(kind));
      for (int i = 0; i < 40; ++i) {
        const Query query = generator.query(kind, plane);
        for (double separation : {0x1p-6, 0.125}) {
          SCOPED_TRACE(::testing::Message() << to_string(kind) << " query " << i << " D " << separation << " "
                                            << ::testing::PrintToString(query.points));
          ++queries;
          const testing::Labelled truth = testing::label(reference::evaluated_kind(kind), query, separation);
          Options options = options_for(Mode::exact);
          options.min_distance = separation;
          const QueryResult exact = query_ccd(kind, query, options);
          const QueryResult searched = lab::query_ccd(kind, query, options, generic);
          ASSERT_EQ(exact.hit, searched.hit);
          if (exact.hit) {
            EXPECT_NEAR(exact.toi, searched.toi, 2 * kExactToiWidth);
          }
          options.mode = Mode::conservative;
          const QueryResult conservative = query_ccd(kind, query, options);
          ASSERT_EQ(conservative.hit, exact.hit);
          if (exact.hit) {
            EXPECT_LE(conservative.toi, exact.toi + 2 * kExactToiWidth);
            EXPECT_GE(conservative.toi, exact.toi - options.toi_tolerance - 2 * kExactToiWidth);
          }
          if (truth.label != testing::Label::unlabelled) {
            ++labelled;
            ASSERT_EQ(exact.hit, truth.label == testing::Label::hit);
            if (exact.hit) {
              EXPECT_LE(exact.toi, truth.witness);
            }
          }
          hits += exact.hit;
          // The planar search itself (the answer where conservative
          // advancement is uncertain): certain, a hit's bracket ending
          // where the distance is exactly within D.
          const reference::ScaledQuery scaled = reference::scale_query(reference::evaluated_kind(kind), query);
          const int axis = *exact::exact_plane_axis(query);
          const reference::PlanarOutcome outcome = reference::solve_planar_within(
              reference::planar_shape(reference::evaluated_kind(kind), query), scaled, axis,
              reference::to_scaled_length(scaled, separation), 1, kExactToiWidth);
          certain += outcome.certain;
          if (outcome.certain && outcome.hit) {
            const testing::Rational d(separation);
            EXPECT_LE(testing::squared_distance_at(reference::evaluated_kind(kind), query, outcome.toi_upper), d * d);
            EXPECT_NEAR(outcome.toi, exact.toi, 2 * kExactToiWidth);
          }
        }
      }
    }
  EXPECT_GT(hits, queries / 5);
  EXPECT_GT(labelled, queries * 9 / 10);
  EXPECT_GT(certain, queries * 95 / 100);
}

// Events whose time is known exactly, on the floor and on a wall (x = 0.5).
TEST(PlanarWithin, KnownTimes) {
  for (const Plane& plane : {kFloor, kWall}) {
    Options options = options_for(Mode::exact);
    options.min_distance = 0.25;
    const auto point_edge = [&](std::array<double, 2> p0, std::array<double, 2> p1) {
      return make_query(Kind::vertex_edge, std::vector<Vec3>{plane(p0[0], p0[1]), plane(0, 0), plane(1, 0)},
                        std::vector<Vec3>{plane(p1[0], p1[1]), plane(0, 0), plane(1, 0)});
    };
    const auto expect_toi = [&](Kind kind, const Query& query, double toi) {
      const QueryResult result = query_ccd(kind, query, options);
      ASSERT_TRUE(result.hit) << toi;
      EXPECT_LE(result.toi, toi);
      EXPECT_GE(result.toi, toi - kExactToiWidth);
    };
    const auto expect_miss = [&](Kind kind, const Query& query) { EXPECT_FALSE(query_ccd(kind, query, options).hit); };
    // Toward the segment's interior: |y| = 1 - 2t reaches 0.25 at t = 3/8.
    expect_toi(Kind::vertex_edge, point_edge({0.5, 1}, {0.5, -1}), 0.375);
    // Toward its end (1, 0) along x: 1.75 - 2t - 1 = 0.25 at t = 1/4.
    expect_toi(Kind::vertex_edge, point_edge({1.75, 0}, {-0.25, 0}), 0.25);
    // Passing the end at height 0.2 (within 0.25 of it only near x = 1):
    // x = 2 - 2t, (x - 1)^2 + 0.04 = 1/16 at x - 1 = 0.15, t = 0.425.
    expect_toi(Kind::vertex_edge, point_edge({2, 0.2}, {0, 0.2}), 0.425);
    expect_miss(Kind::vertex_edge, point_edge({0.5, 0.5}, {2, 0.5}));  // parallel, 0.5 away
    expect_toi(Kind::vertex_edge, point_edge({0.5, 0.125}, {0.5, 0.125}), 0);  // static, within D
    // A vertex deep inside a triangle, far from its edges: within D at 0.
    const Query inside = make_query(Kind::vertex_face, std::vector<Vec3>{plane(1, 1), plane(0, 0), plane(4, 0), plane(0, 4)},
                                    std::vector<Vec3>{plane(1.5, 1), plane(0, 0), plane(4, 0), plane(0, 4)});
    expect_toi(Kind::vertex_face, inside, 0);
    // Two long segments crossing in an X, every end 4 away from the other
    // segment: within D at 0 by the crossing alone.
    const Query crossing = make_query(Kind::edge_edge,
                                      std::vector<Vec3>{plane(-4, 0), plane(4, 0), plane(0, -4), plane(0, 4)},
                                      std::vector<Vec3>{plane(-4, 0), plane(4, 0), plane(1, -4), plane(1, 4)});
    expect_toi(Kind::edge_edge, crossing, 0);
    // Parallel segments closing in: y = 1 - t reaches 0.25 at t = 3/4.
    const Query closing = make_query(Kind::edge_edge,
                                     std::vector<Vec3>{plane(0, 0), plane(2, 0), plane(0.5, 1), plane(1.5, 1)},
                                     std::vector<Vec3>{plane(0, 0), plane(2, 0), plane(0.5, 0), plane(1.5, 0)});
    expect_toi(Kind::edge_edge, closing, 0.75);
    // Points: |x| = 2 - 4t reaches 0.25 at t = 7/16.
    const Query points = make_query(Kind::vertex_vertex, std::vector<Vec3>{plane(2, 0), plane(0, 0)},
                                    std::vector<Vec3>{plane(-2, 0), plane(0, 0)});
    expect_toi(Kind::vertex_vertex, points, 7.0 / 16);
    // tmax before the contact: a miss.
    options.tmax = 0.25;
    expect_miss(Kind::vertex_vertex, points);
  }
}

// Units: a query scaled by 2^k gets the same answers with D scaled alike.
TEST(PlanarWithin, ScaleInvariant) {
  PlanarGenerator generator(47);
  for (int i = 0; i < 60; ++i) {
    const Kind kind = i % 2 ? Kind::edge_edge : Kind::vertex_face;
    const Query query = generator.query(kind, kFloor);
    Options options = options_for(Mode::conservative);
    options.min_distance = 0.0625;
    const QueryResult unit = query_ccd(kind, query, options);
    for (int exponent : {-400, 400}) {
      Options scaled = options;
      scaled.min_distance = std::ldexp(options.min_distance, exponent);
      const QueryResult result = query_ccd(kind, testing::scaled(query, exponent), scaled);
      EXPECT_EQ(result.hit, unit.hit);
      EXPECT_EQ(result.toi, unit.toi);
    }
  }
}

// From fuzz_planar: a triangle whose corners a and b coincide at t0 (and
// stay on one line with c), at d = 8. At t0 the on-line clause of the edge
// a b has all its conditions zero, so no interval [0, w] could exclude it,
// and the search gave the query to the box search (0.5 s, undecided). The
// vertex is far from a there, which excludes the clause (condition 5 of
// PairConditions): the planar search decides it -- with one box for the
// box search, nothing is left undecided -- and its bracket holds the first
// time within d exactly. (Conservative advancement, which comes first at a
// separation, settles it too.)
TEST(PlanarWithin, EdgeOfZeroLengthAtTheStart) {
  const Query query{{Vec3{-129, 125, -1}, Vec3{4, 4, -1}, Vec3{4, 4, -1}, Vec3{-12, -12, -1}, Vec3{4, 4, -1},
                     Vec3{-60, -60, -1}, Vec3{3, 3, -1}, Vec3{4, 4, -1}}};
  const double separation = 8;
  const reference::ScaledQuery scaled = reference::scale_query(Kind::vertex_face, query);
  const reference::PlanarOutcome outcome =
      reference::solve_planar_within(reference::PlanarShape::triangle_vertex, scaled, *exact::exact_plane_axis(query),
                                     reference::to_scaled_length(scaled, separation), 1, kExactToiWidth);
  ASSERT_TRUE(outcome.certain);
  ASSERT_TRUE(outcome.hit);
  const testing::Rational d2 = testing::Rational(separation) * separation;
  EXPECT_LE(testing::squared_distance_at(Kind::vertex_face, query, outcome.toi_upper), d2);
  EXPECT_GT(testing::squared_distance_at(Kind::vertex_face, query, outcome.toi), d2);
  EXPECT_LE(outcome.toi_upper - outcome.toi, kExactToiWidth);
  Options options = options_for(Mode::exact);
  options.min_distance = separation;
  options.max_iterations = 1;
  BatchResult out;
  lab::batch_ccd(Kind::vertex_face, std::span<const Query>(&query, 1), {}, options, {}, out);
  EXPECT_EQ(out.counters.undecided, 0);
  ASSERT_TRUE(out.results[0].hit);
  // Whichever certified search answers: within 2^-40 before the first
  // time within d, which the planar bracket holds.
  EXPECT_LE(out.results[0].toi, outcome.toi_upper);
  EXPECT_GE(out.results[0].toi, outcome.toi - kExactToiWidth);
}

// A 2D mesh (positions n x 2) means the mesh lifted to z = 0: every kind,
// option and layout gives the lifted call's answers, which are exact
// arithmetic's at separation 0.
struct Mesh2D {
  Eigen::MatrixXd t0, t1;  // n x 2
  Eigen::MatrixXi faces;
  Candidates candidates;
};

Mesh2D random_mesh_2d(unsigned seed) {
  PlanarGenerator generator(seed);
  Mesh2D mesh;
  const int n = 40;
  mesh.t0.resize(n, 2);
  mesh.t1.resize(n, 2);
  for (int v = 0; v < n; ++v) {
    mesh.t0.row(v) << generator.coordinate(), generator.coordinate();
    mesh.t1.row(v) = mesh.t0.row(v) + 0.5 * Eigen::RowVector2d(generator.coordinate(), generator.coordinate());
  }
  mesh.faces.resize(n / 3, 3);
  for (int f = 0; f < n / 3; ++f) mesh.faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  for (int v = 0; v < n; ++v) {
    for (int f = 0; f < n / 3; ++f)
      if (v / 3 != f) mesh.candidates.vertex_face.push_back({v, f});
    for (int e = 0; e + 1 < n; e += 2)
      if (v != e && v != e + 1) mesh.candidates.vertex_edge.push_back({v, e, e + 1});
    for (int w = v + 1; w < n; ++w) mesh.candidates.vertex_vertex.push_back({v, w});
  }
  for (int a = 0; a + 1 < n; a += 2)
    for (int b = a + 2; b + 1 < n; b += 2) mesh.candidates.edge_edge.push_back({a, a + 1, b, b + 1});
  return mesh;
}

Eigen::MatrixXd lifted(const Eigen::MatrixXd& positions) {
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(positions.rows(), 3);
  result.leftCols(2) = positions;
  return result;
}

void expect_same_results(const BatchResult& a, const BatchResult& b) {
  ASSERT_EQ(a.results.size(), b.results.size());
  for (std::size_t i = 0; i < a.results.size(); ++i) {
    EXPECT_EQ(a.results[i].hit, b.results[i].hit) << "candidate " << i;
    EXPECT_EQ(a.results[i].toi, b.results[i].toi) << "candidate " << i;
  }
  EXPECT_EQ(a.hits.size(), b.hits.size());
  EXPECT_EQ(a.earliest_toi, b.earliest_toi);
  EXPECT_EQ(a.counters.hits, b.counters.hits);
}

TEST(Mesh2D, MeansTheMeshLiftedToThePlaneZ0) {
  const Mesh2D mesh = random_mesh_2d(21);
  const Eigen::MatrixXd t0 = lifted(mesh.t0), t1 = lifted(mesh.t1);
  // Other layouts of the same 2D positions: row-major, and floats (the
  // coordinates are dyadic with 17 bits: exact in float).
  const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> row_major_t0 = mesh.t0, row_major_t1 = mesh.t1;
  const Eigen::MatrixXf float_t0 = mesh.t0.cast<float>(), float_t1 = mesh.t1.cast<float>();
  std::vector<double> separations(mesh.candidates.vertex_edge.size());
  for (std::size_t i = 0; i < separations.size(); ++i) separations[i] = 0.01 * static_cast<double>(i % 4);
  int contacts = 0;
  for (Mode mode : {Mode::conservative, Mode::exact})
    for (double min_distance : {0.0, 0.02})
      for (double tmax : {1.0, 0.5}) {
        SCOPED_TRACE(::testing::Message() << to_string(mode) << " min_distance " << min_distance << " tmax " << tmax);
        Options options = options_for(mode, tmax);
        options.min_distance = min_distance;
        options.hit_list = true;
        const BatchResult three = mesh_ccd({t0, t1, mesh.faces}, mesh.candidates, options);
        contacts += static_cast<int>(three.counters.hits);
        expect_same_results(mesh_ccd({mesh.t0, mesh.t1, mesh.faces}, mesh.candidates, options), three);
        expect_same_results(mesh_ccd({row_major_t0, row_major_t1, mesh.faces}, mesh.candidates, options), three);
        expect_same_results(mesh_ccd({float_t0, float_t1, mesh.faces}, mesh.candidates, options), three);
        BatchResult by_candidate, by_candidate_3d;
        const MinDistances per_candidate{.vertex_edge = separations};
        mesh_ccd({mesh.t0, mesh.t1, mesh.faces}, mesh.candidates, per_candidate, options, by_candidate);
        mesh_ccd({t0, t1, mesh.faces}, mesh.candidates, per_candidate, options, by_candidate_3d);
        expect_same_results(by_candidate, by_candidate_3d);
        options.threads = 2;
        options.isa = Isa::scalar;
        expect_same_results(mesh_ccd({mesh.t0, mesh.t1, mesh.faces}, mesh.candidates, options), three);
      }
  EXPECT_GT(contacts, 100);
}

TEST(Mesh2D, AgreesWithExactArithmetic) {
  const Mesh2D mesh = random_mesh_2d(22);
  const MeshView view{mesh.t0, mesh.t1, mesh.faces};
  const Eigen::MatrixXd t0 = lifted(mesh.t0), t1 = lifted(mesh.t1);
  const MeshView view_3d{t0, t1, mesh.faces};
  for (Mode mode : {Mode::conservative, Mode::exact}) {
    const BatchResult result = mesh_ccd(view, mesh.candidates, options_for(mode));
    std::size_t index = 0, hits = 0;
    const auto check = [&](Kind kind, const Query& query) {
      const exact::ExactOutcome expected = truth(kind, query);
      hits += expected.hit;
      expect_agrees(result.results[index++], expected, mode, query);
    };
    for (const auto& candidate : mesh.candidates.vertex_face)
      check(Kind::vertex_face, vertex_face_query(view_3d, candidate));
    for (const auto& candidate : mesh.candidates.edge_edge) check(Kind::edge_edge, edge_edge_query(view_3d, candidate));
    for (const auto& [v, e0, e1] : mesh.candidates.vertex_edge)
      check(Kind::vertex_edge, edge_edge_query(view_3d, {v, v, e0, e1}));
    for (const auto& [v, w] : mesh.candidates.vertex_vertex) check(Kind::vertex_vertex, edge_edge_query(view_3d, {v, v, w, w}));
    EXPECT_EQ(index, result.results.size());
    EXPECT_GT(hits, 50u);
    // The helper reads a 2D mesh as the lifted one.
    EXPECT_EQ(vertex_face_query(view, mesh.candidates.vertex_face[5]).points,
              vertex_face_query(view_3d, mesh.candidates.vertex_face[5]).points);
  }
}

// Raw 2D queries (Query2D) mean the queries lifted to z = 0: batch_ccd on
// them gives the lifted batch's answers in every kind, mode and option, and
// those are exact arithmetic's at separation 0.
std::vector<Query2D> random_queries_2d(Kind kind, unsigned seed, int count) {
  PlanarGenerator generator(seed);
  std::vector<Query2D> queries;
  for (int i = 0; i < count; ++i) {
    const Query query = generator.query(kind, kFloor);
    Query2D in_plane;
    for (int k = 0; k < 8; ++k) in_plane.points[k] = query.points[k].head<2>();
    queries.push_back(in_plane);
  }
  return queries;
}

TEST(Queries2D, MeanTheQueriesLiftedToThePlaneZ0) {
  for (Kind kind : {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex}) {
    const std::vector<Query2D> queries = random_queries_2d(kind, 31 + static_cast<unsigned>(kind), 120);
    std::vector<Query> spatial;
    for (const Query2D& query : queries) {
      spatial.push_back(lifted(query));
      ASSERT_EQ(spatial.back().points[3].z(), 0.0);
      ASSERT_EQ(spatial.back().points[6].head<2>(), query.points[6]);
    }
    std::vector<double> separations(queries.size());
    for (std::size_t i = 0; i < separations.size(); ++i) separations[i] = 0.01 * static_cast<double>(i % 4);
    int contacts = 0;
    for (Mode mode : {Mode::conservative, Mode::exact})
      for (double min_distance : {0.0, 0.02})
        for (double tmax : {1.0, 0.5}) {
          SCOPED_TRACE(::testing::Message() << to_string(kind) << " " << to_string(mode) << " min_distance "
                                            << min_distance << " tmax " << tmax);
          Options options = options_for(mode, tmax);
          options.min_distance = min_distance;
          options.hit_list = true;
          const BatchResult three = batch_ccd(kind, spatial, options);
          contacts += static_cast<int>(three.counters.hits);
          expect_same_results(batch_ccd(kind, queries, options), three);
          BatchResult each_2d, each_3d;
          batch_ccd(kind, std::span<const Query2D>(queries), separations, options, each_2d);
          batch_ccd(kind, std::span<const Query>(spatial), separations, options, each_3d);
          expect_same_results(each_2d, each_3d);
          options.threads = 2;
          options.isa = Isa::scalar;
          expect_same_results(batch_ccd(kind, queries, options), three);
          if (min_distance == 0 && tmax == 1)
            for (std::size_t i = 0; i < queries.size(); i += 7)
              expect_agrees(three.results[i], truth(kind, spatial[i]), mode, spatial[i]);
        }
    EXPECT_GT(contacts, kind == Kind::vertex_vertex ? 2 : 100) << to_string(kind);
  }
}

TEST(Queries2D, MakeQueryAndBadInput) {
  const std::array<Vec2, 3> start{Vec2(0, 1), Vec2(-1, 0), Vec2(1, 0)}, end{Vec2(0, -1), Vec2(-1, 0), Vec2(1, 0)};
  const Query2D crossing = make_query(Kind::vertex_edge, start, end);
  EXPECT_EQ(crossing.points[1], start[0]);  // the point as a zero-length edge
  EXPECT_EQ(crossing.points[7], end[2]);
  EXPECT_THROW(make_query(Kind::vertex_face, start, end), std::invalid_argument);
  const QueryResult alone = query_ccd(Kind::vertex_edge, lifted(crossing));
  EXPECT_TRUE(alone.hit);
  EXPECT_NEAR(alone.toi, 0.5, 1e-6);

  // A NaN makes that query invalid_input and leaves the others' answers.
  std::vector<Query2D> queries(3, crossing);
  queries[1].points[4].y() = std::nan("");
  Options options;
  options.per_candidate_results = true;
  BatchResult out = batch_ccd(Kind::vertex_edge, queries, options);
  ASSERT_EQ(out.results.size(), 3u);
  EXPECT_EQ(out.results[1].status, Status::invalid_input);
  EXPECT_EQ(out.results[0].toi, alone.toi);
  EXPECT_EQ(out.results[2].toi, alone.toi);
  EXPECT_EQ(out.counters.invalid, 1);

  // What the call refuses leaves `out` as it was.
  const std::vector<double> too_few(2, 0.0), negative{0.0, -1.0, 0.0};
  EXPECT_THROW(batch_ccd(Kind::vertex_edge, std::span<const Query2D>(queries), too_few, options, out),
               std::invalid_argument);
  EXPECT_THROW(batch_ccd(Kind::vertex_edge, std::span<const Query2D>(queries), negative, options, out),
               std::invalid_argument);
  Options bad = options;
  bad.tmax = 2;
  EXPECT_THROW(batch_ccd(Kind::vertex_edge, std::span<const Query2D>(queries), bad, out), std::invalid_argument);
  EXPECT_EQ(out.results[1].status, Status::invalid_input);
  EXPECT_EQ(out.counters.invalid, 1);
}

// The shared data's coplanar-motion queries (planar/), in every mode, and the
// lanes against the scalar path: identical answers.
TEST(PlanarSharedData, ZeroWrongDecisionsAndLanesMatchScalar) {
  const std::filesystem::path root = testing::kSharedData / "planar";
  if (!std::filesystem::is_directory(root)) GTEST_SKIP() << root << " is absent";
  int files = 0;
  for (const char* plane : {"z0", "z075"})
    for (const auto& [kind, path] : {std::pair{Kind::vertex_face, "vertex-face/vf.csv"},
                                     std::pair{Kind::edge_edge, "edge-edge/ee.csv"}}) {
      const QueryFile file = read_query_csv(root / plane / path, kind);
      ASSERT_TRUE(file.truth.has_value());
      ++files;
      for (Mode mode : {Mode::conservative, Mode::exact}) {
        Options options = options_for(mode);
        const BatchResult lanes = batch_ccd(kind, file.queries, options);
        options.isa = Isa::scalar;
        const BatchResult scalar = batch_ccd(kind, file.queries, options);
        int wrong = 0;
        for (std::size_t i = 0; i < file.queries.size(); ++i) {
          wrong += lanes.results[i].hit != (*file.truth)[i];
          EXPECT_EQ(lanes.results[i].hit, scalar.results[i].hit);
          EXPECT_EQ(lanes.results[i].toi, scalar.results[i].toi);
        }
        EXPECT_EQ(wrong, 0) << plane << " " << path << " " << to_string(mode);
        EXPECT_LE(lanes.counters.exact_escalations, static_cast<std::int64_t>(file.queries.size() / 100));
      }
    }
  EXPECT_EQ(files, 4);
}

}  // namespace
}  // namespace batchccd

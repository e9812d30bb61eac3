// Minimum separation, tmax and the point kinds (docs/design.md §11): hand-made
// cases at and around the separation, an independent exact reference
// (tests/exact_distance.hpp), properties, batches against single queries,
// bad options, and the labelled data of ../shared/data/min-distance.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "batchccd/io.hpp"
#include "batchccd/lab.hpp"
#include "exact/exact_solver.hpp"
#include "exact/plane_axis.hpp"
#include "reference/filter.hpp"
#include "reference/scaled_query.hpp"
#include "exact_distance.hpp"
#include "query_builders.hpp"
#include "shared_data.hpp"

namespace batchccd {
namespace {

using testing::Rational;
using testing::squared_distance_at;

constexpr Mode kCertified[] = {Mode::conservative, Mode::exact};

Options with(Mode mode, double min_distance, double tmax = 1.0) {
  Options options;
  options.mode = mode;
  options.min_distance = min_distance;
  options.tmax = tmax;
  return options;
}

// A vertex moving straight down (-z) onto the unit right triangle in z = 0,
// above the point (0.25, 0.25): at height `low` at t = 1/2, symmetric in time.
Query vertex_dipping_to(double low) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const double high = low + 1;  // at t = 0 and t = 1 (it goes down, then up: two steps joined)
  return {{Vec3(0.25, 0.25, high), a, b, c, Vec3(0.25, 0.25, low), a, b, c}};
}

TEST(MinDistance, VertexFaceAtAndAroundTheSeparation) {
  const double separation = 0.01;
  for (const Mode mode : kCertified) {
    SCOPED_TRACE(to_string(mode));
    const QueryResult touching = query_ccd(Kind::vertex_face, vertex_dipping_to(separation), with(mode, separation));
    EXPECT_TRUE(touching.hit);
    EXPECT_LE(touching.toi, 1.0);
    EXPECT_GE(touching.toi, 1.0 - 1e-6);  // the first time within the separation is t = 1
    EXPECT_TRUE(query_ccd(Kind::vertex_face, vertex_dipping_to(separation * (1 - 1e-6)), with(mode, separation)).hit);
    EXPECT_FALSE(query_ccd(Kind::vertex_face, vertex_dipping_to(separation * (1 + 1e-6)), with(mode, separation)).hit);
  }
  // Exact mode's band is 2^-40 of the query's size: a hair of 1e-10 outside is a miss.
  EXPECT_FALSE(query_ccd(Kind::vertex_face, vertex_dipping_to(separation + 1e-10), with(Mode::exact, separation)).hit);
}

TEST(MinDistance, ContactBeforeCrossingIsFoundEarlier) {
  // Falling through the triangle at t = 1/2 from height 1: within 0.1 from t = 0.45.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Query falling{{Vec3(0.2, 0.2, 1), a, b, c, Vec3(0.2, 0.2, -1), a, b, c}};
  for (const Mode mode : kCertified) {
    const QueryResult result = query_ccd(Kind::vertex_face, falling, with(mode, 0.1));
    ASSERT_TRUE(result.hit);
    EXPECT_LE(result.toi, 0.45);
    EXPECT_GE(result.toi, 0.45 - 1e-6);
  }
}

TEST(MinDistance, ParallelEdgesAtTheSeparation) {
  // Two parallel edges exactly 0.5 apart, sliding along each other.
  const Query query{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0.5, 0), Vec3(1, 0.5, 0), Vec3(0, 0, 0),
                     Vec3(1, 0, 0), Vec3(0.5, 0.5, 0), Vec3(1.5, 0.5, 0)}};
  for (const Mode mode : kCertified) {
    SCOPED_TRACE(to_string(mode));
    const QueryResult at = query_ccd(Kind::edge_edge, query, with(mode, 0.5));
    EXPECT_TRUE(at.hit);
    EXPECT_EQ(at.toi, 0.0);
    EXPECT_FALSE(query_ccd(Kind::edge_edge, query, with(mode, 0.5 * (1 - 1e-6))).hit);
  }
}

TEST(MinDistance, VertexSlidingAlongTheShell) {
  // A vertex gliding over the triangle at height h: a contact at t = 0 when h <= s.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const auto gliding = [&](double h) {
    return Query{{Vec3(0.1, 0.1, h), a, b, c, Vec3(0.6, 0.2, h), a, b, c}};
  };
  for (const Mode mode : kCertified) {
    EXPECT_EQ(query_ccd(Kind::vertex_face, gliding(0.125), with(mode, 0.125)).toi, 0.0);
    EXPECT_FALSE(query_ccd(Kind::vertex_face, gliding(0.125 * (1 + 1e-6)), with(mode, 0.125)).hit);
  }
}

TEST(MinDistance, PointKindsAndDegeneratePrimitives) {
  const Vec3 origin(0, 0, 0);
  for (const Mode mode : kCertified) {
    SCOPED_TRACE(to_string(mode));
    // A point passing 0.3 from a static edge's middle (closest at t = 1/2).
    const QueryResult near = vertex_edge_ccd(Vec3(0.5, 0.3, -1), Vec3(0, 0, 0), Vec3(1, 0, 0),
                                             Vec3(0.5, 0.3, 1), Vec3(0, 0, 0), Vec3(1, 0, 0), with(mode, 0.3));
    EXPECT_TRUE(near.hit);
    EXPECT_NEAR(near.toi, 0.5, 1e-6);
    EXPECT_FALSE(vertex_edge_ccd(Vec3(0.5, 0.3, -1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.3, 1),
                                 Vec3(0, 0, 0), Vec3(1, 0, 0), with(mode, 0.29))
                     .hit);
    // Past the edge's end: the distance to the end point counts (0.5 at t = 1/2).
    EXPECT_FALSE(vertex_edge_ccd(Vec3(1.3, 0.4, -1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1.3, 0.4, 1),
                                 Vec3(0, 0, 0), Vec3(1, 0, 0), with(mode, 0.49))
                     .hit);
    EXPECT_TRUE(vertex_edge_ccd(Vec3(1.3, 0.4, -1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1.3, 0.4, 1),
                                Vec3(0, 0, 0), Vec3(1, 0, 0), with(mode, 0.5))
                    .hit);
    // A zero-length edge is a point; coincident points are within any separation.
    EXPECT_TRUE(vertex_edge_ccd(Vec3(0, 0, 1), origin, origin, Vec3(0, 0, -1), origin, origin, with(mode, 0.0)).hit);
    EXPECT_EQ(vertex_vertex_ccd(origin, origin, origin, origin, with(mode, 0.5)).toi, 0.0);
    // Two points passing 0.25 apart at t = 1/2.
    EXPECT_TRUE(vertex_vertex_ccd(Vec3(-1, 0, 0), Vec3(1, 0.25, 0), Vec3(1, 0, 0), Vec3(-1, 0.25, 0),
                                  with(mode, 0.25))
                    .hit);
    EXPECT_FALSE(vertex_vertex_ccd(Vec3(-1, 0, 0), Vec3(1, 0.25, 0), Vec3(1, 0, 0), Vec3(-1, 0.25, 0),
                                   with(mode, 0.24))
                     .hit);
    // A zero-area triangle is a segment.
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
    EXPECT_TRUE(vertex_face_ccd(Vec3(1.5, 0.2, 0), a, b, c, Vec3(1.5, 0.2, 0), a, b, c, with(mode, 0.2)).hit);
    EXPECT_FALSE(vertex_face_ccd(Vec3(1.5, 0.2, 0), a, b, c, Vec3(1.5, 0.2, 0), a, b, c, with(mode, 0.19)).hit);
  }
}

TEST(MinDistance, MakeQueryLaysOutPointKinds) {
  const std::vector<Vec3> t0{Vec3(1, 2, 3), Vec3(4, 5, 6), Vec3(7, 8, 9)}, t1{Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0)};
  const Query q = make_query(Kind::vertex_edge, t0, t1);
  EXPECT_EQ(q.points[0], t0[0]);
  EXPECT_EQ(q.points[1], t0[0]);
  EXPECT_EQ(q.points[3], t0[2]);
  EXPECT_EQ(q.points[5], t1[0]);
  EXPECT_EQ(q.points[7], t1[2]);
  EXPECT_THROW(make_query(Kind::vertex_vertex, t0, t1), std::invalid_argument);
}

TEST(Tmax, CutsAContactOffInEveryModeAndBaseline) {
  // The vertex crosses the triangle at t = 0.6.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Query crossing{{Vec3(0.2, 0.2, 0.6), a, b, c, Vec3(0.2, 0.2, -0.4), a, b, c}};
  for (const lab::Method& method : {lab::kConservative, lab::kExact, lab::kFast, lab::kCubic}) {
    SCOPED_TRACE(lab::to_string(method));
    const auto run = [&](double tmax) {
      return lab::query_ccd(Kind::vertex_face, crossing, with(method.mode, 0, tmax), method.settings());
    };
    EXPECT_FALSE(run(0.5).hit);
    const QueryResult within = run(0.75);
    EXPECT_TRUE(within.hit);
    EXPECT_NEAR(within.toi, 0.6, 1e-6);
    // Exactly at tmax counts.
    if (method == lab::kExact) {
      EXPECT_TRUE(run(0.6).hit);
    }
  }
  // With a separation of 0.1 the contact starts at t = 0.5.
  for (const Mode mode : kCertified) {
    EXPECT_FALSE(query_ccd(Kind::vertex_face, crossing, with(mode, 0.1, 0.49)).hit);
    EXPECT_TRUE(query_ccd(Kind::vertex_face, crossing, with(mode, 0.1, 0.51)).hit);
  }
}

TEST(Tmax, ExactModeDecidesAtTmaxExactly) {
  // Crossing at t = 0.6 (not a dyadic): the exact stage compares with tmax exactly.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Query crossing{{Vec3(0.2, 0.2, 0.6), a, b, c, Vec3(0.2, 0.2, -0.4), a, b, c}};
  const double before = std::nextafter(0.6, 0.0), after = std::nextafter(0.6, 1.0);
  // 0.6 as a double is either side of the true 3/5; its neighbours bracket it.
  EXPECT_FALSE(query_ccd(Kind::vertex_face, crossing, with(Mode::exact, 0, std::nextafter(before, 0.0))).hit);
  EXPECT_TRUE(query_ccd(Kind::vertex_face, crossing, with(Mode::exact, 0, after)).hit);
}

// squared_distance (ccd.hpp) against distances known by construction, for
// every kind and closest feature: a face's interior, an edge, a corner;
// edges skew, parallel, end to end; a point beside a segment and beyond its
// end. Each configuration is the midpoint of a motion, asked at t = 1/2.
TEST(SquaredDistance, EqualsTheDistanceKnownByConstruction) {
  struct Case {
    Kind kind;
    std::vector<Vec3> points;  // make_query's, at t = 1/2
    double expected;
  };
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  const std::vector<Case> cases = {
      {Kind::vertex_face, {Vec3(1, 1, 3), a, b, c}, 9},     // above the face
      {Kind::vertex_face, {Vec3(2, -3, 4), a, b, c}, 25},   // beside edge ab
      {Kind::vertex_face, {Vec3(3, 3, 0), a, b, c}, 2},     // beside the hypotenuse, in the plane
      {Kind::vertex_face, {Vec3(-3, -4, 0), a, b, c}, 25},  // beyond corner a
      {Kind::edge_edge, {a, b, Vec3(2, -1, 3), Vec3(2, 1, 3)}, 9},      // skew, crossing above
      {Kind::edge_edge, {a, b, Vec3(1, 2, 0), Vec3(3, 2, 0)}, 4},       // parallel
      {Kind::edge_edge, {a, Vec3(1, 0, 0), b, Vec3(5, 0, 0)}, 9},       // collinear, end to end
      {Kind::edge_edge, {a, b, Vec3(7, 4, -1), Vec3(7, 4, 1)}, 25},     // end b to the other's middle
      {Kind::vertex_edge, {Vec3(2, 3, 0), a, b}, 9},
      {Kind::vertex_edge, {Vec3(7, 4, 0), a, b}, 25},
      {Kind::vertex_vertex, {Vec3(1, 2, 2), a}, 9},
  };
  const Vec3 motion(1, -2, 3);
  for (const Case& test : cases) {
    std::vector<Vec3> start, end;
    for (std::size_t k = 0; k < test.points.size(); ++k) {
      const Vec3 along = static_cast<double>(k + 1) * motion;
      start.push_back(test.points[k] - along);
      end.push_back(test.points[k] + along);
    }
    const Query query = make_query(test.kind, start, end);
    EXPECT_EQ(squared_distance(test.kind, query, 0.5), test.expected) << to_string(test.kind) << " " << test.expected;
    // Exact at the ends too: the exact rational distance there.
    for (const double t : {0.0, 1.0})
      EXPECT_NEAR(squared_distance(test.kind, query, t),
                  squared_distance_at(test.kind, query, Rational(t)).get_d(), 1e-12 * (1 + test.expected))
          << to_string(test.kind) << " t = " << t;
  }
}

// From fuzz_point_kinds: the labeller on a query scaled by 2^509, whose
// squared speeds (2^1026) lie beyond the doubles. Its Lipschitz bound was
// the Rational of an infinite double, which traps inside GMP (SIGFPE). Now
// the bound is +inf: a witness still labels a hit, nothing certifies a miss.
TEST(ExactLabels, QueriesNearTheTopOfTheDoubleRange) {
  const double s = 0x1p509;
  Options options;
  options.mode = Mode::exact;
  options.min_distance = s / 2;
  // A point crossing a static segment at t = 1/2, within s/2 of it from t = 15/32.
  const Query crossing = make_query(Kind::vertex_edge, std::vector<Vec3>{{8 * s, 0, 0}, {0, -s, 0}, {0, s, 0}},
                                    std::vector<Vec3>{{-8 * s, 0, 0}, {0, -s, 0}, {0, s, 0}});
  const testing::Labelled hit = testing::label(Kind::edge_edge, crossing, options.min_distance);
  ASSERT_EQ(hit.label, testing::Label::hit);
  const QueryResult result = query_ccd(Kind::vertex_edge, crossing, options);
  ASSERT_TRUE(result.hit);
  EXPECT_LE(result.toi, hit.witness);
  EXPECT_GE(result.toi, 15.0 / 32 - 0x1p-40);
  // The same point passing 3s above the segment: never within s/2.
  const Query passing = make_query(Kind::vertex_edge, std::vector<Vec3>{{8 * s, 0, 3 * s}, {0, -s, 0}, {0, s, 0}},
                                   std::vector<Vec3>{{-8 * s, 0, 3 * s}, {0, -s, 0}, {0, s, 0}});
  EXPECT_NE(testing::label(Kind::edge_edge, passing, options.min_distance).label, testing::Label::hit);
  EXPECT_FALSE(query_ccd(Kind::vertex_edge, passing, options).hit);
}

TEST(BadOptions, AreRefusedByEveryCall) {
  const Query q = vertex_dipping_to(1);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const Options& bad : {with(Mode::conservative, -1), with(Mode::conservative, nan), with(Mode::exact, inf),
                             with(Mode::conservative, 0, 0), with(Mode::conservative, 0, 1.5),
                             with(Mode::conservative, 0, nan)}) {
    EXPECT_THROW(query_ccd(Kind::vertex_face, q, bad), std::invalid_argument);
    EXPECT_THROW(batch_ccd(Kind::vertex_face, std::vector<Query>{q}, bad), std::invalid_argument);
    const Eigen::MatrixXd positions = Eigen::MatrixXd::Zero(3, 3);
    const Eigen::MatrixXi faces = Eigen::MatrixXi::Zero(0, 3);
    EXPECT_THROW(mesh_ccd({positions, positions, faces}, CandidateLists{}, bad), std::invalid_argument);
  }
  try {
    query_ccd(Kind::vertex_face, q, with(Mode::conservative, -0.5));
    ADD_FAILURE() << "min_distance -0.5 was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("min_distance"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("-0.5"), std::string::npos) << error.what();
  }
  // Per-candidate separations: the length and each value.
  BatchResult out;
  const std::vector<Query> queries{q, q};
  const std::vector<double> short_list{0.1}, bad_value{0.1, -2};
  EXPECT_THROW(batch_ccd(Kind::vertex_face, queries, short_list, Options{}, out), std::invalid_argument);
  try {
    batch_ccd(Kind::vertex_face, queries, bad_value, Options{}, out);
    ADD_FAILURE() << "a negative separation was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("candidate 1"), std::string::npos) << error.what();
  }
}

// The cubic baseline finds roots, not distances: every lab call refuses a
// separation for it, naming the field and the value.
TEST(BadOptions, CubicBaselineRefusesASeparation) {
  const Query q = vertex_dipping_to(1);
  const lab::Settings cubic = lab::kCubic.settings();
  const Options separated = with(Mode::conservative, 0.1);
  EXPECT_NO_THROW(validate(separated));  // a mode takes it
  try {
    lab::query_ccd(Kind::vertex_face, q, separated, cubic);
    ADD_FAILURE() << "the cubic baseline took min_distance 0.1";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("min_distance"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("0.1"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("cubic"), std::string::npos) << error.what();
  }
  EXPECT_THROW(lab::batch_ccd(Kind::vertex_face, std::vector<Query>{q}, separated, cubic), std::invalid_argument);
  const Eigen::MatrixXd positions = Eigen::MatrixXd::Zero(3, 3);
  const Eigen::MatrixXi faces = Eigen::MatrixXi::Zero(0, 3);
  EXPECT_THROW(lab::mesh_ccd({positions, positions, faces}, CandidateLists{}, separated, cubic), std::invalid_argument);
  // One per candidate, too; a separation of 0 is no separation.
  BatchResult out;
  const std::vector<Query> queries{q, q};
  const std::vector<double> one_separated{0, 0.1}, none{0, 0};
  EXPECT_THROW(lab::batch_ccd(Kind::vertex_face, queries, one_separated, Options{}, cubic, out),
               std::invalid_argument);
  EXPECT_NO_THROW(lab::batch_ccd(Kind::vertex_face, queries, none, Options{}, cubic, out));
  EXPECT_EQ(out.results.size(), 2u);
}

// Random queries of every kind with dyadic coordinates, near misses among them.
struct RandomQueries {
  std::mt19937_64 random{20261124};
  double coordinate() { return static_cast<double>(std::uniform_int_distribution<int>(-1024, 1024)(random)) / 1024; }
  Vec3 point() { return {coordinate(), coordinate(), coordinate()}; }
  Query next(Kind kind) {
    std::vector<Vec3> t0, t1;
    for (int k = 0; k < points_per_time(kind); ++k) {
      t0.push_back(point());
      t1.push_back(point());
    }
    return make_query(kind, t0, t1);
  }
};

constexpr Kind kKinds[] = {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex};

// Exact distances at 65 times: a sampled time within the separation proves a
// contact; a certified miss must have none, and a hit's toi none before it.
TEST(MinDistance, AgreesWithExactDistancesAtSampledTimes) {
  RandomQueries generator;
  const double separation = 0.25;
  const Rational separation2 = Rational(separation) * Rational(separation);
  int hits = 0, misses = 0;
  for (const Kind kind : kKinds)
    for (int n = 0; n < 60; ++n) {
      const Query q = generator.next(kind);
      int first_sample = -1;
      for (int k = 0; k <= 64 && first_sample < 0; ++k)
        if (squared_distance_at(kind, q, Rational(k, 64)) <= separation2) first_sample = k;
      for (const Mode mode : kCertified) {
        const QueryResult result = query_ccd(kind, q, with(mode, separation));
        if (first_sample >= 0) {
          EXPECT_TRUE(result.hit) << to_string(kind) << " " << n << " " << to_string(mode);
          EXPECT_LE(result.toi, first_sample / 64.0);
        }
        (result.hit ? hits : misses) += 1;
      }
    }
  // The generator's queries are neither all hits nor all misses.
  EXPECT_GT(hits, 60);
  EXPECT_GT(misses, 60);
}

// Pairs sliding past each other near a separation of 1/16 (the survivors
// the solver clears along the closest direction, docs/design.md §11): the
// lower primitive near z = 0 with small tilts, the upper one between s/2
// and 3s above it, both moving far across it and slowly along z, with the
// axes permuted by n.
Query sliding_pair(std::mt19937_64& random, Kind kind, int n) {
  const auto dyadic = [&](int low, int high, int denominator) {
    return static_cast<double>(std::uniform_int_distribution<int>(low, high)(random)) / denominator;
  };
  const int count = points_per_time(kind);
  // Kind's layout: the upper primitive first (VF: the vertex, then the
  // triangle; edge-edge and the point kinds: the first edge or point).
  const int upper = kind == Kind::vertex_face ? 1 : count / 2;
  const int axis = n % 3;
  std::vector<Vec3> t0, t1;
  for (int k = 0; k < count; ++k) {
    const bool above = k < upper;
    const auto place = [&](std::vector<Vec3>& at) {
      const double height = above ? dyadic(32, 192, 1024) : dyadic(-16, 16, 1024);
      Vec3 p(dyadic(-1024, 1024, 1024), dyadic(-1024, 1024, 1024), height);
      at.push_back(Vec3(p[(3 - axis) % 3], p[(4 - axis) % 3], p[(5 - axis) % 3]));
    };
    place(t0);
    place(t1);
  }
  return make_query(kind, t0, t1);
}

// Sliding pairs, exact distances at 257 times: a sample within s must give
// a hit no later than it. A step along the closest direction that went
// past the time its gap reaches s (the plain-double reach not certified,
// or taken 1.5 times) fails here.
TEST(MinDistance, SlidingPairsAgreeWithExactDistancesAtSampledTimes) {
  std::mt19937_64 random(20261127);
  const double separation = 0.0625;
  const Rational separation2 = Rational(separation) * Rational(separation);
  int hits = 0, misses = 0;
  for (const Kind kind : kKinds)
    for (int n = 0; n < 150; ++n) {
      const Query q = sliding_pair(random, kind, n);
      int first_sample = -1;
      for (int k = 0; k <= 256 && first_sample < 0; ++k)
        if (squared_distance_at(kind, q, Rational(k, 256)) <= separation2) first_sample = k;
      for (const Mode mode : kCertified) {
        const QueryResult result = query_ccd(kind, q, with(mode, separation));
        if (first_sample >= 0) {
          EXPECT_TRUE(result.hit) << to_string(kind) << " " << n << " " << to_string(mode);
          EXPECT_LE(result.toi, first_sample / 256.0) << to_string(kind) << " " << n << " " << to_string(mode);
        }
        (result.hit ? hits : misses) += 1;
      }
    }
  EXPECT_GT(hits, 50);
  EXPECT_GT(misses, 500);
}

// The pieces of the step the filters prove free (FilterVerdict::free_pieces,
// which the solver never searches) hold no time within the separation:
// exact distances at 33 times in each, on sliding pairs at 1/16 and at 0
// (where they are rarely that close), with 2, 4 and 8 pieces. Pieces
// counted free by mistake (a bit for the wrong piece, a piece free by one
// test taken for free by both) fail here.
TEST(FreePieces, HoldNoTimeWithinTheSeparation) {
  std::mt19937_64 random(20261128);
  int free = 0, open = 0;
  for (const Kind kind : kKinds)
    for (int n = 0; n < 150; ++n) {
      const Query q = sliding_pair(random, kind, n);
      for (const double separation : {0.0625, 0.0})
        for (const int pieces : {2, 4, 8}) {
          lab::Settings lab;
          lab.filter_pieces = pieces;
          const reference::FilterSettings settings = reference::settings_for(
              kind, reference::filter_settings(with(Mode::conservative, separation), lab));
          const reference::FilterVerdict verdict =
              reference::run_filters(reference::evaluated_kind(kind), q, settings);
          if (verdict.culled() && !verdict.pieces) continue;  // the whole step, before the pieces ran
          const Rational separation2 = Rational(separation) * Rational(separation);
          for (int j = 0; j < pieces; ++j) {
            if (!(verdict.free_pieces >> j & 1)) {
              ++open;
              continue;
            }
            ++free;
            for (int k = 0; k <= 32; ++k) {
              const Rational t = Rational(32 * j + k, 32 * pieces);
              EXPECT_GT(squared_distance_at(kind, q, t), separation2)
                  << to_string(kind) << " " << n << ", piece " << j << " of " << pieces << " at " << t.get_d()
                  << ", separation " << separation;
            }
          }
        }
    }
  EXPECT_GT(free, 1000);
  EXPECT_GT(open, 1000);
}

TEST(MinDistance, Properties) {
  RandomQueries generator;
  for (const Kind kind : kKinds)
    for (int n = 0; n < 40; ++n) {
      const Query q = generator.next(kind);
      const QueryResult zero = query_ccd(kind, q, with(Mode::exact, 0));
      const QueryResult small = query_ccd(kind, q, with(Mode::exact, 0x1p-60));
      const QueryResult at = query_ccd(kind, q, with(Mode::exact, 0.125));
      const QueryResult larger = query_ccd(kind, q, with(Mode::exact, 0.25));
      // A hit at a separation is a hit at every larger one, never later.
      if (zero.hit) {
        EXPECT_TRUE(small.hit);
      }
      if (at.hit) {
        EXPECT_TRUE(larger.hit);
        EXPECT_LE(larger.toi, at.toi);
      }
      // A separation that tends to 0 gives the zero-separation decision.
      EXPECT_EQ(small.hit, zero.hit) << to_string(kind) << " " << n;
      // Powers of two scale nothing that matters.
      Query scaled = q;
      for (Vec3& p : scaled.points) p *= 0x1p-300;
      for (const Mode mode : kCertified) {
        const QueryResult original = query_ccd(kind, q, with(mode, 0.125));
        const QueryResult tiny = query_ccd(kind, scaled, with(mode, 0.125 * 0x1p-300));
        EXPECT_EQ(original.hit, tiny.hit);
        EXPECT_EQ(original.toi, tiny.toi);
      }
      // Axis permutations, the order of the primitives and time reversal keep the decision.
      Query permuted = q, reversed = q;
      for (Vec3& p : permuted.points) p = Vec3(p.z(), p.x(), p.y());
      for (int k = 0; k < 4; ++k) std::swap(reversed.points[k], reversed.points[k + 4]);
      EXPECT_EQ(query_ccd(kind, permuted, with(Mode::exact, 0.125)).hit, at.hit);
      EXPECT_EQ(query_ccd(kind, reversed, with(Mode::exact, 0.125)).hit, at.hit);
      if (kind != Kind::vertex_face) {
        Query swapped = q;
        for (int t = 0; t < 8; t += 4) {
          std::swap(swapped.points[t], swapped.points[t + 2]);
          std::swap(swapped.points[t + 1], swapped.points[t + 3]);
        }
        EXPECT_EQ(query_ccd(Kind::edge_edge, swapped, with(Mode::exact, 0.125)).hit, at.hit);
      } else {
        Query rotated = q;  // the triangle's corners in another order
        for (int t = 0; t < 8; t += 4) std::swap(rotated.points[t + 1], rotated.points[t + 3]);
        EXPECT_EQ(query_ccd(kind, rotated, with(Mode::exact, 0.125)).hit, at.hit);
      }
    }
}

TEST(MinDistance, BatchesEqualSingleQueriesWithEveryInstructionSet) {
  RandomQueries generator;
  for (const Kind kind : kKinds) {
    std::vector<Query> queries;
    std::vector<double> separations;
    for (int n = 0; n < 200; ++n) {
      queries.push_back(generator.next(kind));
      separations.push_back(n % 3 == 0 ? 0.0 : 0.0625 * (n % 5));
    }
    for (const Isa isa : available_isas()) {
      Options options;
      options.isa = isa;
      BatchResult batch;
      batch_ccd(kind, queries, separations, options, batch);
      for (std::size_t i = 0; i < queries.size(); ++i) {
        Options single = options;
        single.min_distance = separations[i];
        const QueryResult alone = query_ccd(kind, queries[i], single);
        EXPECT_EQ(batch.results[i].hit, alone.hit) << to_string(kind) << " " << i;
        EXPECT_EQ(batch.results[i].toi, alone.toi) << to_string(kind) << " " << i;
      }
    }
  }
}

TEST(MinDistance, MeshCandidatesOfEveryKind) {
  // A falling vertex over a square of two triangles, its edges, and a static vertex.
  Eigen::MatrixXd x0(6, 3), x1(6, 3);
  x0 << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1, 2, 2, 0;
  x1 = x0;
  x1.row(4) << 0.5, 0.5, -1;
  Eigen::MatrixXi faces(2, 3);
  faces << 0, 1, 2, 0, 2, 3;
  Candidates candidates;
  candidates.vertex_face = {{4, 0}, {4, 1}, {5, 0}};
  candidates.edge_edge = {{0, 1, 2, 3}};
  candidates.vertex_edge = {{4, 0, 1}, {5, 1, 2}};
  candidates.vertex_vertex = {{4, 2}, {5, 2}};
  const std::vector<double> vertex_vertex_separations{0.1, 1.5};
  Options options;
  options.min_distance = 0.5;
  BatchResult out;
  mesh_ccd({x0, x1, faces}, candidates, MinDistances{.vertex_vertex = vertex_vertex_separations}, options, out);
  ASSERT_EQ(out.results.size(), 8u);
  const std::vector<testing::KindQuery> singles = testing::candidate_queries({x0, x1, faces}, candidates);
  ASSERT_EQ(singles.size(), out.results.size());
  for (std::size_t i = 0; i < singles.size(); ++i) {
    Options single = options;
    if (i >= 6) single.min_distance = vertex_vertex_separations[i - 6];
    const QueryResult alone = query_ccd(singles[i].kind, singles[i].query, single);
    EXPECT_EQ(out.results[i].hit, alone.hit) << i;
    EXPECT_EQ(out.results[i].toi, alone.toi) << i;
  }
  EXPECT_TRUE(out.results[0].hit);   // the vertex falls through the first triangle
  EXPECT_FALSE(out.results[2].hit);  // the static vertex is far from it
  EXPECT_TRUE(out.results[4].hit);   // vertex 4 passes 0.5 from edge (0, 1) at t = 1/2
  EXPECT_FALSE(out.results[6].hit);  // and sqrt(1/2) from vertex 2: more than its own 0.1
  EXPECT_TRUE(out.results[7].hit);   // vertex 5 is sqrt(2) from vertex 2: within its own 1.5
}

// ../shared/data/min-distance/unit-ms1e-3: labelled by exact witnesses and a
// conservative peer; its near misses are far from the separation, so both
// certified modes must match every label.
TEST(SharedMinDistanceData, CertifiedModesMatchEveryLabel) {
  const std::filesystem::path directory = testing::kSharedData / "min-distance" / "unit-ms1e-3";
  if (!std::filesystem::exists(directory / "ms.txt")) GTEST_SKIP() << directory << " is absent";
  double separation = 0;
  std::ifstream(directory / "ms.txt") >> separation;
  ASSERT_EQ(separation, 1e-3);
  for (const char* name : {"vf.csv", "ee.csv"}) {
    const QueryFile file = read_query_csv(directory / name, *kind_from_path(directory / name));
    ASSERT_TRUE(file.truth.has_value());
    // Both answers present: a file of one label could not tell a mode that says it always.
    ASSERT_GT(std::count(file.truth->begin(), file.truth->end(), true), 0) << name;
    ASSERT_GT(std::count(file.truth->begin(), file.truth->end(), false), 0) << name;
    for (const Mode mode : kCertified) {
      Options options = with(mode, separation);
      const BatchResult batch = batch_ccd(file.kind, file.queries, options);
      int false_negatives = 0, false_positives = 0;
      for (std::size_t i = 0; i < file.queries.size(); ++i) {
        false_negatives += (*file.truth)[i] && !batch.results[i].hit;
        false_positives += !(*file.truth)[i] && batch.results[i].hit;
      }
      EXPECT_EQ(false_negatives, 0) << name << " " << to_string(mode);
      EXPECT_EQ(false_positives, 0) << name << " " << to_string(mode);
    }
  }
}

}  // namespace
}  // namespace batchccd

namespace batchccd {
namespace {

// A point against a segment or a point in 3D is decided by its
// vertex-segment conditions (docs/design.md §5a): at a separation, every
// answer held to exact labels and to the search over (t, u, v) in exact mode
// (the same decisions, TOIs within 2^-40); at separation 0, its misses to
// the exact stage. Nearly planar motion (heights within 2^-6) is where that
// search got lost.
TEST(PointSearch, AgreesWithExactLabelsAndTheGenericSearch) {
  lab::Settings generic;
  generic.point_search = false;
  std::mt19937_64 random(53);
  std::uniform_int_distribution<int> coordinate(-(1 << 16), 1 << 16);
  const auto dyadic = [&](int bits) { return std::ldexp(static_cast<double>(coordinate(random)), -16 - bits); };
  int hits = 0, labelled = 0, queries = 0, misses_at_zero = 0;
  for (Kind kind : {Kind::vertex_edge, Kind::vertex_vertex})
    for (int i = 0; i < 120; ++i) {
      const int flat = i % 2 ? 6 : 0;  // every other query nearly planar
      std::vector<Vec3> start, end;
      for (int k = 0; k < points_per_time(kind); ++k) {
        start.emplace_back(dyadic(0), dyadic(0), dyadic(flat));
        end.push_back(start.back() + Vec3(dyadic(1), dyadic(1), dyadic(flat + 1)));
      }
      // The point ends near the other primitive (within about 0.1 of a
      // point of it): a good part come within the separations below.
      const Vec3 target = kind == Kind::vertex_edge ? 0.5 * (end[1] + end[2]) + (dyadic(1) + 0.5) * (end[2] - end[1])
                                                    : end[1];
      end[0] = target + Vec3(dyadic(4), dyadic(4), dyadic(flat + 4));
      const Query query = make_query(kind, start, end);
      for (double separation : {0.0, 0x1p-6, 0.125}) {
        SCOPED_TRACE(::testing::Message() << to_string(kind) << " query " << i << " D " << separation << " "
                                          << ::testing::PrintToString(query.points));
        ++queries;
        Options options;
        options.mode = Mode::exact;
        options.min_distance = separation;
        const QueryResult exact = query_ccd(kind, query, options);
        const QueryResult searched = lab::query_ccd(kind, query, options, generic);
        ASSERT_EQ(exact.hit, searched.hit);
        if (exact.hit) {
          EXPECT_NEAR(exact.toi, searched.toi, 2 * 0x1p-40);
        }
        options.mode = Mode::conservative;
        const QueryResult conservative = query_ccd(kind, query, options);
        ASSERT_EQ(conservative.hit, exact.hit);
        if (exact.hit) {
          EXPECT_LE(conservative.toi, exact.toi + 2 * 0x1p-40);
          EXPECT_GE(conservative.toi, exact.toi - options.toi_tolerance - 2 * 0x1p-40);
        }
        hits += exact.hit;
        misses_at_zero += separation == 0 && !exact.hit;
        if (separation == 0) continue;
        const testing::Labelled truth = testing::label(Kind::edge_edge, query, separation);
        if (truth.label == testing::Label::unlabelled) continue;
        ++labelled;
        ASSERT_EQ(exact.hit, truth.label == testing::Label::hit);
        if (exact.hit) {
          EXPECT_LE(exact.toi, truth.witness);
        }
      }
    }
  EXPECT_GT(hits, queries / 6);
  EXPECT_GT(misses_at_zero, 200);
  EXPECT_GT(labelled, queries * 6 / 10);
}

// Nearly planar point-edge motion without a separation: the search over
// (t, u, v) leaves many misses uncertain, which went to the exact stage;
// the pairs' search proves them (counted: no escalation).
// As in the 2D point lists of the planar benchmark lifted to 3D: a long
// segment, a point near it, motions of a few percent of the segment,
// heights within 1 % (drawn at t0 and t1 alike).
std::vector<Query> nearly_planar_point_edges(unsigned seed, int count) {
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<int> coordinate(-(1 << 16), 1 << 16);
  const auto dyadic = [&](int bits) { return std::ldexp(static_cast<double>(coordinate(random)), -16 - bits); };
  std::vector<Query> queries;
  for (int i = 0; i < count; ++i) {
    std::vector<Vec3> start, end;
    for (int k = 0; k < 3; ++k) start.emplace_back(dyadic(0), dyadic(0), std::fabs(dyadic(6)));
    start[0].head<2>() = 0.5 * (start[1] + start[2]).head<2>() + Vec3(dyadic(4), dyadic(4), 0).head<2>();
    for (int k = 0; k < 3; ++k)
      end.push_back(Vec3(start[k].x() + dyadic(5), start[k].y() + dyadic(5), std::fabs(dyadic(6))));
    queries.push_back(make_query(Kind::vertex_edge, start, end));
  }
  return queries;
}

TEST(PointSearch, ProvesNearlyPlanarMissesWithoutTheExactStage) {
  const std::vector<Query> queries = nearly_planar_point_edges(59, 2000);
  lab::Settings generic;
  generic.point_search = false;
  for (Mode mode : {Mode::conservative, Mode::exact}) {
    Options options;
    options.mode = mode;
    BatchResult with_pairs, without;
    lab::batch_ccd(Kind::vertex_edge, queries, {}, options, {}, with_pairs);
    lab::batch_ccd(Kind::vertex_edge, queries, {}, options, generic, without);
    EXPECT_GT(without.counters.exact_escalations, 10) << to_string(mode);  // 18 with the free pieces skipped
    EXPECT_LE(with_pairs.counters.exact_escalations, without.counters.hits) << to_string(mode);
    EXPECT_EQ(with_pairs.counters.hits, without.counters.hits);
    for (std::size_t i = 0; i < queries.size(); ++i) EXPECT_EQ(with_pairs.results[i].hit, without.results[i].hit);
  }
}

// At a separation the search over (t, u, v) comes first, with a small
// budget of boxes: conservative advancement settles nearly every query
// without any. Where exact mode needs more (nearly planar motion, hits
// within 2^-40 of the separation to certify), the pairs' search settles
// the query: with a budget the box search alone runs out of on many, it
// leaves nearly none undecided, and every decision is the box search's
// with the whole budget.
TEST(PointSearch, SettlesWhatTheFirstSearchLeavesAtASeparation) {
  const std::vector<Query> queries = nearly_planar_point_edges(67, 2000);
  lab::Settings generic;
  generic.point_search = false;
  for (Mode mode : {Mode::conservative, Mode::exact}) {
    Options options;
    options.mode = mode;
    options.min_distance = 0x1p-8;
    BatchResult whole_budget;
    lab::batch_ccd(Kind::vertex_edge, queries, {}, options, generic, whole_budget);
    options.max_iterations = 4;
    BatchResult with_pairs, without;
    lab::batch_ccd(Kind::vertex_edge, queries, {}, options, {}, with_pairs);
    lab::batch_ccd(Kind::vertex_edge, queries, {}, options, generic, without);
    EXPECT_EQ(whole_budget.counters.undecided, 0) << to_string(mode);
    if (mode == Mode::exact) {
      EXPECT_GT(without.counters.undecided, 50);  // the premise: 118
      EXPECT_LT(with_pairs.counters.undecided * 20, without.counters.undecided);  // 1
    }
    EXPECT_GT(with_pairs.counters.hits, 100) << to_string(mode);
    for (std::size_t i = 0; i < queries.size(); ++i) EXPECT_EQ(with_pairs.results[i].hit, whole_budget.results[i].hit);
  }
}

// At separation 0 the pairs' search only proves misses (proves_point_miss).
// A point that really touches its segment in motion that is not planar
// leaves the search over (t, u, v) uncertain -- the contact is an equality it
// cannot certify -- and must then reach the exact stage, never be excluded.
// Each contact is placed exactly at t = 1/2, at a quarter point of the
// segment: the exact distance there is 0. (Two points that meet always move
// in one plane, the planar path's.)
TEST(PointSearch, NeverExcludesAContactAtZeroSeparation) {
  std::mt19937_64 random(61);
  std::uniform_int_distribution<int> coordinate(-64, 64);
  const auto grid = [&] { return coordinate(random) / 16.0; };
  int queries = 0, escalated = 0;
  for (int i = 0; i < 60; ++i) {
    std::vector<Vec3> start, end;
    for (int k = 0; k < 3; ++k) {
      start.emplace_back(grid(), grid(), grid());
      end.emplace_back(grid(), grid(), grid());
    }
    const auto middle = [&](int k) -> Vec3 { return 0.5 * (start[k] + end[k]); };
    end[0] = 2 * (middle(1) + (i % 5) / 4.0 * (middle(2) - middle(1))) - start[0];
    const Query query = make_query(Kind::vertex_edge, start, end);
    if (exact::exact_plane_axis(query)) continue;  // planar: the planar path's, not this search's
    SCOPED_TRACE(::testing::Message() << "query " << i << " " << ::testing::PrintToString(query.points));
    ++queries;
    ASSERT_EQ(testing::squared_distance_at(Kind::edge_edge, query, testing::Rational(1, 2)), 0);
    const exact::ExactOutcome truth = exact::solve_exactly(Kind::edge_edge, query, true);
    ASSERT_TRUE(truth.hit);
    for (Mode mode : {Mode::conservative, Mode::exact}) {
      Options options;
      options.mode = mode;
      BatchResult out;
      lab::batch_ccd(Kind::vertex_edge, std::span<const Query>(&query, 1), {}, options, {}, out);
      ASSERT_TRUE(out.results[0].hit) << to_string(mode);
      EXPECT_LE(out.results[0].toi, truth.toi + 0x1p-40) << to_string(mode);
      if (mode == Mode::exact) {
        EXPECT_GE(out.results[0].toi, truth.toi - 0x1p-40);
        escalated += static_cast<int>(out.counters.exact_escalations);
      }
    }
  }
  EXPECT_GT(queries, 50);
  EXPECT_EQ(escalated, queries);  // every one left uncertain by the search over (t, u, v)
}

// Known times in 3D: a point falling past a tilted segment, and two points.
TEST(PointSearch, KnownTimes) {
  Options options;
  options.mode = Mode::exact;
  const auto expect_toi = [&](const QueryResult& result, double toi) {
    ASSERT_TRUE(result.hit) << toi;
    EXPECT_LE(result.toi, toi);
    EXPECT_GE(result.toi, toi - 0x1p-40);
  };
  options.min_distance = 0.25;
  // The segment from (0, 0, 0) to (1, 1, 0); the point falls along z at
  // (0.5, 0.5): its distance |z| = 1 - 2t reaches 0.25 at t = 3/8.
  expect_toi(vertex_edge_ccd({0.5, 0.5, 1}, {0, 0, 0}, {1, 1, 0}, {0.5, 0.5, -1}, {0, 0, 0}, {1, 1, 0}, options),
             0.375);
  // Points 4t apart along a diagonal direction of length 3 (2, 1, 2):
  // |q - p| = 3 (1 - t) reaches 0.25 at t = 11/12.
  expect_toi(vertex_vertex_ccd({0, 0, 0}, {2, 1, 2}, {0, 0, 0}, {0, 0, 0}, options), 11.0 / 12);
  // At separation 0 a point through the segment: a contact at t = 1/2;
  // reaching the segment's end exactly at t = 1 in nearly planar motion
  // (the box search stays uncertain, the exact stage decides); passing
  // 2^-20 beside it: a miss.
  options.min_distance = 0;
  expect_toi(vertex_edge_ccd({0.5, 0.5, 1}, {0, 0, 0}, {1, 1, 0}, {0.5, 0.5, -1}, {0, 0, 0}, {1, 1, 0}, options),
             0.5);
  expect_toi(vertex_edge_ccd({2, 1, 0x1p-10}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}, options), 1.0);
  EXPECT_FALSE(vertex_edge_ccd({0.5, 0.5, 1}, {0, 0, 0}, {1, 1, 0}, {0.5, 0.5 + 0x1p-19, -1}, {0, 0, 0},
                               {1, 1, 0}, options)
                   .hit);
}

}  // namespace
}  // namespace batchccd

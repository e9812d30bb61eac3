// Separations between turning primitives: a triangle or an edge that turns
// through a large angle over the step while the other primitive comes
// slowly towards it, as on the rod-twist scene. There a fixed direction's
// gap shrinks as fast as the turning primitive's farthest vertex moves, and
// the solver advances on the distance to the plane or between the lines
// instead (docs/design.md §11, cleared_by_plane). Held to exact distances
// at sampled times: a sample within the separation must give a hit no
// later than it; and to the exact labels of tests/exact_distance.hpp where
// they settle a query.
#include <array>
#include <cmath>
#include <iostream>
#include <random>
#include <span>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"
#include "exact_distance.hpp"
#include "reference/turning_gap.hpp"

namespace batchccd {
namespace {

using testing::Label;
using testing::Rational;

constexpr Mode kCertified[] = {Mode::conservative, Mode::exact};
constexpr int kSamples = 256;

Options with(Mode mode, double min_distance) {
  Options options;
  options.mode = mode;
  options.min_distance = min_distance;
  return options;
}

// On a grid of 2^-12, so that the exact distances stay cheap.
Vec3 on_grid(const Vec3& p) {
  return Vec3(std::round(p.x() * 4096) / 4096, std::round(p.y() * 4096) / 4096, std::round(p.z() * 4096) / 4096);
}

// p turned by `angle` about the axis through `centre` along unit `axis`.
Vec3 turned(const Vec3& p, const Vec3& centre, const Vec3& axis, double angle) {
  const Vec3 r = p - centre;
  return centre + r * std::cos(angle) + axis.cross(r) * std::sin(angle) + axis * axis.dot(r) * (1 - std::cos(angle));
}

// A query whose turning primitive (VF the triangle, EE the second edge)
// turns by up to two radians about an axis through a point near the
// origin, while the other (VF the vertex, EE the first edge) starts above
// it and drifts down across the separation, or nearly.
Query turning_query(Kind kind, std::mt19937_64& random, double separation, bool passing) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto random_vector = [&] { return Vec3(unit(random), unit(random), unit(random)); };
  Vec3 axis = random_vector();
  axis.normalize();
  const double angle = 2 * unit(random);
  const Vec3 centre = 0.1 * random_vector();
  // In the plane z = 0 at t0, both over the origin's neighbourhood: the
  // triangle's corners around it, the edges crossing near it.
  const bool vertex_face = kind == Kind::vertex_face;
  std::vector<Vec3> turning, upper;
  for (int k = 0; k < (vertex_face ? 3 : 2); ++k) {
    const double direction = (vertex_face ? 2.1 * k : 3.1 * k) + 0.3 * unit(random);
    turning.push_back(Vec3(std::cos(direction), std::sin(direction), 0) * (0.7 + 0.3 * unit(random)));
  }
  if (vertex_face) {
    upper.push_back(0.2 * Vec3(unit(random), unit(random), 0));
  } else {
    const Vec3 across = Vec3(-turning[0].y(), turning[0].x(), 0);  // at right angles to edge b
    for (int k = 0; k < 2; ++k) upper.push_back(across * (k == 0 ? 1 : -1) + 0.2 * Vec3(unit(random), unit(random), 0));
  }
  // The other primitive: over the turning one, from a height of a few
  // separations down to about the separation (it touches or nearly).
  const double start = separation * (2 + 3 * (unit(random) + 1)), end = separation * (0.6 + 0.5 * unit(random));
  // Half of them pass by: moved sideways by up to the primitives' size at
  // t1, where the turned plane may lie far from them.
  const Vec3 aside = passing ? Vec3(0.8 * Vec3(unit(random), unit(random), 0)) : Vec3(Vec3::Zero());
  std::vector<Vec3> t0, t1;
  const auto add_upper = [&] {
    for (const Vec3& p : upper) {
      t0.push_back(on_grid(p + Vec3(0, 0, start)));
      // Beside where the turning one's plane went, at the height `end`
      // over the turned plane's point below it.
      const Vec3 below = turned(p + aside, centre, axis, angle);
      t1.push_back(on_grid(below + turned(Vec3(0, 0, end), Vec3::Zero(), axis, angle)));
    }
  };
  const auto add_turning = [&] {
    for (const Vec3& p : turning) {
      t0.push_back(on_grid(p));
      t1.push_back(on_grid(turned(p, centre, axis, angle)));
    }
  };
  add_upper();  // VF: the vertex first; EE: edge a first
  add_turning();
  return make_query(kind, t0, t1);
}

TEST(TurningPrimitives, AgreeWithExactDistancesAtSampledTimes) {
  std::mt19937_64 random(20261127);
  const double separation = 0x1p-6;
  const Rational separation2 = Rational(separation) * Rational(separation);
  int sampled_hits = 0, labelled_misses = 0;
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (int n = 0; n < 200; ++n) {
      const Query q = turning_query(kind, random, separation, n % 2 == 1);
      int first_sample = -1;
      for (int k = 0; k <= kSamples && first_sample < 0; ++k)
        if (testing::squared_distance_at(kind, q, Rational(k, kSamples)) <= separation2) first_sample = k;
      const Label label = first_sample >= 0 ? Label::hit : testing::label(kind, q, separation).label;
      sampled_hits += first_sample >= 0;
      labelled_misses += label == Label::miss;
      for (const Mode mode : kCertified) {
        SCOPED_TRACE(::testing::Message() << to_string(kind) << " " << n << " " << to_string(mode));
        const QueryResult result = query_ccd(kind, q, with(mode, separation));
        if (first_sample >= 0) {
          EXPECT_TRUE(result.hit);
          EXPECT_LE(result.toi, static_cast<double>(first_sample) / kSamples);
        }
        if (label == Label::miss && mode == Mode::exact) {
          EXPECT_FALSE(result.hit);
        }
      }
    }
  std::cout << "sampled hits " << sampled_hits << ", labelled misses " << labelled_misses << " of 400\n";
  // Both kinds of answer are well represented.
  EXPECT_GT(sampled_hits, 200);
  EXPECT_GT(labelled_misses, 50);
}

// A triangle that turns a quarter turn about z while it widens and narrows:
// a sliver standing in the plane y = 0 at t0 and in x = 0 at t1, wide and
// flat (z = 0) at t = 1/2. Its normal n(t), quadratic, is `sliver` long at
// both ends and about `stretch` / 2 at t = 1/2: the middle Bernstein control
// point (about `stretch` long) bounds it there, the end ones would not. The
// triangle's corners in the order `order`, the vertex moving from `start`
// to `end`.
Query widening_sliver(double sliver, double stretch, const Vec3& start, const Vec3& end,
                      const std::array<int, 3>& order = {0, 1, 2}) {
  const std::array<Vec3, 3> corners_start = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, -sliver)};
  const std::array<Vec3, 3> corners_end = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1 + 2 * stretch, sliver)};
  return make_query(
      Kind::vertex_face,
      std::vector<Vec3>{start, corners_start[order[0]], corners_start[order[1]], corners_start[order[2]]},
      std::vector<Vec3>{end, corners_end[order[0]], corners_end[order[1]], corners_end[order[2]]});
}

// The filters off: the solver's own plane test and plane step decide.
lab::Settings solver_alone() {
  lab::Settings settings;
  settings.sign_filter = settings.separation_filter = settings.swept_box_filter = false;
  return settings;
}

// The vertex still, `height` over the triangle's interior at t = 1/2, far
// from the sliver planes at the ends: a sign test on the distance to the
// plane that bounded |n| by its end control points alone culls it.
TEST(TurningPrimitives, NormalLargestBetweenItsEndsStillBoundsThePlaneDistance) {
  const double separation = 0x1p-4;
  const Rational separation2 = Rational(separation) * Rational(separation);
  int cases = 0;
  for (const double sliver : {0x1p-10, 0x1p-7})
    for (const double height : {0x1p-5, 0x1p-8})
      for (const std::array<int, 3>& order : {std::array{0, 1, 2}, std::array{1, 2, 0}, std::array{2, 1, 0}}) {
        const Vec3 vertex(0.25, 0.625, height);
        const Query q = widening_sliver(sliver, 1, vertex, vertex, order);
        SCOPED_TRACE(::testing::Message() << "sliver " << sliver << ", height " << height << ", order "
                                          << order[0] << order[1] << order[2]);
        // The geometry as described: apart by more than the separation at
        // both ends, `height` apart at t = 1/2.
        ASSERT_GT(testing::squared_distance_at(Kind::vertex_face, q, 0), separation2);
        ASSERT_GT(testing::squared_distance_at(Kind::vertex_face, q, 1), separation2);
        ASSERT_EQ(testing::squared_distance_at(Kind::vertex_face, q, Rational(1, 2)),
                  Rational(height) * Rational(height));
        for (const Mode mode : kCertified) {
          SCOPED_TRACE(to_string(mode));
          const QueryResult alone = query_ccd(Kind::vertex_face, q, with(mode, separation));
          EXPECT_TRUE(alone.hit);
          EXPECT_LE(alone.toi, 0.5);
          const QueryResult solver = lab::query_ccd(Kind::vertex_face, q, with(mode, separation), solver_alone());
          EXPECT_TRUE(solver.hit);
          EXPECT_LE(solver.toi, 0.5);
          for (const Isa isa : available_isas()) {
            Options options = with(mode, separation);
            options.isa = isa;
            const BatchResult lanes = batch_ccd(Kind::vertex_face, std::span<const Query>(&q, 1), options);
            EXPECT_TRUE(lanes.results.at(0).hit) << to_string(isa);
          }
          ++cases;
        }
      }
  EXPECT_EQ(cases, 24);
}

// The same triangles, the vertex passing by: over their interior at a
// height below the separation at t = 1/2, moving at random. Held to the
// first of 257 sampled times with an exact distance within the separation.
// Exact mode's solver, bounding |n| by its end control points alone in
// the plane test over a whole interval, missed some of these.
TEST(TurningPrimitives, VertexPassingAWideningSliverIsFound) {
  const double separation = 0x1p-4;
  const Rational separation2 = Rational(separation) * Rational(separation);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto draw = [&](double low, double high) { return low + (high - low) * unit(random); };
  constexpr int kQueries = 128;
  for (int n = 0; n < kQueries; ++n) {
    const double sliver = std::ldexp(1.0, -static_cast<int>(draw(4, 12)));
    const double height = separation * draw(0.1, 0.9);
    const double stretch = draw(1, 5);
    const double u = draw(0.1, 0.4), v = draw(0.1, 0.4);
    const double vx = draw(-1, 1), vy = draw(-1, 1), vz = draw(-0.3, 0.3);
    // The corners' midpoints at t = 1/2: x1 (0, 0, 0), x2 (1/2, 1/2, 0), x3 (1/2, stretch + 1/2, 0).
    const Vec3 middle = u * Vec3(0.5, 0.5, 0) + v * Vec3(0.5, stretch + 0.5, 0) + Vec3(0, 0, height);
    const Vec3 velocity(vx, vy, vz);
    const Query q =
        widening_sliver(sliver, stretch, on_grid(middle - 0.5 * velocity), on_grid(middle + 0.5 * velocity));
    int first_sample = -1;
    for (int k = 0; k <= kSamples && first_sample < 0; ++k)
      if (testing::squared_distance_at(Kind::vertex_face, q, Rational(k, kSamples)) <= separation2) first_sample = k;
    SCOPED_TRACE(::testing::Message() << "query " << n << ", sliver " << sliver << ", stretch " << stretch);
    // Near t = 1/2 the vertex is within the separation (on the grid, within 2^-12 of `height` over it).
    ASSERT_GE(first_sample, 0);
    const double witness = static_cast<double>(first_sample) / kSamples;
    for (const Mode mode : kCertified) {
      SCOPED_TRACE(to_string(mode));
      const QueryResult alone = query_ccd(Kind::vertex_face, q, with(mode, separation));
      EXPECT_TRUE(alone.hit);
      EXPECT_LE(alone.toi, witness);
      const QueryResult solver = lab::query_ccd(Kind::vertex_face, q, with(mode, separation), solver_alone());
      EXPECT_TRUE(solver.hit);
      EXPECT_LE(solver.toi, witness);
    }
  }
}

// A vertex beside an edge of a triangle, near one end b of it, while the
// edge turns about b towards the vertex: the closest pair lies on the edge
// and its distance falls at the rate of the edge's points next to the
// vertex, while along any fixed direction the far end c swings towards the
// vertex several times faster (as on rod-twist). Neither the closest
// direction's step nor the plane's follows that (the closest pair is not
// inside the triangle), and both crawl: after a dozen steps the solver
// turns its direction with the closest pair (docs/design.md §11,
// cleared_turning). Half of the vertices come within the separation by
// t1, half stop short of it.
Query vertex_by_turning_edge(std::mt19937_64& random, double separation, bool reaching) {
  std::uniform_real_distribution<double> unit(0, 1);
  const auto draw = [&](double low, double high) { return low + (high - low) * unit(random); };
  // The edge along x from b = 0, the vertex towards +y at `along` of its
  // length (a little off its plane), the third corner towards -y and out
  // of the plane.
  const double along = draw(0.05, 0.2), start = draw(4, 8) * separation;
  const double end = (reaching ? draw(0.3, 0.8) : draw(1.5, 3)) * separation;
  // The edge turns in the x-y plane by the angle that brings its line from
  // `start` to `end` of the vertex: start cos(angle) - along length
  // sin(angle) = end.
  const double length = draw(0.8, 1.2);
  const double angle = std::acos(end / std::hypot(along * length, start)) - std::atan2(along * length, start);
  const Vec3 b(0, 0, 0), c0(length, 0, 0), c1(length * std::cos(angle), length * std::sin(angle), 0);
  const Vec3 a0(draw(0.2, 0.6), -draw(0.5, 1), draw(-0.3, 0.3));
  const Vec3 a1(a0.x() * std::cos(angle) - a0.y() * std::sin(angle), a0.x() * std::sin(angle) + a0.y() * std::cos(angle),
                a0.z());
  const Vec3 vertex(along * length, start, draw(-0.5, 0.5) * separation);
  const Vec3 drift = draw(0, 0.1) * separation * Vec3(draw(-1, 1), 0, draw(-1, 1));
  return make_query(Kind::vertex_face,
                    std::vector<Vec3>{on_grid(vertex), on_grid(a0), on_grid(b), on_grid(c0)},
                    std::vector<Vec3>{on_grid(vertex + drift), on_grid(a1), on_grid(b), on_grid(c1)});
}

TEST(TurningPrimitives, VertexClosingOnATurningEdge) {
  std::mt19937_64 random(29);
  const double separation = 0x1p-6;
  const Rational separation2 = Rational(separation) * Rational(separation);
  int sampled_hits = 0, labelled_misses = 0;
  constexpr int kQueries = 200;
  for (int n = 0; n < kQueries; ++n) {
    const Query q = vertex_by_turning_edge(random, separation, n % 2 == 0);
    int first_sample = -1;
    for (int k = 0; k <= kSamples && first_sample < 0; ++k)
      if (testing::squared_distance_at(Kind::vertex_face, q, Rational(k, kSamples)) <= separation2) first_sample = k;
    const Label label = first_sample >= 0 ? Label::hit : testing::label(Kind::vertex_face, q, separation).label;
    sampled_hits += first_sample >= 0;
    labelled_misses += label == Label::miss;
    for (const Mode mode : kCertified) {
      SCOPED_TRACE(::testing::Message() << "query " << n << " " << to_string(mode));
      const QueryResult result = query_ccd(Kind::vertex_face, q, with(mode, separation));
      if (first_sample >= 0) {
        EXPECT_TRUE(result.hit);
        EXPECT_LE(result.toi, static_cast<double>(first_sample) / kSamples);
      }
      if (label == Label::miss) {
        EXPECT_FALSE(result.hit);
      }
    }
  }
  std::cout << "sampled hits " << sampled_hits << ", labelled misses " << labelled_misses << " of " << kQueries << "\n";
  EXPECT_GT(sampled_hits, kQueries / 4);
  EXPECT_GT(labelled_misses, kQueries / 4);
}

// turning_apart (turning_gap.hpp), the turning step's certificate, alone:
// the positions x2..x4 relative to x1 at the interval's ends (the query
// from them, x1 the origin throughout) and the directions at either end.
using V3 = reference::Vector3<double>;
using Positions = std::array<V3, 3>;

Positions reach_of(const Positions& start, const Positions& end) {
  Positions reach;
  for (int i = 0; i < 3; ++i)
    reach[i] = {std::max(std::fabs(start[i].x), std::fabs(end[i].x)), std::max(std::fabs(start[i].y), std::fabs(end[i].y)),
                std::max(std::fabs(start[i].z), std::fabs(end[i].z))};
  return reach;
}

bool turning_apart(Kind kind, const V3& n0, const Positions& start, const V3& n1, const Positions& end,
                   double min_distance) {
  return reference::turning_apart(kind, n0, start, n1, end, reach_of(start, end), 0, min_distance, true);
}

// The query whose x1 stays at the origin and whose x2..x4 move from `start`
// to `end` (make_query's order: VF p a b c, EE as x1..x4).
Query relative_query(Kind kind, const Positions& start, const Positions& end) {
  const auto points = [&](const Positions& x) {
    const auto vec = [](const V3& v) { return Vec3(v.x, v.y, v.z); };
    return kind == Kind::vertex_face ? std::vector<Vec3>{vec(x[2]), Vec3::Zero(), vec(x[0]), vec(x[1])}
                                     : std::vector<Vec3>{Vec3::Zero(), vec(x[0]), vec(x[1]), vec(x[2])};
  };
  return make_query(kind, points(start), points(end));
}

// A vertex passing straight through a small triangle: apart along +x at the
// start and along -x at the end, but not in between. Only the middle
// coefficient (n0 . D1 + n1 . D0) / 2 says so.
TEST(TurningGap, TheMiddleCoefficientSeesAVertexPassingThrough) {
  const Positions triangle_and_vertex_start{V3{0, 0.1, 0}, V3{0, 0, 0.1}, V3{1, 0.02, 0.02}};
  const Positions triangle_and_vertex_end{V3{0, 0.1, 0}, V3{0, 0, 0.1}, V3{-1, 0.02, 0.02}};
  const Query q = relative_query(Kind::vertex_face, triangle_and_vertex_start, triangle_and_vertex_end);
  ASSERT_EQ(testing::squared_distance_at(Kind::vertex_face, q, Rational(1, 2)), 0);
  EXPECT_FALSE(turning_apart(Kind::vertex_face, V3{1, 0, 0}, triangle_and_vertex_start, V3{-1, 0, 0},
                             triangle_and_vertex_end, 0x1p-6));
  // The same directions over the first half alone (the vertex at x = 0.5
  // at its end) certify it.
  const Positions halfway{V3{0, 0.1, 0}, V3{0, 0, 0.1}, V3{0.5, 0.02, 0.02}};
  EXPECT_TRUE(turning_apart(Kind::vertex_face, V3{1, 0, 0}, triangle_and_vertex_start, V3{1, 0, 0}, halfway, 0x1p-6));
}

// n1 a hundred times n0, both along x: the vertex 1.5 separations from
// the triangle's plane x = 0 at the start and half a separation at the
// end. Every coefficient exceeds the separation times the shorter
// direction; the longer one is what |n(s)| may reach.
TEST(TurningGap, TheThresholdTakesTheLongerDirection) {
  const double separation = 0x1p-6;
  const Positions start{V3{0, 0.5, 0}, V3{0, 0, 0.5}, V3{1.5 * separation, 0.1, 0.1}};
  const Positions end{V3{0, 0.5, 0}, V3{0, 0, 0.5}, V3{0.5 * separation, 0.1, 0.1}};
  const Query q = relative_query(Kind::vertex_face, start, end);
  ASSERT_LT(testing::squared_distance_at(Kind::vertex_face, q, 1), Rational(separation) * Rational(separation));
  EXPECT_FALSE(turning_apart(Kind::vertex_face, V3{1, 0, 0}, start, V3{100, 0, 0}, end, separation));
  EXPECT_FALSE(turning_apart(Kind::vertex_face, V3{100, 0, 0}, start, V3{1, 0, 0}, end, separation));
}

// At random: whatever it certifies is farther apart than the separation at
// every one of 65 sampled times (exact distances), for directions near the
// ones the solver takes (from the second primitive towards the first at
// either end) and for directions at random.
TEST(TurningGap, CertifiedIntervalsAreApartAtEverySample) {
  std::mt19937_64 random(2811);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto on_grid_v3 = [&](double scale) {
    const Vec3 p = on_grid(scale * Vec3(unit(random), unit(random), unit(random)));
    return V3{p.x(), p.y(), p.z()};
  };
  int certified = 0, refused = 0;
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (int n = 0; n < 400; ++n) {
      Positions start, end;
      for (int i = 0; i < 3; ++i) {
        start[i] = on_grid_v3(1);
        const V3 motion = on_grid_v3(0.5);
        end[i] = {start[i].x + motion.x, start[i].y + motion.y, start[i].z + motion.z};
      }
      // Upper minus lower centroid at either end (VF x4 over x1 x2 x3; EE
      // x1 x2 over x3 x4), nudged; every fourth pair at random.
      const auto towards_upper = [&](const Positions& x) {
        V3 d = kind == Kind::vertex_face
                   ? V3{x[2].x - (x[0].x + x[1].x) / 3, x[2].y - (x[0].y + x[1].y) / 3, x[2].z - (x[0].z + x[1].z) / 3}
                   : V3{(x[0].x - x[1].x - x[2].x) / 2, (x[0].y - x[1].y - x[2].y) / 2, (x[0].z - x[1].z - x[2].z) / 2};
        const V3 nudge = on_grid_v3(0.2);
        return V3{d.x + nudge.x, d.y + nudge.y, d.z + nudge.z};
      };
      const bool at_random = n % 4 == 3;
      const V3 n0 = at_random ? on_grid_v3(1) : towards_upper(start), n1 = at_random ? on_grid_v3(1) : towards_upper(end);
      const double separation = 0.1 * (unit(random) + 1);
      const bool apart = turning_apart(kind, n0, start, n1, end, separation);
      (apart ? certified : refused) += 1;
      if (!apart) continue;
      const Query q = relative_query(kind, start, end);
      const Rational separation2 = Rational(separation) * Rational(separation);
      for (int k = 0; k <= 64; ++k) {
        SCOPED_TRACE(::testing::Message() << to_string(kind) << " " << n << " sample " << k);
        EXPECT_GT(testing::squared_distance_at(kind, q, Rational(k, 64)), separation2);
      }
    }
  std::cout << "certified " << certified << ", refused " << refused << " of 800\n";
  EXPECT_GT(certified, 100);
  EXPECT_GT(refused, 100);
}

}  // namespace
}  // namespace batchccd

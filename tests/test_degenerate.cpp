// Hand-made degenerate queries with answers worked out exactly (docs/design.md §1,
// "Degenerate input"). Every coordinate is exact in
// binary, so each expected answer is the exact-arithmetic answer; the
// derivation sits next to each case.
//
// Conservative mode must get every case right: the hit, and for a hit a time
// of impact that is never after the true first contact and within 1e-6 of
// it; exact mode too, within 2^-40. Each derived contact time is checked by
// the exact distance there (tests/exact_distance.hpp). The fast and cubic baselines may miss degenerate contacts; for them only
// sanity is checked (no NaN, toi in [0, 1] on a hit, +inf otherwise), except
// on the clean cases at the end, where all three must agree.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"
#include "exact_distance.hpp"
#include "query_builders.hpp"

namespace {

using batchccd::Kind;
using batchccd::Mode;
using batchccd::Options;
using batchccd::Query;
using batchccd::QueryResult;
using batchccd::Status;
using batchccd::Vec3;
using batchccd::testing::at_rest;
using batchccd::testing::from_points;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// How much earlier than the true first contact a conservative TOI may be.
constexpr double kToiSlack = 1e-6;

Vec3 V(double x, double y, double z) { return Vec3(x, y, z); }

Options with_mode(Mode mode, bool need_toi = true) {
  Options options;
  options.mode = mode;
  options.need_toi = need_toi;
  return options;
}

QueryResult run(Kind kind, const Query& q, const Options& options) {
  const auto& x = q.points;
  if (kind == Kind::vertex_face)
    return batchccd::vertex_face_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], options);
  return batchccd::edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], options);
}

// A mode or a baseline (lab.hpp), through the generic entry point.
QueryResult run(Kind kind, const Query& q, const batchccd::lab::Method& method) {
  return batchccd::lab::query_ccd(kind, q, method.applied_to({}), method.settings());
}

// The result of a mode that promises nothing about correctness must still be
// well formed.
void expect_well_formed(const QueryResult& r) {
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_FALSE(std::isnan(r.toi));
  if (r.hit) {
    EXPECT_GE(r.toi, 0.0);
    EXPECT_LE(r.toi, 1.0);
  } else {
    EXPECT_EQ(r.toi, kInfinity);
  }
}

// true_toi: the exact first contact, or nullopt when the primitives never touch.
// slack: how much earlier than true_toi the reported toi may be.
void check(Kind kind, const Query& q, std::optional<double> true_toi,
           double slack = kToiSlack) {
  const QueryResult r = run(kind, q, with_mode(Mode::conservative));
  EXPECT_EQ(r.status, Status::ok);
  if (true_toi) {
    EXPECT_TRUE(r.hit) << "conservative missed a contact at t = " << *true_toi;
    if (r.hit) {
      EXPECT_GE(r.toi, 0.0);
      EXPECT_LE(r.toi, *true_toi) << "toi after the first contact";
      EXPECT_LE(*true_toi - r.toi, slack) << "toi = " << r.toi;
    }
  } else {
    EXPECT_FALSE(r.hit) << "false positive, toi = " << r.toi;
    EXPECT_EQ(r.toi, kInfinity);
  }
  // Only hit/no-hit asked: the same decision.
  const QueryResult decision = run(kind, q, with_mode(Mode::conservative, false));
  EXPECT_EQ(decision.status, Status::ok);
  EXPECT_EQ(decision.hit, true_toi.has_value());
  if (decision.hit && true_toi) {
    EXPECT_GE(decision.toi, 0.0);
    EXPECT_LE(decision.toi, *true_toi);
  }
  // The generic entry point answers the same.
  const QueryResult generic = batchccd::query_ccd(kind, q, with_mode(Mode::conservative));
  EXPECT_EQ(generic.hit, r.hit);
  EXPECT_EQ(generic.toi, r.toi);
  // Exact mode: exact arithmetic's decision, a TOI less than 2^-40 before
  // the contact (true_toi is the double nearest it: one rounding either way).
  const QueryResult exact = run(kind, q, with_mode(Mode::exact));
  EXPECT_EQ(exact.status, Status::ok);
  EXPECT_EQ(exact.hit, true_toi.has_value()) << "exact mode";
  if (exact.hit && true_toi) {
    EXPECT_LE(exact.toi, std::nextafter(*true_toi, 1.0)) << "exact mode's toi after the first contact";
    EXPECT_LT(*true_toi - exact.toi, 0x1p-40) << "exact mode's toi = " << exact.toi;
  }
  // The derivation itself: at true_toi the primitives touch, by the exact
  // distance there (within what true_toi's rounding moves them).
  if (true_toi) {
    double extent = 0;
    for (const Vec3& a : q.points)
      for (const Vec3& b : q.points) extent = std::max(extent, (a - b).cwiseAbs().maxCoeff());
    const batchccd::testing::Rational reach = 0x1p-45 * extent;
    EXPECT_LE(batchccd::testing::squared_distance_at(kind, q, *true_toi), reach * reach)
        << "the primitives do not touch at t = " << *true_toi;
  }
  // The fast and cubic baselines: no correctness promise on degenerate
  // input, but no garbage.
  {
    SCOPED_TRACE("fast baseline");
    expect_well_formed(run(kind, q, batchccd::lab::kFast));
  }
  {
    SCOPED_TRACE("cubic baseline");
    expect_well_formed(run(kind, q, batchccd::lab::kCubic));
  }
}

void check_vf(const Query& q, std::optional<double> true_toi, double slack = kToiSlack) {
  check(Kind::vertex_face, q, true_toi, slack);
}
void check_ee(const Query& q, std::optional<double> true_toi, double slack = kToiSlack) {
  check(Kind::edge_edge, q, true_toi, slack);
}

const std::optional<double> kMiss = std::nullopt;

// The triangle most VF cases use: the right triangle x, y >= 0, x + y <= 4 in
// the plane z = 0.
const Vec3 A = V(0, 0, 0), B = V(4, 0, 0), C = V(0, 4, 0);

// ---------------------------------------------------------------------------
// Coplanar motion: d(t) == 0 for all t, a 2-D problem.

TEST(DegenerateVertexFace, CoplanarVertexSlidesIntoTriangle) {
  // p(t) = (-2 + 4t, 1, 0) reaches the edge x = 0 (edge ca) at t = 1/2.
  check_vf(from_points(V(-2, 1, 0), A, B, C, V(2, 1, 0), A, B, C), 0.5);
}

TEST(DegenerateVertexFace, CoplanarVertexSlidesPastTriangle) {
  // p(t) = (-2 + 8t, 5, 0): the line y = 5 stays 1 above the apex c = (0, 4).
  check_vf(from_points(V(-2, 5, 0), A, B, C, V(6, 5, 0), A, B, C), kMiss);
}

TEST(DegenerateVertexFace, CoplanarVertexSlidesAlongOutsideOfHypotenuse) {
  // p(t) = (5 - 4t, 4t, 0): x + y = 5 throughout, parallel to edge bc at
  // distance 1/sqrt(2).
  check_vf(from_points(V(5, 0, 0), A, B, C, V(1, 4, 0), A, B, C), kMiss);
}

TEST(DegenerateVertexFace, CoplanarTriangleSlidesOntoStaticVertex) {
  // The triangle translates by (4, 0, 0); the vertex (5, 1, 0) is reached by
  // the hypotenuse x + y = 4 + 4t when 6 = 4 + 4t, t = 1/2.
  check_vf(from_points(V(5, 1, 0), A, B, C, V(5, 1, 0), V(4, 0, 0), V(8, 0, 0), V(4, 4, 0)), 0.5);
}

TEST(DegenerateEdgeEdge, CoplanarEdgesSlideIntoCrossing) {
  // Edge b = (1, -2)-(3, -1) moves by (0, 4) in z = 0; its endpoint (3, -1 + 4t)
  // reaches edge a (the segment [0, 4] of the x axis) at t = 1/4.
  check_ee(from_points(A, B, V(1, -2, 0), V(3, -1, 0), A, B, V(1, 2, 0), V(3, 3, 0)), 0.25);
}

TEST(DegenerateEdgeEdge, CoplanarEdgesSlidePastEachOther) {
  // The same motion 4 units further along x: edge b stays at x >= 5, 1 away
  // from edge a's end (4, 0, 0).
  check_ee(from_points(A, B, V(5, -2, 0), V(6, -1, 0), A, B, V(5, 2, 0), V(6, 3, 0)), kMiss);
}

TEST(DegenerateEdgeEdge, CollinearEdgesSlideIntoOverlap) {
  // Edge a = [0, 1] on the x axis, edge b = [2 - 4t, 3 - 4t] on the same line:
  // they touch when 2 - 4t = 1, t = 1/4.
  check_ee(from_points(A, V(1, 0, 0), V(2, 0, 0), V(3, 0, 0), A, V(1, 0, 0), V(-2, 0, 0), V(-1, 0, 0)),
           0.25);
}

// ---------------------------------------------------------------------------
// a3 = 0: the coplanarity cubic has lower degree.

TEST(DegenerateVertexFace, LinearCubicStaticTriangle) {
  // Static triangle, vertex falling straight down: d is linear. z = 1 - 2t = 0
  // at t = 1/2, at (1, 1) inside.
  check_vf(from_points(V(1, 1, 1), A, B, C, V(1, 1, -1), A, B, C), 0.5);
}

TEST(DegenerateVertexFace, LinearCubicTiltingTriangle) {
  // c(t) = (0, 4, 4t - 2): the plane is z = (t - 1/2) y. p(t) = (1, 1, 1 - t):
  // 1 - t = t - 1/2 at t = 3/4, where p = (1, 1, 1/4) projects inside.
  // a3 = a2 = 0 (only c and p move, and only along z).
  check_vf(from_points(V(1, 1, 1), A, B, V(0, 4, -2), V(1, 1, 0), A, B, V(0, 4, 2)), 0.75);
}

TEST(DegenerateVertexFace, QuadraticCubicFirstRootOutsideSecondInside) {
  // Plane z = (t - 1/2) y as above, p(t) = (1, 6 - 8t, 4t - 2).
  // pz - (t - 1/2) py = 8 (t - 1/4)(t - 1/2): coplanar at t = 1/4, where
  // p = (1, 4, -1) projects to x + y = 5 > 4 (outside), and at t = 1/2, where
  // p = (1, 2, 0) is inside. First contact t = 1/2; a3 = 0 (a, b static).
  check_vf(from_points(V(1, 6, -2), A, B, V(0, 4, -2), V(1, -2, 2), A, B, V(0, 4, 2)), 0.5);
}

TEST(DegenerateEdgeEdge, LinearCubicTranslatingEdge) {
  // Edge a static on the x axis; edge b = (2, -1 .. 1, 1 - 2t) translates down
  // and crosses it at (2, 0, 0) at t = 1/2. a3 = a2 = 0.
  check_ee(from_points(A, B, V(2, -1, 1), V(2, 1, 1), A, B, V(2, -1, -1), V(2, 1, -1)), 0.5);
}

TEST(DegenerateEdgeEdge, QuadraticCubicFirstRootApartSecondCrossing) {
  // Edge a = (4, 0, 0)-(0, 4, 4t - 2), edge b = (6, 0, 0)-(1, 6 - 8t, 4t - 2):
  // all four points lie in the plane z = (t - 1/2) y exactly when
  // 8 (t - 1/4)(t - 1/2) = 0. At t = 1/4 (in-plane coordinates x, y) edge b
  // runs from (6, 0) to (1, 4), where x + y >= 5, beside edge a on x + y = 4:
  // no contact. At t = 1/2 edge b = (6, 0)-(1, 2) crosses x + y = 4 at
  // (8/3, 4/3), inside edge a. a3 = 0 (a0, b0 static).
  check_ee(from_points(B, V(0, 4, -2), V(6, 0, 0), V(1, 6, -2), B, V(0, 4, 2), V(6, 0, 0), V(1, -2, 2)),
           0.5);
}

// ---------------------------------------------------------------------------
// Double roots: tangential contact, d(t) = k (t - 1/2)^2.

TEST(DegenerateVertexFace, DoubleRootGrazingInsideFace) {
  // c(t) = (0, 4, 4t - 2): plane z = (t - 1/2) y. p(t) = (1, 2t, t - 1/2):
  // pz - (t - 1/2) py = -2 (t - 1/2)^2 <= 0, zero only at t = 1/2, where
  // p = (1, 1, 0) is inside the triangle (0,0,0), (4,0,0), (0,4,0).
  check_vf(from_points(V(1, 0, -0.5), A, B, V(0, 4, -2), V(1, 2, 0.5), A, B, V(0, 4, 2)), 0.5);
}

TEST(DegenerateVertexFace, DoubleRootGrazingOutsideFace) {
  // The same motion shifted to x = 5: at t = 1/2 p = (5, 1, 0), x + y = 6 > 4,
  // sqrt(2) from the hypotenuse; never coplanar otherwise.
  check_vf(from_points(V(5, 0, -0.5), A, B, V(0, 4, -2), V(5, 2, 0.5), A, B, V(0, 4, 2)), kMiss);
}

TEST(DegenerateEdgeEdge, DoubleRootGrazingCrossing) {
  // Edge a = (0,0,0)-(0, 4, 4t - 2), edge b = (4,0,0)-(-4, 2t, t - 1/2).
  // d(t) = 8 (2t - 1)^2; at t = 1/2 edge b = (4,0,0)-(-4,1,0) crosses x = 0 at
  // y = 1/2, inside edge a = (0,0,0)-(0,4,0).
  check_ee(from_points(A, V(0, 4, -2), B, V(-4, 0, -0.5), A, V(0, 4, 2), B, V(-4, 2, 0.5)), 0.5);
}

TEST(DegenerateEdgeEdge, DoubleRootGrazingApart) {
  // Edge a = (0, 2, 2t - 1)-(0, 4, 4t - 2) (in the same tilting plane), edge b
  // as above: d(t) = 4 (2t - 1)^2. At t = 1/2 edge b crosses x = 0 at y = 1/2,
  // 3/2 short of edge a = y in [2, 4].
  check_ee(from_points(V(0, 2, -1), V(0, 4, -2), B, V(-4, 0, -0.5), V(0, 2, 1), V(0, 4, 2), B,
                V(-4, 2, 0.5)),
           kMiss);
}

// Triple roots: with s = 2t - 1, B = b - a = (s, 1, 0), C = c - a = (0, s, 1)
// and D = p - a = lambda B + mu C + (0, 0, s), d(t) = det(B, C, D) = s^3. At
// t = 1/2, b = (0, 1, 0), c = (0, 0, 1) and D = (0, lambda, mu).
//
// Not a clean crossing: the distance to contact is about 8 |t - 1/2|^3, below
// the default tolerance (1e-9 of the query's size ~1.25) for |t - 1/2| up to
// about 5.4e-4. A conservative TOI anywhere in that window is within the
// promise (a contact reported only within `tolerance`), so the slack here is
// 1e-3, not 1e-6; the TOI must still never be after 1/2.
constexpr double kTripleRootSlack = 1e-3;

TEST(DegenerateVertexFace, TripleRootInsideFace) {
  // lambda = mu = 1/4: p(1/2) = (0, 1/4, 1/4), inside.
  const Vec3 origin = V(0, 0, 0);
  check_vf(from_points(V(-0.25, 0, -0.75), origin, V(-1, 1, 0), V(0, -1, 1), V(0.25, 0.5, 1.25), origin,
                V(1, 1, 0), V(0, 1, 1)),
           0.5, kTripleRootSlack);
}

TEST(DegenerateVertexFace, TripleRootOutsideFace) {
  // lambda = mu = 1: p(1/2) = (0, 1, 1), sqrt(1/2) beyond edge bc.
  const Vec3 origin = V(0, 0, 0);
  check_vf(from_points(V(-1, 0, 0), origin, V(-1, 1, 0), V(0, -1, 1), V(1, 2, 2), origin, V(1, 1, 0),
                V(0, 1, 1)),
           kMiss);
}

TEST(DegenerateEdgeEdge, TripleRootCrossing) {
  // Edge a = (0, B), edge b = (C, D) with lambda = 1, mu = -1: at t = 1/2 edge
  // b runs from (0, 0, 1) to (0, 1, -1) and crosses edge a = (0,0,0)-(0,1,0)
  // at (0, 1/2, 0).
  const Vec3 origin = V(0, 0, 0);
  check_ee(from_points(origin, V(-1, 1, 0), V(0, -1, 1), V(-1, 2, -2), origin, V(1, 1, 0), V(0, 1, 1),
                V(1, 0, 0)),
           0.5, kTripleRootSlack);
}

TEST(DegenerateEdgeEdge, TripleRootApart) {
  // lambda = 3, mu = -1: at t = 1/2 edge b = (0,0,1)-(0,3,-1) meets z = 0 at
  // y = 3/2, 1/sqrt(13) from edge a's end (0, 1, 0).
  const Vec3 origin = V(0, 0, 0);
  check_ee(from_points(origin, V(-1, 1, 0), V(0, -1, 1), V(-3, 4, -2), origin, V(1, 1, 0), V(0, 1, 1),
                V(3, 2, 0)),
           kMiss);
}

// ---------------------------------------------------------------------------
// Contact exactly at t = 0 and at t = 1.

TEST(DegenerateVertexFace, ContactAtTimeZero) {
  // The vertex starts on the face and leaves it.
  check_vf(from_points(V(1, 1, 0), A, B, C, V(1, 1, 1), A, B, C), 0.0);
}

TEST(DegenerateVertexFace, ContactAtTimeOne) {
  // The vertex arrives on the face at the end of the step.
  check_vf(from_points(V(1, 1, 1), A, B, C, V(1, 1, 0), A, B, C), 1.0);
}

TEST(DegenerateVertexFace, ContactAtTimeOneOnTriangleCorner) {
  // The vertex arrives exactly at the corner b at t = 1.
  check_vf(from_points(V(4, 0, 2), A, B, C, V(4, 0, 0), A, B, C), 1.0);
}

TEST(DegenerateEdgeEdge, ContactAtTimeZero) {
  check_ee(from_points(A, B, V(2, -1, 0), V(2, 1, 0), A, B, V(2, -1, 1), V(2, 1, 1)), 0.0);
}

TEST(DegenerateEdgeEdge, ContactAtTimeOne) {
  check_ee(from_points(A, B, V(2, -1, 1), V(2, 1, 1), A, B, V(2, -1, 0), V(2, 1, 0)), 1.0);
}

TEST(DegenerateEdgeEdge, ContactAtTimeOneEndpointToEndpoint) {
  // Edge b's endpoint lands exactly on edge a's endpoint (4, 0, 0) at t = 1.
  check_ee(from_points(A, B, V(4, 0, 2), V(4, 2, 2), A, B, V(4, 0, 0), V(4, 2, 0)), 1.0);
}

// ---------------------------------------------------------------------------
// Zero-area triangles.

TEST(DegenerateVertexFace, CollinearTriangleVertexPassesThroughSegment) {
  // Triangle (0,0,0), (4,0,0), (2,0,0) is the segment [0, 4] of the x axis;
  // p(t) = (1, 0, 1 - 2t) crosses it at t = 1/2.
  check_vf(from_points(V(1, 0, 1), A, B, V(2, 0, 0), V(1, 0, -1), A, B, V(2, 0, 0)), 0.5);
}

TEST(DegenerateVertexFace, CollinearTriangleVertexPassesBesideSegment) {
  // p(t) = (1, 1, 1 - 2t): 1 away from the segment at t = 1/2.
  check_vf(from_points(V(1, 1, 1), A, B, V(2, 0, 0), V(1, 1, -1), A, B, V(2, 0, 0)), kMiss);
}

TEST(DegenerateVertexFace, CollinearTriangleVertexPassesBeyondSegmentEnd) {
  // p(t) = (6, 0, 1 - 2t) crosses the segment's line 2 past its end (4, 0, 0).
  check_vf(from_points(V(6, 0, 1), A, B, V(2, 0, 0), V(6, 0, -1), A, B, V(2, 0, 0)), kMiss);
}

TEST(DegenerateVertexFace, CollinearTriangleVertexSlidesAlongLineIntoSegment) {
  // Collinear motion: p(t) = (7 - 8t, 0, 0) reaches the end (4, 0, 0) at
  // t = 3/8.
  check_vf(from_points(V(7, 0, 0), A, B, V(2, 0, 0), V(-1, 0, 0), A, B, V(2, 0, 0)), 0.375);
}

TEST(DegenerateVertexFace, CoincidentTriangleVertexPassesThroughPoint) {
  // a = b = c = (1, 1, 1); p(t) = (1, 1, 2t) passes through it at t = 1/2.
  const Vec3 point = V(1, 1, 1);
  check_vf(from_points(V(1, 1, 0), point, point, point, V(1, 1, 2), point, point, point), 0.5);
}

TEST(DegenerateVertexFace, CoincidentTriangleVertexPassesBesidePoint) {
  // p(t) = (2, 1, 2t): 1 away from the point at t = 1/2.
  const Vec3 point = V(1, 1, 1);
  check_vf(from_points(V(2, 1, 0), point, point, point, V(2, 1, 2), point, point, point), kMiss);
}

TEST(DegenerateVertexFace, TriangleCollapsingToSegmentPassesVertex) {
  // c(t) = (2, 4 - 4t, 0) flattens the triangle onto the x axis at t = 1; the
  // vertex (3, 0.25, 1 - t) sits above the triangle until it lands on z = 0 at
  // t = 1, where the triangle is the segment [0, 4] and p = (3, 0.25, 0) is
  // 1/4 beside it. Before that, at t < 1 the vertex is at height 1 - t > 0.
  check_vf(from_points(V(3, 0.25, 1), A, B, V(2, 4, 0), V(3, 0.25, 0), A, B, V(2, 0, 0)), kMiss);
}

// The same in general position (no axis-aligned shortcut): the contact set
// in the barycentric (u, v) square is then a slanted line.

TEST(DegenerateVertexFace, ZeroAreaTriangleInGeneralPositionVertexCrosses) {
  // a = (0,0,0), b = c = (4,2,1): the segment s (4,2,1), s in [0, 1].
  // p(t) = (1 + 2t, 2 - 2t, -1/2 + 2t) meets it only at t = 1/2, at (2,1,1/2)
  // (s = 1/2): the path is not parallel to the segment, so it meets the
  // segment's line once.
  const Vec3 b = V(4, 2, 1);
  check_vf(from_points(V(1, 2, -0.5), A, b, b, V(3, 0, 1.5), A, b, b), 0.5);
}

TEST(DegenerateVertexFace, CollinearTriangleInGeneralPositionVertexCrosses) {
  // c = 2b: a = (0,0,0), b = (4,2,1), c = (8,4,2) on one line; same vertex path,
  // crossing at (2,1,1/2) at t = 1/2.
  check_vf(from_points(V(1, 2, -0.5), A, V(4, 2, 1), V(8, 4, 2), V(3, 0, 1.5), A, V(4, 2, 1), V(8, 4, 2)),
           0.5);
}

TEST(DegenerateVertexFace, CoplanarVertexCrossesZeroAreaTriangle) {
  // All in z = 0: the segment (0,0)-(4,2) (b = c) lies on y = x / 2;
  // p(t) = (1 + 2t, 2 - 2t) is on that line when 2 - 2t = (1 + 2t) / 2, only
  // at t = 1/2, at (2, 1), the segment's midpoint.
  const Vec3 b = V(4, 2, 0);
  check_vf(from_points(V(1, 2, 0), A, b, b, V(3, 0, 0), A, b, b), 0.5);
}

// ---------------------------------------------------------------------------
// Zero-length edges.

TEST(DegenerateEdgeEdge, PointEdgePassesThroughEdge) {
  // Edge a is the point (2, 0, 1 - 2t); it crosses edge b = [0, 4] x {0} x {0}
  // at t = 1/2.
  check_ee(from_points(V(2, 0, 1), V(2, 0, 1), A, B, V(2, 0, -1), V(2, 0, -1), A, B), 0.5);
}

TEST(DegenerateEdgeEdge, PointEdgeMissesEdge) {
  // The point (2, 1, 1 - 2t) passes 1 beside edge b.
  check_ee(from_points(V(2, 1, 1), V(2, 1, 1), A, B, V(2, 1, -1), V(2, 1, -1), A, B), kMiss);
}

TEST(DegenerateEdgeEdge, PointEdgeHitsEndOfEdge) {
  // The point (4, 0, 1 - 2t) passes exactly through edge b's endpoint.
  check_ee(from_points(A, B, V(4, 0, 1), V(4, 0, 1), A, B, V(4, 0, -1), V(4, 0, -1)), 0.5);
}

TEST(DegenerateEdgeEdge, TwoPointEdgesMeet) {
  // Both edges are points: (1, 1, 1 - 2t) meets (1, 1, 0) at t = 1/2.
  const Vec3 still = V(1, 1, 0);
  check_ee(from_points(V(1, 1, 1), V(1, 1, 1), still, still, V(1, 1, -1), V(1, 1, -1), still, still),
           0.5);
}

TEST(DegenerateEdgeEdge, TwoPointEdgesMiss) {
  // (1, 1, 1 - 2t) passes 1 beside (1, 2, 0).
  const Vec3 still = V(1, 2, 0);
  check_ee(from_points(V(1, 1, 1), V(1, 1, 1), still, still, V(1, 1, -1), V(1, 1, -1), still, still),
           kMiss);
}

// ---------------------------------------------------------------------------
// Parallel edges.

TEST(DegenerateEdgeEdge, ParallelEdgesBecomeCollinearOverlapping) {
  // Edge b = [2, 6] x {0} x {1 - 2t} drops onto edge a = [0, 4] x {0} x {0}:
  // collinear and overlapping on [2, 4] at t = 1/2.
  check_ee(from_points(A, B, V(2, 0, 1), V(6, 0, 1), A, B, V(2, 0, -1), V(6, 0, -1)), 0.5);
}

TEST(DegenerateEdgeEdge, ParallelEdgesInGeneralPositionBecomeCollinear) {
  // Edge a = (0,0,0)-(4,2,1); edge b = (2,1,1/2)-(6,3,3/2) shifted by
  // (1 - 2t)(-1, 1, 1), which has a component across the edges' direction
  // (4,2,1) for t != 1/2: parallel and apart before t = 1/2, collinear and
  // overlapping on (2,1,1/2)-(4,2,1) at t = 1/2.
  check_ee(from_points(A, V(4, 2, 1), V(1, 2, 1.5), V(5, 4, 2.5), A, V(4, 2, 1), V(3, 0, -0.5),
                V(7, 2, 0.5)),
           0.5);
}

TEST(DegenerateEdgeEdge, CoplanarParallelEdgesInGeneralPositionBecomeCollinear) {
  // In z = 0: edge a = (0,0)-(4,2); edge b = (2,1)-(6,3) shifted by
  // (1 - 2t)(-1, 2), perpendicular to (4, 2): apart by sqrt(5) |1 - 2t|,
  // collinear and overlapping on (2,1)-(4,2) at t = 1/2.
  check_ee(from_points(A, V(4, 2, 0), V(1, 3, 0), V(5, 5, 0), A, V(4, 2, 0), V(3, -1, 0), V(7, 1, 0)),
           0.5);
}

TEST(DegenerateEdgeEdge, ParallelEdgesPassOffset) {
  // The same motion 1 aside in y: parallel at distance >= 1 throughout.
  check_ee(from_points(A, B, V(2, 1, 1), V(6, 1, 1), A, B, V(2, 1, -1), V(6, 1, -1)), kMiss);
}

TEST(DegenerateEdgeEdge, ParallelEdgesCollinearButDisjoint) {
  // Edge b = [5, 6] on edge a's line, moving along z: collinear at t = 1/2 but
  // 1 past edge a's end.
  check_ee(from_points(A, B, V(5, 0, 1), V(6, 0, 1), A, B, V(5, 0, -1), V(6, 0, -1)), kMiss);
}

TEST(DegenerateEdgeEdge, ParallelEdgesTouchEndToEnd) {
  // Edge b = [4, 6] lands on the line of edge a = [0, 4]: they share the single
  // point (4, 0, 0) at t = 1/2.
  check_ee(from_points(A, B, V(4, 0, 1), V(6, 0, 1), A, B, V(4, 0, -1), V(6, 0, -1)), 0.5);
}

// ---------------------------------------------------------------------------
// Points that do not move.

TEST(DegenerateVertexFace, StaticTouchingAllTheTime) {
  check_vf(at_rest(V(1, 1, 0), A, B, C), 0.0);
}

TEST(DegenerateVertexFace, StaticVertexOnEdgeAllTheTime) {
  check_vf(at_rest(V(2, 2, 0), A, B, C), 0.0);
}

TEST(DegenerateVertexFace, StaticSeparated) {
  check_vf(at_rest(V(1, 1, 1), A, B, C), kMiss);
}

TEST(DegenerateVertexFace, StaticCoplanarSeparated) {
  check_vf(at_rest(V(3, 3, 0), A, B, C), kMiss);
}

TEST(DegenerateEdgeEdge, StaticCrossingAllTheTime) {
  check_ee(at_rest(A, B, V(2, -1, 0), V(2, 1, 0)), 0.0);
}

TEST(DegenerateEdgeEdge, StaticSeparated) {
  check_ee(at_rest(A, B, V(2, -1, 1), V(2, 1, 1)), kMiss);
}

TEST(DegenerateEdgeEdge, StaticCoplanarSeparated) {
  // Both in z = 0; edge b = (5, -1)-(5, 1) is 1 past edge a's end.
  check_ee(at_rest(A, B, V(5, -1, 0), V(5, 1, 0)), kMiss);
}

TEST(DegenerateVertexFace, AllPointsCoincideAndStayStill) {
  // Everything is the one point (1, 1, 1): touching throughout.
  const Vec3 point = V(1, 1, 1);
  check_vf(at_rest(point, point, point, point), 0.0);
}

TEST(DegenerateEdgeEdge, AllPointsAtOriginThroughout) {
  const Vec3 origin = V(0, 0, 0);
  check_ee(at_rest(origin, origin, origin, origin), 0.0);
}

TEST(DegenerateEdgeEdge, AllPointsCoincideAndMoveTogether) {
  // Four copies of one moving point: in contact throughout.
  const Vec3 from = V(1, 2, 3), to = V(-3, 0.5, 8);
  check_ee(from_points(from, from, from, from, to, to, to, to), 0.0);
}

// ---------------------------------------------------------------------------
// Shared vertices.

TEST(DegenerateEdgeEdge, SharedEndpointTouchesAtStart) {
  // Both edges start at the origin; edge b then moves away to (1,1,1)-(1,5,1).
  check_ee(from_points(A, B, A, V(0, 4, 0), A, B, V(1, 1, 1), V(1, 5, 1)), 0.0);
}

TEST(DegenerateEdgeEdge, SharedEndpointThroughout) {
  // Mesh neighbours: the edges share the endpoint (0,0,0) for all t.
  check_ee(from_points(A, B, A, V(0, 4, 1), A, V(4, 1, 0), A, V(1, 4, 0)), 0.0);
}

TEST(DegenerateEdgeEdge, SharedEndpointAtEndOnly) {
  // Edge b's first endpoint runs from (2, 2, 2) into edge a's endpoint (0,0,0)
  // at t = 1; edge b stays in x >= 0, y >= 0, z >= 0 away from edge a before:
  // b0(t) = (2 - 2t, 2 - 2t, 2 - 2t), b1 = (2, 4, 2) fixed; edge a is [0, 4] on
  // the x axis. Points of edge b have y >= 2 - 2t > 0 for t < 1.
  check_ee(from_points(A, B, V(2, 2, 2), V(2, 4, 2), A, B, A, V(2, 4, 2)), 1.0);
}

TEST(DegenerateVertexFace, VertexIsTriangleCorner) {
  // p is the corner a itself, moving with it.
  check_vf(from_points(A, A, B, C, V(1, 1, 1), V(1, 1, 1), V(5, 1, 0), V(0, 4, 3)), 0.0);
}

TEST(DegenerateVertexFace, VertexStartsAtCornerAndLeaves) {
  // p starts at corner b and moves straight up while the triangle stays.
  check_vf(from_points(B, A, B, C, V(4, 0, 1), A, B, C), 0.0);
}

// ---------------------------------------------------------------------------
// Near misses and exact touches.

TEST(DegenerateVertexFace, NearMissBesideAxisAlignedEdge) {
  // p(t) = (2, -1.25 * 2^-10, 1 - 2t) crosses z = 0 about 1.2e-3 beside edge ab.
  const double y = -0x1.4p-10;
  check_vf(from_points(V(2, y, 1), A, B, C, V(2, y, -1), A, B, C), kMiss);
}

TEST(DegenerateVertexFace, NearMissBesideDiagonalEdge) {
  // p crosses z = 0 at (2 + 2^-10, 2 + 2^-10), 2^-10 sqrt(2) ~ 1.4e-3 beyond
  // the hypotenuse x + y = 4.
  const double x = 2 + 0x1p-10;
  check_vf(from_points(V(x, x, 1), A, B, C, V(x, x, -1), A, B, C), kMiss);
}

TEST(DegenerateVertexFace, NearMissBesideCorner) {
  // p passes 1.25 * 2^-10 ~ 1.2e-3 beyond corner c = (0, 4, 0) along the y axis.
  const double y = 4 + 0x1.4p-10;
  check_vf(from_points(V(0, y, 1), A, B, C, V(0, y, -1), A, B, C), kMiss);
}

TEST(DegenerateVertexFace, ExactlyThroughDiagonalEdge) {
  // p(t) = (2, 2, 1 - 2t) crosses the hypotenuse at its midpoint at t = 1/2.
  check_vf(from_points(V(2, 2, 1), A, B, C, V(2, 2, -1), A, B, C), 0.5);
}

TEST(DegenerateVertexFace, ExactlyThroughAxisAlignedEdge) {
  check_vf(from_points(V(1, 0, 1), A, B, C, V(1, 0, -1), A, B, C), 0.5);
}

TEST(DegenerateVertexFace, ExactlyThroughCorner) {
  check_vf(from_points(V(0, 4, 1), A, B, C, V(0, 4, -1), A, B, C), 0.5);
}

TEST(DegenerateVertexFace, ExactlyThroughEdgeAtQuarterTime) {
  // p(t) = (0.75, 3.25, 1 - 4t) reaches z = 0 at t = 1/4, on x + y = 4.
  check_vf(from_points(V(0.75, 3.25, 1), A, B, C, V(0.75, 3.25, -3), A, B, C), 0.25);
}

TEST(DegenerateEdgeEdge, NearMissBesideEndpoint) {
  // Edge b = (4 + 1.25 * 2^-10, -1 .. 1, 1 - 2t) passes about 1.2e-3 beyond
  // edge a's end.
  const double x = 4 + 0x1.4p-10;
  check_ee(from_points(A, B, V(x, -1, 1), V(x, 1, 1), A, B, V(x, -1, -1), V(x, 1, -1)), kMiss);
}

TEST(DegenerateEdgeEdge, NearMissAbove) {
  // Crossing edges, edge b stops 1.25 * 2^-10 ~ 1.2e-3 above edge a at t = 1.
  const double z = 0x1.4p-10;
  check_ee(from_points(A, B, V(2, -1, 1), V(2, 1, 1), A, B, V(2, -1, z), V(2, 1, z)), kMiss);
}

TEST(DegenerateEdgeEdge, ExactlyThroughEndpoint) {
  // Edge b = (4, -1 .. 1, 1 - 2t) passes exactly through edge a's end (4,0,0).
  check_ee(from_points(A, B, V(4, -1, 1), V(4, 1, 1), A, B, V(4, -1, -1), V(4, 1, -1)), 0.5);
}

TEST(DegenerateEdgeEdge, EndpointToEndpointMidStep) {
  // Edge b = (4, 0 .. 2, 1 - 2t): its endpoint (4, 0, 1 - 2t) meets edge a's
  // endpoint (4, 0, 0) at t = 1/2.
  check_ee(from_points(A, B, V(4, 0, 1), V(4, 2, 1), A, B, V(4, 0, -1), V(4, 2, -1)), 0.5);
}

// ---------------------------------------------------------------------------
// Clean, well-conditioned cases: every mode must give the right answer.

void check_all_modes_agree(Kind kind, const Query& q, std::optional<double> true_toi,
                           double toi_tolerance) {
  namespace lab = batchccd::lab;
  for (const lab::Method& method : {lab::kConservative, lab::kFast, lab::kCubic}) {
    SCOPED_TRACE(lab::to_string(method));
    const QueryResult r = run(kind, q, method);
    EXPECT_EQ(r.status, Status::ok);
    EXPECT_EQ(r.hit, true_toi.has_value());
    if (r.hit && true_toi) {
      EXPECT_NEAR(r.toi, *true_toi, toi_tolerance);
    }
    if (!r.hit) {
      EXPECT_EQ(r.toi, kInfinity);
    }
  }
}

TEST(DegenerateAllModes, VertexFallsThroughMiddleOfTriangle) {
  check_all_modes_agree(Kind::vertex_face, from_points(V(1, 1, 1), A, B, C, V(1, 1, -1), A, B, C), 0.5,
                        1e-6);
}

TEST(DegenerateAllModes, VertexFallsThroughMovingTriangle) {
  // The triangle rises by 1 while the vertex falls by 3 from height 2:
  // relative height 2 - 4t, zero at t = 1/2, at (1, 1.5) inside.
  check_all_modes_agree(Kind::vertex_face,
                        from_points(V(1, 1.5, 2), A, B, C, V(1, 1.5, -1), V(0, 0, 1), V(4, 0, 1),
                             V(0, 4, 1)),
                        0.5, 1e-6);
}

TEST(DegenerateAllModes, VertexFallsBesideTriangle) {
  check_all_modes_agree(Kind::vertex_face, from_points(V(3, 3, 1), A, B, C, V(3, 3, -1), A, B, C), kMiss,
                        0);
}

TEST(DegenerateAllModes, EdgesCrossCleanly) {
  // Edge b = (1, -1 .. 1, 0.75 - t) (diagonal in x) crosses edge a at t = 3/4.
  check_all_modes_agree(Kind::edge_edge,
                        from_points(A, B, V(1, -1, 0.75), V(3, 1, 0.75), A, B, V(1, -1, -0.25),
                             V(3, 1, -0.25)),
                        0.75, 1e-6);
}

TEST(DegenerateAllModes, EdgesPassApart) {
  check_all_modes_agree(Kind::edge_edge,
                        from_points(A, B, V(6, -1, 1), V(6, 1, 1), A, B, V(6, -1, -1), V(6, 1, -1)), kMiss,
                        0);
}

}  // namespace

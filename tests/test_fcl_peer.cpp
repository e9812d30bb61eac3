// The FCL peer (bench/peers/fcl_peer.hpp): clean crossings and clear misses
// with exactly known contact times, so a wrong point order or a lost toi
// shows. Skips when the build has no FCL.
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "peers/fcl_peer.hpp"

namespace {

using batchccd::Kind;
using batchccd::Query;
using batchccd::Vec3;
using batchccd::peers::fcl_available;
using batchccd::peers::fcl_ccd;
using batchccd::peers::PeerResult;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// FCL's interval Newton stops at a bracket narrower than 1e-7 and reports
// its middle.
constexpr double kFclToiSlack = 1e-6;

// Vertex (1/4, 1/4) falls from z = 1 to z = -1 through the static unit
// triangle in z = 0: contact at t = 1/2. With the vertex and a triangle
// corner swapped, nothing would ever be coplanar inside the triangle.
Query falling_vertex() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return {{Vec3(0.25, 0.25, 1), a, b, c, Vec3(0.25, 0.25, -1), a, b, c}};
}

// The same fall half a unit beside the triangle's edge x = 0: the vertex
// crosses the triangle's plane but never comes nearer than 0.5.
Query passing_vertex() {
  Query query = falling_vertex();
  query.points[0].x() = query.points[4].x() = -0.5;
  return query;
}

// Edge a along x falls from z = 1 to z = -1 across the static edge b along
// y in z = 0: contact at t = 1/2.
Query crossing_edges(double edge_a_y = 0) {
  const Vec3 b0(0, -1, 0), b1(0, 1, 0);
  return {{Vec3(-1, edge_a_y, 1), Vec3(1, edge_a_y, 1), b0, b1, Vec3(-1, edge_a_y, -1),
           Vec3(1, edge_a_y, -1), b0, b1}};
}

// The same fall at y = 2: the lines meet at t = 1/2, but a unit beyond edge
// b's end, so the edges never come nearer than 1.
Query passing_edges() { return crossing_edges(2); }

TEST(FclPeer, VertexThroughTriangleHitsAtKnownToi) {
  if (!fcl_available()) GTEST_SKIP() << "built without FCL";
  const PeerResult result = fcl_ccd(Kind::vertex_face, falling_vertex());
  ASSERT_TRUE(result.hit);
  EXPECT_NEAR(result.toi, 0.5, kFclToiSlack);
}

TEST(FclPeer, VertexBesideTriangleMisses) {
  if (!fcl_available()) GTEST_SKIP() << "built without FCL";
  const PeerResult result = fcl_ccd(Kind::vertex_face, passing_vertex());
  EXPECT_FALSE(result.hit);
  EXPECT_EQ(result.toi, kInfinity);
}

TEST(FclPeer, CrossingEdgesHitAtKnownToi) {
  if (!fcl_available()) GTEST_SKIP() << "built without FCL";
  const PeerResult result = fcl_ccd(Kind::edge_edge, crossing_edges());
  ASSERT_TRUE(result.hit);
  EXPECT_NEAR(result.toi, 0.5, kFclToiSlack);
}

TEST(FclPeer, PassingEdgesMiss) {
  if (!fcl_available()) GTEST_SKIP() << "built without FCL";
  const PeerResult result = fcl_ccd(Kind::edge_edge, passing_edges());
  EXPECT_FALSE(result.hit);
  EXPECT_EQ(result.toi, kInfinity);
}

TEST(FclPeer, ThrowsWithoutFcl) {
  if (fcl_available())
    GTEST_SKIP() << "expected skip: this build has FCL, and the test checks the throw of a build without it";
  EXPECT_THROW(fcl_ccd(Kind::vertex_face, falling_vertex()), std::logic_error);
}

}  // namespace

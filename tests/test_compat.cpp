// The Tight-Inclusion/ipc-toolkit shaped calls (compat.hpp), the mesh call
// with an edges matrix (mesh_edges.hpp) and the version macros. Every
// coordinate is exact in binary, so each expected contact time is exact.
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"

namespace {

using batchccd::Vec3;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// How much earlier than the true first contact a conservative TOI may be.
constexpr double kToiSlack = 1e-6;

// Eight points in the order of the calls: four at t0, then the same four at t1.
using Points = std::array<Vec3, 8>;

// Vertex (1/4, 1/4) falls from z = 1 to z = -1 through the static unit
// triangle in z = 0: contact at t = 1/2 exactly.
Points falling_vertex(double scale = 1.0) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Points x = {Vec3(0.25, 0.25, 1), a, b, c, Vec3(0.25, 0.25, -1), a, b, c};
  for (Vec3& point : x) point *= scale;
  return x;
}

// The same fall, but the vertex passes `gap` beside the triangle's edge x = 0.
Points passing_vertex(double gap) {
  Points x = falling_vertex();
  x[0].x() = x[4].x() = -gap;
  return x;
}

// Edge a along x falls from z = 1 to z = -1 across the static edge b along
// y in z = 0: contact at t = 1/2 exactly.
Points crossing_edges() {
  const Vec3 b0(0, -1, 0), b1(0, 1, 0);
  return {Vec3(-1, 0, 1), Vec3(1, 0, 1), b0, b1, Vec3(-1, 0, -1), Vec3(1, 0, -1), b0, b1};
}

bool vertex_face(const Points& x, double& toi, double tmax = 1.0,
                 double tolerance = batchccd::compat::default_tolerance,
                 std::int64_t max_iterations = batchccd::compat::default_max_iterations) {
  return batchccd::compat::vertex_face_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi,
                                           tmax, tolerance, max_iterations);
}

bool edge_edge(const Points& x, double& toi, double tmax = 1.0) {
  return batchccd::compat::edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi,
                                         tmax);
}

TEST(Compat, VertexFaceContactGivesToi) {
  double toi = -1;
  ASSERT_TRUE(vertex_face(falling_vertex(), toi));
  EXPECT_LE(toi, 0.5);
  EXPECT_GE(toi, 0.5 - kToiSlack);
}

TEST(Compat, EdgeEdgeContactGivesToi) {
  double toi = -1;
  ASSERT_TRUE(edge_edge(crossing_edges(), toi));
  EXPECT_LE(toi, 0.5);
  EXPECT_GE(toi, 0.5 - kToiSlack);
}

TEST(Compat, AgreesWithTheNativeCall) {
  const Points x = falling_vertex();
  const batchccd::QueryResult native =
      batchccd::vertex_face_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7]);
  double toi = -1;
  EXPECT_EQ(vertex_face(x, toi), native.hit);
  EXPECT_NEAR(toi, native.toi, kToiSlack);
}

TEST(Compat, TmaxRestrictsTheStepAndKeepsTheCallersTime) {
  double toi = -1;
  EXPECT_FALSE(vertex_face(falling_vertex(), toi, 0.25));
  EXPECT_EQ(toi, kInfinity);
  EXPECT_FALSE(edge_edge(crossing_edges(), toi, 0.25));
  EXPECT_EQ(toi, kInfinity);

  for (const double tmax : {0.5, 0.75}) {
    toi = -1;
    ASSERT_TRUE(vertex_face(falling_vertex(), toi, tmax)) << tmax;
    EXPECT_LE(toi, 0.5);  // in the caller's time units, not relative to tmax
    EXPECT_GE(toi, 0.5 - kToiSlack);
    toi = -1;
    ASSERT_TRUE(edge_edge(crossing_edges(), toi, tmax)) << tmax;
    EXPECT_LE(toi, 0.5);
    EXPECT_GE(toi, 0.5 - kToiSlack);
  }
}

TEST(Compat, NoContactGivesInfinity) {
  double toi = -1;
  EXPECT_FALSE(vertex_face(passing_vertex(0.5), toi));
  EXPECT_EQ(toi, kInfinity);
}

// The tolerance is a distance in the caller's units: a vertex that passes
// farther from the triangle than the tolerance is never a contact, however
// small the gap is against the query's size.
TEST(Compat, NearMissBeyondTheToleranceIsNoContact) {
  double toi = -1;
  EXPECT_FALSE(vertex_face(passing_vertex(0x1p-30), toi, 1.0, 0x1p-34));
  EXPECT_EQ(toi, kInfinity);
}

// Coordinates and tolerance scaled together (by powers of two, exactly):
// the same decision and the same toi bit for bit.
TEST(Compat, ToleranceScalesWithTheCoordinates) {
  double toi = -1, scaled_toi = -2;
  ASSERT_TRUE(vertex_face(falling_vertex(), toi, 1.0, 1e-6));
  ASSERT_TRUE(vertex_face(falling_vertex(0x1p40), scaled_toi, 1.0, 1e-6 * 0x1p40));
  EXPECT_EQ(toi, scaled_toi);
}

TEST(Compat, IterationBudget) {
  double toi = -1;
  EXPECT_TRUE(vertex_face(falling_vertex(), toi, 1.0, 1e-6, batchccd::compat::no_max_iterations));
  EXPECT_LE(toi, 0.5);
  // An exhausted budget reports a contact, never hides one.
  toi = -1;
  EXPECT_TRUE(vertex_face(falling_vertex(), toi, 1.0, 1e-6, 0));
  EXPECT_LE(toi, 0.5);
}

TEST(Compat, RejectsBadStepAndTolerance) {
  double toi = 0;
  for (const double tmax : {-0.1, 1.5, kNaN, kInfinity})
    EXPECT_THROW(vertex_face(falling_vertex(), toi, tmax), std::invalid_argument) << tmax;
  for (const double tolerance : {0.0, -1e-6, kNaN, kInfinity})
    EXPECT_THROW(vertex_face(falling_vertex(), toi, 1.0, tolerance), std::invalid_argument)
        << tolerance;
}

TEST(Compat, NonFiniteCoordinateIsReportedAsContactAtZero) {
  Points x = falling_vertex();
  x[5].y() = kNaN;
  double toi = -1;
  EXPECT_TRUE(vertex_face(x, toi));
  EXPECT_EQ(toi, 0.0);
}

// Two triangles: (0, 1, 2) still in z = 0, (3, 4, 5) falling through it from
// z = 1 to z = -1, so every crossing happens at t = 1/2.
struct TwoTriangles {
  Eigen::MatrixXd positions_t0 = Eigen::MatrixXd(6, 3), positions_t1;
  Eigen::MatrixXi faces = Eigen::MatrixXi(2, 3), edges = Eigen::MatrixXi(6, 2);
  TwoTriangles() {
    positions_t0 << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, 1, 0.25, -1, 1, -1, 0.25, 1;
    positions_t1 = positions_t0;
    positions_t1.bottomRows(3).col(2).setConstant(-1);
    faces << 0, 1, 2, 3, 4, 5;
    edges << 0, 1, 1, 2, 2, 0, 3, 4, 4, 5, 5, 3;
  }
  batchccd::MeshWithEdgesView view() const {
    return {positions_t0, positions_t1, faces, edges};
  }
};

// Every vertex of one triangle against the other face, every edge pair.
std::vector<std::array<int, 2>> all_vertex_face() {
  return {{3, 0}, {4, 0}, {5, 0}, {0, 1}, {1, 1}, {2, 1}};
}
std::vector<std::array<int, 2>> all_edge_edge() {
  std::vector<std::array<int, 2>> pairs;
  for (int a = 0; a < 3; ++a)
    for (int b = 3; b < 6; ++b) pairs.push_back({a, b});
  return pairs;
}

TEST(MeshEdges, MatchesTheVertexIdCall) {
  const TwoTriangles mesh;
  const auto vertex_face_pairs = all_vertex_face();
  const auto edge_edge_pairs = all_edge_edge();
  const batchccd::BatchResult by_edge_id =
      batchccd::mesh_ccd(mesh.view(), {vertex_face_pairs, edge_edge_pairs});

  batchccd::Candidates by_vertex{vertex_face_pairs, {}};
  for (const auto [a, b] : edge_edge_pairs)
    by_vertex.edge_edge.push_back(
        {mesh.edges(a, 0), mesh.edges(a, 1), mesh.edges(b, 0), mesh.edges(b, 1)});
  const batchccd::BatchResult expected =
      batchccd::mesh_ccd({mesh.positions_t0, mesh.positions_t1, mesh.faces}, by_vertex);

  ASSERT_EQ(by_edge_id.results.size(), vertex_face_pairs.size() + edge_edge_pairs.size());
  ASSERT_EQ(by_edge_id.results.size(), expected.results.size());
  for (std::size_t i = 0; i < expected.results.size(); ++i) {
    EXPECT_EQ(by_edge_id.results[i].hit, expected.results[i].hit) << i;
    EXPECT_EQ(by_edge_id.results[i].toi, expected.results[i].toi) << i;
  }
  EXPECT_EQ(by_edge_id.earliest_toi, expected.earliest_toi);
  EXPECT_EQ(by_edge_id.counters.candidates, expected.counters.candidates);
  EXPECT_EQ(by_edge_id.counters.hits, expected.counters.hits);
  EXPECT_GT(by_edge_id.counters.hits, 0);
  EXPECT_LE(by_edge_id.earliest_toi, 0.5);
  EXPECT_GE(by_edge_id.earliest_toi, 0.5 - kToiSlack);

  // Into an earlier result (here one of another size): the same answers.
  batchccd::BatchResult reused = expected;
  reused.results.resize(1);
  batchccd::mesh_ccd(mesh.view(), {vertex_face_pairs, edge_edge_pairs}, {}, reused);
  ASSERT_EQ(reused.results.size(), by_edge_id.results.size());
  for (std::size_t i = 0; i < reused.results.size(); ++i) {
    EXPECT_EQ(reused.results[i].hit, by_edge_id.results[i].hit) << i;
    EXPECT_EQ(reused.results[i].toi, by_edge_id.results[i].toi) << i;
  }
  EXPECT_EQ(reused.counters.hits, by_edge_id.counters.hits);
}

TEST(MeshEdges, HonoursOptions) {
  const TwoTriangles mesh;
  const auto vertex_face_pairs = all_vertex_face();
  const auto edge_edge_pairs = all_edge_edge();
  batchccd::Options options;
  options.per_candidate_results = false;
  options.vertex_face = false;
  const batchccd::BatchResult result =
      batchccd::mesh_ccd(mesh.view(), {vertex_face_pairs, edge_edge_pairs}, options);
  EXPECT_TRUE(result.results.empty());
  EXPECT_EQ(result.counters.candidates, static_cast<std::int64_t>(edge_edge_pairs.size()));
}

// The message of the std::invalid_argument that `call` throws ("" if none).
template <class Call>
std::string rejection(const Call& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(MeshEdges, RejectsBadEdgeIds) {
  const TwoTriangles mesh;
  const std::vector<std::array<int, 2>> no_pairs;
  for (const std::array<int, 2> pair : {std::array{0, 6}, std::array{-1, 3}}) {
    const std::vector<std::array<int, 2>> pairs = {{0, 3}, pair};
    const std::string message =
        rejection([&] { batchccd::mesh_ccd(mesh.view(), {no_pairs, pairs}); });
    EXPECT_NE(message.find("edge-edge candidate 1: edge " + std::to_string(pair[0] < 0 ? -1 : 6)),
              std::string::npos)
        << message;
  }
}

TEST(MeshEdges, RejectsBadEdgesMatrix) {
  TwoTriangles mesh;
  const std::vector<std::array<int, 2>> no_pairs;
  mesh.edges(2, 1) = 99;
  std::string message = rejection([&] { batchccd::mesh_ccd(mesh.view(), {no_pairs, no_pairs}); });
  EXPECT_NE(message.find("edge 2: vertex 99"), std::string::npos) << message;

  for (const Eigen::Index columns : {0, 1, 3}) {
    mesh.edges = Eigen::MatrixXi::Zero(2, columns);
    message = rejection([&] { batchccd::mesh_ccd(mesh.view(), {no_pairs, no_pairs}); });
    EXPECT_NE(message.find("2 columns"), std::string::npos) << columns << ": " << message;
  }
}

TEST(MeshEdges, RejectsWhatTheVertexIdCallRejects) {
  const TwoTriangles mesh;
  const std::vector<std::array<int, 2>> bad_face = {{0, 2}}, no_pairs;
  EXPECT_THROW(batchccd::mesh_ccd(mesh.view(), {bad_face, no_pairs}), std::invalid_argument);
}

}  // namespace

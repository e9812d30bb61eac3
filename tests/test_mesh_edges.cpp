// The mesh call with an edges matrix (mesh_edges.hpp) and the version macros. Every
// coordinate is exact in binary, so each expected contact time is exact.
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "same_answers.hpp"

namespace {

// How much earlier than the true first contact a conservative TOI may be.
constexpr double kToiSlack = 1e-6;

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
  batchccd::MeshView view() const {
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

  batchccd::Candidates by_vertex{.vertex_face = vertex_face_pairs};
  for (const auto [a, b] : edge_edge_pairs)
    by_vertex.edge_edge.push_back(
        {mesh.edges(a, 0), mesh.edges(a, 1), mesh.edges(b, 0), mesh.edges(b, 1)});
  const batchccd::BatchResult expected =
      batchccd::mesh_ccd({mesh.positions_t0, mesh.positions_t1, mesh.faces}, by_vertex);

  ASSERT_EQ(by_edge_id.results.size(), vertex_face_pairs.size() + edge_edge_pairs.size());
  batchccd::testing::expect_same_answers(by_edge_id, expected);
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
  batchccd::testing::expect_same_answers(reused, by_edge_id);
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

// Point-edge by edge id (ipc-toolkit's edge-vertex candidates) and
// point-point pairs: the same answers as the vertex-id lists.
TEST(MeshEdges, PointKindsByEdgeId) {
  const TwoTriangles mesh;
  std::vector<std::array<int, 2>> vertex_edge, vertex_vertex;
  for (int v = 3; v < 6; ++v)
    for (int e = 0; e < 3; ++e) vertex_edge.push_back({v, e});
  for (int p = 0; p < 3; ++p)
    for (int q = 3; q < 6; ++q) vertex_vertex.push_back({p, q});
  batchccd::Options options;
  options.min_distance = 0.3;  // points pass 0.25 from the fixed triangle's edges
  const batchccd::BatchResult by_edge_id = batchccd::mesh_ccd(
      mesh.view(), batchccd::EdgeIdCandidates{.vertex_edge = vertex_edge, .vertex_vertex = vertex_vertex}, options);

  batchccd::Candidates by_vertex{.vertex_vertex = vertex_vertex};
  for (const auto [v, e] : vertex_edge) by_vertex.vertex_edge.push_back({v, mesh.edges(e, 0), mesh.edges(e, 1)});
  const batchccd::BatchResult expected = batchccd::mesh_ccd(mesh.view(), by_vertex, options);
  ASSERT_EQ(by_edge_id.results.size(), vertex_edge.size() + vertex_vertex.size());
  batchccd::testing::expect_same_answers(by_edge_id, expected);
  EXPECT_GT(expected.counters.hits, 0);
  EXPECT_LT(expected.counters.hits, expected.counters.candidates);
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

TEST(MeshEdges, RejectsBadEdgeIdsOfPointEdgePairs) {
  const TwoTriangles mesh;
  const std::vector<std::array<int, 2>> pairs = {{3, 0}, {4, 6}};
  const std::string message = rejection(
      [&] { batchccd::mesh_ccd(mesh.view(), batchccd::EdgeIdCandidates{.vertex_edge = pairs}); });
  EXPECT_NE(message.find("vertex-edge candidate 1: edge 6"), std::string::npos) << message;
  // Its vertex id is the vertex-id call's to check.
  const std::vector<std::array<int, 2>> bad_vertex = {{7, 0}};
  EXPECT_NE(rejection([&] {
              batchccd::mesh_ccd(mesh.view(), batchccd::EdgeIdCandidates{.vertex_edge = bad_vertex});
            }).find("vertex-edge candidate 0: vertex 7"),
            std::string::npos);
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

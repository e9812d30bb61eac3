// What lies between a mesh and the narrow phase (candidates.hpp) and the
// enums' names (names.hpp).
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"

namespace batchccd {
namespace {

// Two triangles apart in z; the upper one falls through the lower one.
struct FallingTriangle {
  Eigen::MatrixXd t0 = Eigen::MatrixXd(6, 3), t1;
  Eigen::MatrixXi faces = Eigen::MatrixXi(2, 3);
  FallingTriangle() {
    t0 << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, 1, 0.25, -1, 1, -1, 0.25, 1;
    t1 = t0;
    t1.bottomRows(3).col(2).setConstant(-1);
    faces << 0, 1, 2, 3, 4, 5;
  }
  MeshView view() const { return {t0, t1, faces}; }
};

TEST(UniqueEdges, EachUndirectedEdgeOnceSorted) {
  Eigen::MatrixXi faces(3, 3);
  faces << 0, 1, 2,  //
      2, 3, 0,       // shares edge 0-2 with the first
      4, 4, 1;       // repeated vertex: only edge 1-4
  Eigen::MatrixXi expected(6, 2);
  expected << 0, 1, 0, 2, 0, 3, 1, 2, 1, 4, 2, 3;
  EXPECT_EQ(unique_edges(faces), expected);
  const Eigen::MatrixXi no_rows(0, 3), empty;
  EXPECT_EQ(unique_edges(no_rows).rows(), 0);
  EXPECT_EQ(unique_edges(empty).rows(), 0);
  // Any layout: the same faces row-major.
  const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> row_major = faces;
  EXPECT_EQ(unique_edges(row_major), expected);
}

TEST(UniqueEdges, FeedsTheEdgeIdCall) {
  const FallingTriangle mesh;
  const Eigen::MatrixXi edges = unique_edges(mesh.faces);
  ASSERT_EQ(edges.rows(), 6);
  // Edge 3-4 (row 3) crosses edge 0-1 (row 0) going down; edge 0-1 against 1-2 shares a vertex.
  EXPECT_EQ(edges.row(0), Eigen::RowVector2i(0, 1));
  EXPECT_EQ(edges.row(3), Eigen::RowVector2i(3, 4));
  const std::vector<std::array<int, 2>> edge_edge = {{0, 3}}, none;
  const BatchResult result = mesh_ccd({mesh.t0, mesh.t1, mesh.faces, edges}, {none, edge_edge});
  ASSERT_EQ(result.results.size(), 1u);
  EXPECT_TRUE(result.results[0].hit);
}

TEST(UniqueEdges, RefusesMalformedFaces) {
  const Eigen::MatrixXi four_columns = Eigen::MatrixXi::Zero(2, 4);
  EXPECT_THROW(unique_edges(four_columns), std::invalid_argument);
  Eigen::MatrixXi negative(1, 3);
  negative << 0, -1, 2;
  EXPECT_THROW(unique_edges(negative), std::invalid_argument);
}

// The query of a candidate is the one mesh_ccd evaluates: the same answer,
// bit for bit, from the single-query call.
TEST(CandidateQueries, AnswerAsMeshCcdDoes) {
  const FallingTriangle mesh;
  Candidates candidates;
  candidates.vertex_face = {{3, 0}, {4, 0}, {5, 0}, {0, 1}, {1, 1}, {2, 1}};
  for (int a : {0, 1, 2})
    for (int b : {3, 4, 5}) candidates.edge_edge.push_back({a, (a + 1) % 3, b, b == 5 ? 3 : b + 1});
  Options options;
  options.isa = Isa::scalar;
  const BatchResult batch = mesh_ccd(mesh.view(), candidates, options);
  std::size_t i = 0, hits = 0;
  for (const auto& pair : candidates.vertex_face) {
    const QueryResult alone = query_ccd(Kind::vertex_face, vertex_face_query(mesh.view(), pair), options);
    EXPECT_EQ(alone.hit, batch.results[i].hit) << "vf " << i;
    EXPECT_EQ(alone.toi, batch.results[i].toi) << "vf " << i;
    hits += alone.hit;
    ++i;
  }
  for (const auto& quad : candidates.edge_edge) {
    const QueryResult alone = query_ccd(Kind::edge_edge, edge_edge_query(mesh.view(), quad), options);
    EXPECT_EQ(alone.hit, batch.results[i].hit) << "ee " << i;
    EXPECT_EQ(alone.toi, batch.results[i].toi) << "ee " << i;
    hits += alone.hit;
    ++i;
  }
  EXPECT_GT(hits, 0u);  // the comparison saw contacts, not only misses
  const Query q = vertex_face_query(mesh.view(), {3, 0});
  EXPECT_EQ(q.points[0], Vec3(0.25, 0.25, 1));   // the vertex at t0
  EXPECT_EQ(q.points[2], Vec3(1, 0, 0));         // the face's second corner
  EXPECT_EQ(q.points[4], Vec3(0.25, 0.25, -1));  // the vertex at t1
}

TEST(CandidateQueries, RefuseIdsOutsideTheMesh) {
  const FallingTriangle mesh;
  EXPECT_THROW(vertex_face_query(mesh.view(), {6, 0}), std::invalid_argument);
  EXPECT_THROW(vertex_face_query(mesh.view(), {0, 2}), std::invalid_argument);
  EXPECT_THROW(vertex_face_query(mesh.view(), {-1, 0}), std::invalid_argument);
  EXPECT_THROW(edge_edge_query(mesh.view(), {0, 1, 2, 6}), std::invalid_argument);
  try {
    edge_edge_query(mesh.view(), {0, -3, 2, 4});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("-3"), std::string::npos) << error.what();
  }
  Eigen::MatrixXi bad_face(1, 3);
  bad_face << 0, 1, 9;
  const Eigen::MatrixXd shorter = mesh.t1.topRows(5);
  EXPECT_THROW(vertex_face_query({mesh.t0, mesh.t1, bad_face}, {3, 0}), std::invalid_argument);
  EXPECT_THROW(edge_edge_query({mesh.t0, shorter, mesh.faces}, {0, 1, 2, 3}), std::invalid_argument);
}

template <class Enum>
void expect_names_round_trip(std::span<const EnumName<Enum>> table,
                             std::optional<Enum> (*from_string)(std::string_view)) {
  ASSERT_FALSE(table.empty());
  for (const EnumName<Enum>& entry : table) {
    EXPECT_EQ(std::string(to_string(entry.value)), entry.name);
    EXPECT_EQ(from_string(entry.name), entry.value) << entry.name;
  }
  EXPECT_EQ(from_string(""), std::nullopt);
  EXPECT_EQ(from_string(std::string(table.front().name) + " "), std::nullopt);
}

TEST(Names, EveryNameReadsBackAsItsValue) {
  expect_names_round_trip(kind_names(), kind_from_string);
  expect_names_round_trip(mode_names(), mode_from_string);
  expect_names_round_trip(isa_names(), isa_from_string);
  EXPECT_EQ(mode_from_string("Exact"), std::nullopt);  // case matters
  EXPECT_EQ(kind_from_string("vf"), Kind::vertex_face);
  EXPECT_EQ(isa_from_string("auto"), Isa::automatic);
  EXPECT_STREQ(to_string(static_cast<Mode>(99)), "?");
  // The baselines are no modes (lab.hpp names them).
  EXPECT_EQ(mode_from_string("fast"), std::nullopt);
  EXPECT_EQ(mode_from_string("cubic"), std::nullopt);
  EXPECT_STREQ(lab::to_string(lab::kFast), "fast");
  EXPECT_STREQ(lab::to_string(lab::kCubic), "cubic");
  EXPECT_STREQ(lab::to_string(lab::kExact), "exact");
  EXPECT_STREQ(lab::to_string(static_cast<lab::Baseline>(99)), "?");
}

}  // namespace
}  // namespace batchccd

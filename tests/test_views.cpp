// The caller's arrays read in place (views.hpp): every layout of the same
// positions, ids and candidate lists gives the same answers bit for bit,
// and a view cannot be made from a temporary.
#include <gtest/gtest.h>

#include <array>
#include <type_traits>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "broad_phase.hpp"
#include "scenes.hpp"
#include "same_answers.hpp"

namespace batchccd {
namespace {

using RowMajorPositions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMajorIds = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Views take lvalues and views of the caller's memory, never a temporary
// matrix, and no expression without storage.
static_assert(std::is_constructible_v<PositionsView, const Eigen::MatrixXd&>);
static_assert(std::is_constructible_v<PositionsView, const Eigen::MatrixXf&>);
static_assert(std::is_constructible_v<PositionsView, const RowMajorPositions&>);
static_assert(std::is_constructible_v<PositionsView, Eigen::Map<const Eigen::MatrixXd>>);
static_assert(!std::is_constructible_v<PositionsView, Eigen::MatrixXd&&>);
static_assert(!std::is_constructible_v<PositionsView, Eigen::MatrixXf&&>);
static_assert(!std::is_constructible_v<PositionsView, const Eigen::MatrixXi&>);
static_assert(!std::is_constructible_v<IdsView, Eigen::MatrixXi&&>);
static_assert(!std::is_constructible_v<IdsView, const Eigen::MatrixXd&>);
static_assert(std::is_convertible_v<const Candidates&, CandidateLists>);
static_assert(!std::is_convertible_v<Candidates&&, CandidateLists>);

// The cloth scene's step with a dense broad-phase list: hits and near misses.
struct Scene {
  scenes::MovingMesh mesh = scenes::cloth_scene({.resolution = 16, .frames = 100, .frame = 80});
  Candidates candidates = scenes::swept_box_candidates(mesh.view(), 0.02);
};
const Scene& scene() {
  static const Scene s;
  return s;
}

void expect_same(const BatchResult& a, const BatchResult& b) {
  testing::expect_same_answers(a, b);
  EXPECT_EQ(a.earliest_toi, b.earliest_toi);
  EXPECT_EQ(a.counters.hits, b.counters.hits);
}

TEST(Views, EveryLayoutOfThePositionsGivesTheSameAnswers) {
  const Scene& s = scene();
  const BatchResult expected = mesh_ccd(s.mesh.view(), s.candidates);
  ASSERT_GT(expected.counters.hits, 0);
  ASSERT_LT(expected.counters.hits, expected.counters.candidates);

  // Row-major, as NumPy and most simulators keep them.
  const RowMajorPositions t0 = s.mesh.positions_t0, t1 = s.mesh.positions_t1;
  const RowMajorIds faces = s.mesh.faces;
  expect_same(mesh_ccd({t0, t1, faces}, s.candidates), expected);

  // Columns 1..3 of a wider matrix (a block: strides other than its size).
  const Eigen::Index n = s.mesh.positions_t0.rows();
  Eigen::MatrixXd wide0(n, 5), wide1(n, 5);
  wide0.setConstant(1e300);
  wide1.setConstant(-1e300);
  wide0.middleCols(1, 3) = s.mesh.positions_t0;
  wide1.middleCols(1, 3) = s.mesh.positions_t1;
  expect_same(mesh_ccd({wide0.middleCols(1, 3), wide1.middleCols(1, 3), s.mesh.faces}, s.candidates), expected);

  // A raw interleaved buffer (x0 y0 z0 x1 y1 z1 per vertex) through explicit strides.
  std::vector<double> interleaved(static_cast<std::size_t>(6 * n));
  for (Eigen::Index v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) {
      interleaved[static_cast<std::size_t>(6 * v + c)] = s.mesh.positions_t0(v, c);
      interleaved[static_cast<std::size_t>(6 * v + 3 + c)] = s.mesh.positions_t1(v, c);
    }
  const MatrixView<double> at_t0(interleaved.data(), n, 3, 6, 1), at_t1(interleaved.data() + 3, n, 3, 6, 1);
  expect_same(mesh_ccd({at_t0, at_t1, s.mesh.faces}, s.candidates), expected);
}

// Negative strides (rows stored last to first, coordinates z, y, x), an
// Eigen Map with inner and outer strides, and a strided Ref: the same
// answers, faces read the same ways.
TEST(Views, NegativeStridesStridedMapsAndRefsGiveTheSameAnswers) {
  const Scene& s = scene();
  const BatchResult expected = mesh_ccd(s.mesh.view(), s.candidates);
  const Eigen::Index n = s.mesh.positions_t0.rows(), m = s.mesh.faces.rows();

  // Vertex v's z, y, x at storage[3 (n - 1 - v) + 2 - c]: both strides negative.
  std::vector<double> reversed0(static_cast<std::size_t>(3 * n)), reversed1(reversed0.size());
  for (Eigen::Index v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) {
      const auto at = static_cast<std::size_t>(3 * (n - 1 - v) + 2 - c);
      reversed0[at] = s.mesh.positions_t0(v, c);
      reversed1[at] = s.mesh.positions_t1(v, c);
    }
  const MatrixView<double> back0(reversed0.data() + reversed0.size() - 1, n, 3, -3, -1),
      back1(reversed1.data() + reversed1.size() - 1, n, 3, -3, -1);
  std::vector<int> reversed_faces(static_cast<std::size_t>(3 * m));
  for (Eigen::Index f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) reversed_faces[static_cast<std::size_t>(3 * (m - 1 - f) + c)] = s.mesh.faces(f, c);
  const MatrixView<int> back_faces(reversed_faces.data() + 3 * (m - 1), m, 3, -3, 1);
  expect_same(mesh_ccd({back0, back1, back_faces}, s.candidates), expected);

  // Every other double of a buffer, rows 8 doubles apart: a Map with both strides.
  using Strided = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<double> spread0(static_cast<std::size_t>(8 * n), 1e300), spread1(spread0.size(), -1e300);
  for (Eigen::Index v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) {
      spread0[static_cast<std::size_t>(8 * v + 2 * c)] = s.mesh.positions_t0(v, c);
      spread1[static_cast<std::size_t>(8 * v + 2 * c)] = s.mesh.positions_t1(v, c);
    }
  using RowMajorMap = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>, 0, Strided>;
  const RowMajorMap map0(spread0.data(), n, 3, Strided(8, 2)), map1(spread1.data(), n, 3, Strided(8, 2));
  expect_same(mesh_ccd({map0, map1, s.mesh.faces}, s.candidates), expected);

  // A Ref with any strides, to every third row of a taller matrix.
  Eigen::MatrixXd tall0 = Eigen::MatrixXd::Constant(3 * n, 3, 1e300), tall1 = tall0;
  for (Eigen::Index v = 0; v < n; ++v) {
    tall0.row(3 * v) = s.mesh.positions_t0.row(v);
    tall1.row(3 * v) = s.mesh.positions_t1.row(v);
  }
  using AnyStrides = Eigen::Ref<const Eigen::MatrixXd, 0, Strided>;
  const Eigen::Map<const Eigen::MatrixXd, 0, Strided> rows0(tall0.data(), n, 3, Strided(tall0.outerStride(), 3)),
      rows1(tall1.data(), n, 3, Strided(tall1.outerStride(), 3));
  const AnyStrides ref0(rows0), ref1(rows1);
  expect_same(mesh_ccd({ref0, ref1, s.mesh.faces}, s.candidates), expected);
}

TEST(Views, FloatPositionsAreReadExactly) {
  const Scene& s = scene();
  const Eigen::MatrixXf t0 = s.mesh.positions_t0.cast<float>(), t1 = s.mesh.positions_t1.cast<float>();
  // The same numbers as doubles: every float is one.
  const Eigen::MatrixXd t0_double = t0.cast<double>(), t1_double = t1.cast<double>();
  for (const Mode mode : {Mode::conservative, Mode::exact}) {
    const Options options{.mode = mode};
    const BatchResult expected = mesh_ccd({t0_double, t1_double, s.mesh.faces}, s.candidates, options);
    ASSERT_GT(expected.counters.hits, 0);
    expect_same(mesh_ccd({t0, t1, s.mesh.faces}, s.candidates, options), expected);
    // One float and one double matrix in the same call.
    expect_same(mesh_ccd({t0, t1_double, s.mesh.faces}, s.candidates, options), expected);
  }
}

TEST(Views, CandidateListsAreReadInPlace) {
  const Scene& s = scene();
  const BatchResult expected = mesh_ccd(s.mesh.view(), s.candidates);
  // The broad phase's output in buffers of the caller's own kind.
  const std::unique_ptr<std::array<int, 2>[]> vertex_face(new std::array<int, 2>[s.candidates.vertex_face.size()]);
  std::copy(s.candidates.vertex_face.begin(), s.candidates.vertex_face.end(), vertex_face.get());
  const CandidateLists lists{.vertex_face = {vertex_face.get(), s.candidates.vertex_face.size()},
                             .edge_edge = s.candidates.edge_edge};
  expect_same(mesh_ccd(s.mesh.view(), lists), expected);
}

TEST(Views, BadShapesAreRefusedWithTheirNames) {
  const Scene& s = scene();
  const Eigen::MatrixXd four_columns = Eigen::MatrixXd::Zero(s.mesh.positions_t0.rows(), 4);
  try {
    mesh_ccd({four_columns, s.mesh.positions_t1, s.mesh.faces}, s.candidates);
    FAIL() << "not refused";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("positions_t0 must have 3 columns"), std::string::npos) << error.what();
  }
  const Eigen::MatrixXd two_columns = s.mesh.positions_t0.leftCols(2);  // 2D at t0, 3D at t1
  try {
    mesh_ccd({two_columns, s.mesh.positions_t1, s.mesh.faces}, s.candidates);
    FAIL() << "not refused";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("a mesh is 2D or 3D at both times"), std::string::npos) << error.what();
  }
  const Eigen::MatrixXf fewer_rows = s.mesh.positions_t1.topRows(3).cast<float>();
  try {
    mesh_ccd({s.mesh.positions_t0, fewer_rows, s.mesh.faces}, s.candidates);
    FAIL() << "not refused";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("positions_t1 has 3"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace batchccd

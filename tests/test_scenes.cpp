// The benchmark scene tooling of bench/: the swept-box broad phase against
// brute force, its determinism and its agreement with the candidates of
// ../shared/data, the scene-directory writer, and the built-in scenes
// (true contacts, growth with size).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "batchccd/batch.hpp"
#include "batchccd/candidates.hpp"
#include "batchccd/io.hpp"
#include "broad_phase.hpp"
#include "scene_writer.hpp"
#include "scenes.hpp"
#include "shared_data.hpp"
#include "temporary_directory.hpp"

namespace batchccd {
namespace {

namespace fs = std::filesystem;
using scenes::MovingMesh;

// ------------------------------------------------------------------ helpers

// The definition of broad_phase.hpp, pair by pair.
Candidates brute_force_candidates(const MeshView& mesh, double margin) {
  auto box = [&](std::initializer_list<int> vertices) {
    std::array<double, 6> b{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int v : vertices)
      for (const PositionsView* positions : {&mesh.positions_t0, &mesh.positions_t1})
        for (int axis = 0; axis < 3; ++axis) {
          b[axis] = std::min(b[axis], (*positions)(v, axis));
          b[axis + 3] = std::max(b[axis + 3], (*positions)(v, axis));
        }
    for (int axis = 0; axis < 3; ++axis) {
      b[axis] -= margin;
      b[axis + 3] += margin;
    }
    return b;
  };
  auto overlap = [](const std::array<double, 6>& a, const std::array<double, 6>& b) {
    for (int axis = 0; axis < 3; ++axis)
      if (a[axis] > b[axis + 3] || b[axis] > a[axis + 3]) return false;
    return true;
  };
  Candidates candidates;
  const auto& faces = mesh.faces;
  for (int v = 0; v < mesh.positions_t0.rows(); ++v)
    for (int f = 0; f < faces.rows(); ++f)
      if (v != faces(f, 0) && v != faces(f, 1) && v != faces(f, 2) &&
          overlap(box({v}), box({faces(f, 0), faces(f, 1), faces(f, 2)})))
        candidates.vertex_face.push_back({v, f});
  const Eigen::MatrixXi edges = unique_edges(faces);
  for (Eigen::Index i = 0; i < edges.rows(); ++i)
    for (Eigen::Index j = i + 1; j < edges.rows(); ++j) {
      const int a0 = edges(i, 0), a1 = edges(i, 1), b0 = edges(j, 0), b1 = edges(j, 1);
      if (a0 != b0 && a0 != b1 && a1 != b0 && a1 != b1 && overlap(box({a0, a1}), box({b0, b1})))
        candidates.edge_edge.push_back({a0, a1, b0, b1});
    }
  return candidates;  // already in sorted order
}

// A mesh whose vertices follow a random walk of the given step, so faces of
// nearby ids are small and spread over space (many slabs), or, with a large
// step, big and overlapping everything. Coordinates are multiples of 1/64:
// boxes often touch exactly.
MovingMesh random_mesh(unsigned seed, int vertex_count, int face_count, double step) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-step, step);
  auto on_grid = [](double x) { return std::round(64 * x) / 64; };
  MovingMesh mesh;
  mesh.positions_t0.resize(vertex_count, 3);
  mesh.positions_t1.resize(vertex_count, 3);
  Eigen::RowVector3d walk = Eigen::RowVector3d::Zero();
  for (int v = 0; v < vertex_count; ++v) {
    for (int axis = 0; axis < 3; ++axis) {
      walk[axis] += offset(random);
      mesh.positions_t0(v, axis) = on_grid(walk[axis]);
      mesh.positions_t1(v, axis) = on_grid(walk[axis] + offset(random));
    }
  }
  std::uniform_int_distribution<int> first(0, vertex_count - 5), next(1, 4);
  mesh.faces.resize(face_count, 3);
  for (int f = 0; f < face_count; ++f) {
    const int a = first(random), b = a + next(random);
    int c = a + next(random);
    if (c == b) c = b == a + 4 ? a + 1 : b + 1;
    mesh.faces.row(f) << a, b, c;
  }
  return mesh;
}

void expect_same(const Candidates& actual, const Candidates& expected) {
  EXPECT_EQ(actual.vertex_face, expected.vertex_face);
  EXPECT_EQ(actual.edge_edge, expected.edge_edge);
}

Counters conservative_counters(const MeshView& mesh, const Candidates& candidates) {
  Options options;
  options.mode = Mode::conservative;
  options.per_candidate_results = false;
  return mesh_ccd(mesh, candidates, options).counters;
}

Counters conservative_counters(const MovingMesh& mesh) {
  const MeshView view = mesh.view();
  return conservative_counters(view, scenes::swept_box_candidates(view, scenes::mean_edge_length(view)));
}

std::size_t candidate_count(const MovingMesh& mesh, double margin) {
  const Candidates c = scenes::swept_box_candidates(mesh.view(), margin);
  return c.vertex_face.size() + c.edge_edge.size();
}

// -------------------------------------------------------------- broad phase

TEST(BroadPhase, MeanEdgeLength) {
  Eigen::MatrixXd square(4, 3);
  square << 0, 0, 0, 3, 0, 0, 3, 4, 0, 0, 4, 0;
  Eigen::MatrixXi faces(2, 3);
  faces << 0, 1, 2, 2, 3, 0;
  EXPECT_DOUBLE_EQ(scenes::mean_edge_length({square, square, faces}), (3 + 5 + 4 + 4 + 3) / 5.0);
}

TEST(BroadPhase, EqualsBruteForceOnRandomMeshes) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    for (const double step : {0.05, 0.4}) {
      const MovingMesh mesh = random_mesh(seed, 120, 160, step);
      for (const double margin : {0.0, 1.0 / 64, 0.1}) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " step " + std::to_string(step) + " margin " +
                     std::to_string(margin));
        expect_same(scenes::swept_box_candidates(mesh.view(), margin),
                    brute_force_candidates(mesh.view(), margin));
      }
    }
  }
}

TEST(BroadPhase, EqualsBruteForceOnSmallBuiltInScenes) {
  scenes::ClothOptions cloth;
  cloth.resolution = 12;
  scenes::RigidOptions rigid;
  rigid.resolution = 3;
  for (const MovingMesh& mesh : {scenes::cloth_scene(cloth), scenes::rigid_scene(rigid)}) {
    SCOPED_TRACE(mesh.name);
    const double margin = scenes::mean_edge_length(mesh.view());
    const Candidates candidates = scenes::swept_box_candidates(mesh.view(), margin);
    EXPECT_GT(candidates.vertex_face.size(), 1000u);
    expect_same(candidates, brute_force_candidates(mesh.view(), margin));
  }
}

TEST(BroadPhase, SameOutputEveryRunAndThreadCount) {
  scenes::ClothOptions cloth;
  cloth.resolution = 40;
  const MovingMesh mesh = scenes::cloth_scene(cloth);
  const double margin = scenes::mean_edge_length(mesh.view());
  const Candidates first = scenes::swept_box_candidates(mesh.view(), margin);
  expect_same(scenes::swept_box_candidates(mesh.view(), margin), first);
  tbb::task_arena one_thread(1);
  one_thread.execute([&] { expect_same(scenes::swept_box_candidates(mesh.view(), margin), first); });
}

TEST(BroadPhase, RejectsBadInput) {
  const MovingMesh mesh = random_mesh(7, 10, 5, 0.1);
  EXPECT_THROW(scenes::swept_box_candidates(mesh.view(), -1.0), std::invalid_argument);
  EXPECT_THROW(scenes::swept_box_candidates(mesh.view(), NAN), std::invalid_argument);
  MovingMesh broken = mesh;
  broken.positions_t1(3, 1) = NAN;
  EXPECT_THROW(scenes::swept_box_candidates(broken.view(), 0.0), std::invalid_argument);
  broken = mesh;
  broken.faces(2, 2) = 10;
  EXPECT_THROW(scenes::swept_box_candidates(broken.view(), 0.0), std::invalid_argument);
}

// Every candidate of the shared scenes has overlapping swept boxes (their
// README), so the dense list with no margin holds them all.
TEST(BroadPhase, ContainsTheCandidatesOfTheSharedScenes) {
  if (!testing::shared_data_present()) GTEST_SKIP() << testing::kSharedData << " is absent";
  int scenes_read = 0;
  for (const fs::path& directory : testing::shared_scene_directories()) {
    SCOPED_TRACE(directory.string());
    const Scene scene = read_scene(directory);
    const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
    const Candidates dense = scenes::swept_box_candidates(mesh, 0.0);
    for (const auto& candidate : scene.candidates.vertex_face)
      EXPECT_TRUE(std::binary_search(dense.vertex_face.begin(), dense.vertex_face.end(), candidate))
          << "vf " << candidate[0] << "," << candidate[1];
    for (auto candidate : scene.candidates.edge_edge) {
      // The dense list's orientation: each edge (low, high), edge a first.
      std::array<int, 2> a{std::min(candidate[0], candidate[1]), std::max(candidate[0], candidate[1])};
      std::array<int, 2> b{std::min(candidate[2], candidate[3]), std::max(candidate[2], candidate[3])};
      if (b < a) std::swap(a, b);
      const std::array<int, 4> sorted{a[0], a[1], b[0], b[1]};
      EXPECT_TRUE(std::binary_search(dense.edge_edge.begin(), dense.edge_edge.end(), sorted))
          << "ee " << sorted[0] << "," << sorted[1] << "," << sorted[2] << "," << sorted[3];
    }
    ++scenes_read;
  }
  EXPECT_GT(scenes_read, 0);
}

// ------------------------------------------------------------- scene writer

using SceneWriter = test_support::TemporaryDirectoryTest;

TEST_F(SceneWriter, RoundTripsThroughReadScene) {
  scenes::RigidOptions options;
  options.resolution = 2;
  const MovingMesh mesh = scenes::rigid_scene(options);
  const Candidates candidates =
      scenes::swept_box_candidates(mesh.view(), scenes::mean_edge_length(mesh.view()));
  const fs::path scene_directory = path(mesh.name);
  scenes::write_scene_directory(scene_directory, mesh.view(), candidates);
  const Scene scene = read_scene(scene_directory);

  EXPECT_EQ(scene.positions_t0, mesh.positions_t0);  // bit for bit
  EXPECT_EQ(scene.positions_t1, mesh.positions_t1);
  EXPECT_EQ(scene.faces, mesh.faces);
  expect_same(scene.candidates, candidates);
  EXPECT_FALSE(scene.vertex_face_truth.has_value());
  EXPECT_FALSE(scene.edge_edge_truth.has_value());
}

// ---------------------------------------------------------- built-in scenes

TEST(BuiltInScenes, AreDeterministic) {
  const MovingMesh a = scenes::cloth_scene(), b = scenes::cloth_scene();
  EXPECT_EQ(a.positions_t0, b.positions_t0);
  EXPECT_EQ(a.positions_t1, b.positions_t1);
  EXPECT_EQ(a.faces, b.faces);
  const MovingMesh c = scenes::rigid_scene(), d = scenes::rigid_scene();
  EXPECT_EQ(c.positions_t0, d.positions_t0);
  EXPECT_EQ(c.positions_t1, d.positions_t1);
  EXPECT_EQ(c.faces, d.faces);
}

TEST(BuiltInScenes, ClothFoldsOntoItselfLate) {
  scenes::ClothOptions options;
  options.resolution = 20;
  EXPECT_GT(conservative_counters(scenes::cloth_scene(options)).hits, 0);  // the default frame
  options.frame = 40;  // still unfolding: no contact yet
  EXPECT_EQ(conservative_counters(scenes::cloth_scene(options)).hits, 0);
}

TEST(BuiltInScenes, RigidBodiesTunnelWithinTheStep) {
  scenes::RigidOptions options;
  options.resolution = 3;
  const MovingMesh mesh = scenes::rigid_scene(options);
  EXPECT_GT(conservative_counters(mesh).hits, 0);
  // Neither end pose has a contact: a check of the end poses misses them all.
  for (const Eigen::MatrixXd* pose : {&mesh.positions_t0, &mesh.positions_t1}) {
    const MeshView still{*pose, *pose, mesh.faces};
    const Candidates candidates = scenes::swept_box_candidates(still, scenes::mean_edge_length(still));
    EXPECT_GT(candidates.edge_edge.size(), 0u);
    EXPECT_EQ(conservative_counters(still, candidates).hits, 0);
  }
}

TEST(BuiltInScenes, CandidatesGrowWithSize) {
  std::size_t previous = 0;
  for (const int resolution : {6, 12, 24}) {
    scenes::ClothOptions options;
    options.resolution = resolution;
    const MovingMesh mesh = scenes::cloth_scene(options);
    const std::size_t count = candidate_count(mesh, scenes::mean_edge_length(mesh.view()));
    EXPECT_GT(count, 2 * previous) << mesh.name;
    previous = count;
  }
  EXPECT_GE(previous, std::size_t{1000});
  previous = 0;
  for (const int resolution : {1, 2, 4}) {
    scenes::RigidOptions options;
    options.resolution = resolution;
    const MovingMesh mesh = scenes::rigid_scene(options);
    const std::size_t count = candidate_count(mesh, scenes::mean_edge_length(mesh.view()));
    EXPECT_GT(count, 2 * previous) << mesh.name;
    previous = count;
  }
}

TEST(BuiltInScenes, RejectBadOptions) {
  scenes::ClothOptions cloth;
  cloth.frame = cloth.frames;
  EXPECT_THROW(scenes::cloth_scene(cloth), std::invalid_argument);
  scenes::RigidOptions rigid;
  rigid.resolution = 0;
  EXPECT_THROW(scenes::rigid_scene(rigid), std::invalid_argument);
}

}  // namespace
}  // namespace batchccd

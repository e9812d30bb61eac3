// batchccd::ipc::collision_free_stepsize: the minimum over candidates of the
// per-query calls (ipc.hpp) called as ipc-toolkit's loop calls them, the
// same for any thread count, on 3D and 2D meshes.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "broad_phase.hpp"
#include "falling_contacts.hpp"
#include "scenes.hpp"

namespace batchccd {
namespace {

// The per-query front over every candidate, one after another, each asked
// over the whole step (tmax = 1): what the batch call must equal.
double per_query_minimum(const MeshView& mesh, const CandidateLists& candidates, double min_distance,
                         double rescaling = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING) {
  double earliest = 1;
  const auto row = [](const PositionsView& positions, int v) {
    Eigen::VectorXd point(positions.cols());
    for (int c = 0; c < positions.cols(); ++c) point[c] = positions(v, c);
    return point;
  };
  const auto& x0 = mesh.positions_t0;
  const auto& x1 = mesh.positions_t1;
  const double tolerance = ipc::DEFAULT_CCD_TOLERANCE;
  const long iterations = ipc::DEFAULT_CCD_MAX_ITERATIONS;
  double toi = 1;
  for (const auto& [v, f] : candidates.vertex_face) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (ipc::point_triangle_ccd(row(x0, v), row(x0, a), row(x0, b), row(x0, c), row(x1, v), row(x1, a),
                                row(x1, b), row(x1, c), toi, min_distance, 1.0, tolerance, iterations, rescaling))
      earliest = std::min(earliest, toi);
  }
  for (const auto& [a0, a1, b0, b1] : candidates.edge_edge)
    if (ipc::edge_edge_ccd(row(x0, a0), row(x0, a1), row(x0, b0), row(x0, b1), row(x1, a0), row(x1, a1),
                           row(x1, b0), row(x1, b1), toi, min_distance, 1.0, tolerance, iterations, rescaling))
      earliest = std::min(earliest, toi);
  for (const auto& [p, e0, e1] : candidates.vertex_edge)
    if (ipc::point_edge_ccd(row(x0, p), row(x0, e0), row(x0, e1), row(x1, p), row(x1, e0), row(x1, e1), toi,
                            min_distance, 1.0, tolerance, iterations, rescaling))
      earliest = std::min(earliest, toi);
  for (const auto& [p, q] : candidates.vertex_vertex)
    if (ipc::point_point_ccd(row(x0, p), row(x0, q), row(x1, p), row(x1, q), toi, min_distance, 1.0, tolerance,
                             iterations, rescaling))
      earliest = std::min(earliest, toi);
  return earliest;
}

struct SceneCase {
  scenes::MovingMesh mesh;
  Candidates candidates;
  double edge_length;
};

SceneCase cloth(int frame) {
  SceneCase scene{scenes::cloth_scene({.resolution = 16, .frames = 100, .frame = frame}), {}, 0};
  scene.edge_length = scenes::mean_edge_length(scene.mesh.view());
  scene.candidates = scenes::swept_box_candidates(scene.mesh.view(), scene.edge_length);
  return scene;
}

TEST(CollisionFreeStepsize, EqualsThePerQueryMinimumForAnyThreadCount) {
  int steps_below_one = 0;
  for (const int frame : {60, 73, 76, 90}) {
    const SceneCase scene = cloth(frame);
    ASSERT_GT(scene.candidates.vertex_face.size() + scene.candidates.edge_edge.size(), 1000u);
    for (const double separation : {0.0, 1e-3 * scene.edge_length, 1e-2 * scene.edge_length}) {
      SCOPED_TRACE(::testing::Message() << "frame " << frame << " min_distance " << separation);
      const double expected = per_query_minimum(scene.mesh.view(), scene.candidates, separation);
      for (const int threads : {1, 2}) {
        const double step = ipc::collision_free_stepsize(scene.mesh.view(), scene.candidates, separation,
                                                         ipc::DEFAULT_CCD_TOLERANCE, ipc::DEFAULT_CCD_MAX_ITERATIONS,
                                                         ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING, threads);
        EXPECT_EQ(step, expected) << threads << " threads";
      }
      steps_below_one += expected < 1;
    }
  }
  EXPECT_GE(steps_below_one, 6) << "the frames should hold contacts";
}

TEST(CollisionFreeStepsize, AllowsAStepFreeOfContact) {
  // A vertex falling onto a triangle at speed 1 from height 0.5: at the
  // returned step the vertex is still above min_distance (0.1).
  const Eigen::MatrixXd x0 = (Eigen::MatrixXd(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, 0.5).finished();
  Eigen::MatrixXd x1 = x0;
  x1(3, 2) = -0.5;
  const Eigen::MatrixXi faces = (Eigen::MatrixXi(1, 3) << 0, 1, 2).finished();
  const std::vector<std::array<int, 2>> vertex_face{{3, 0}};
  const double step = ipc::collision_free_stepsize({x0, x1, faces}, {.vertex_face = vertex_face}, 0.1);
  // The effective separation: 0.1 + min((1 - 0.8) (0.5 - 0.1), 1e-4) =
  // 0.1001, reached at t = 0.3999; within the distance tolerance (1e-6 at
  // speed 1) and the solver's time tolerance before it, never after.
  EXPECT_LE(step, 0.3999 + 1e-12);
  EXPECT_GE(step, 0.3999 - 2e-6);
  const double height = 0.5 - step;
  EXPECT_GT(height, 0.1);
  // Nothing in the way: the whole step.
  const std::vector<std::array<int, 2>> none;
  EXPECT_EQ(ipc::collision_free_stepsize({x0, x1, faces}, {.vertex_face = none}, 0.1), 1.0);
}

TEST(CollisionFreeStepsize, Planar2DMeshesEqualThePerQueryCalls) {
  // Random 2D segments (vertex pairs) moving in the plane, every vertex
  // against every segment not its own, and every vertex pair.
  const int n = 40;
  Eigen::MatrixXd x0(n, 2), x1(n, 2);
  std::uint64_t state = 12345;
  const auto coordinate = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return std::ldexp(static_cast<double>(state >> 44), -20) - 0.5;  // dyadic in [-0.5, 0.5)
  };
  for (int v = 0; v < n; ++v) {
    x0.row(v) << coordinate(), coordinate();
    x1.row(v) = x0.row(v) + 0.5 * Eigen::RowVector2d(coordinate(), coordinate());
  }
  Candidates candidates;
  for (int v = 0; v < n; ++v) {
    for (int e = 0; e + 1 < n; e += 2)
      if (v != e && v != e + 1) candidates.vertex_edge.push_back({v, e, e + 1});
    for (int w = v + 1; w < n; ++w) candidates.vertex_vertex.push_back({v, w});
  }
  const Eigen::MatrixXi no_faces;
  for (const double separation : {0.0, 1e-3, 1e-2}) {
    const double expected = per_query_minimum({x0, x1, no_faces}, candidates, separation);
    EXPECT_LT(expected, 1);
    for (const int threads : {1, 2})
      EXPECT_EQ(ipc::collision_free_stepsize({x0, x1, no_faces}, candidates, separation, ipc::DEFAULT_CCD_TOLERANCE,
                                             ipc::DEFAULT_CCD_MAX_ITERATIONS,
                                             ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING, threads),
                expected);
  }
}

// Contacts at falling times (falling_contacts.hpp), each the earliest once:
// filtered over the part of the step the ones before left open, the call
// must still find it.
TEST(CollisionFreeStepsize, FiltersOverTheOpenPartOfTheStepMissNoEarlierContact) {
  const std::vector<std::vector<double>> times = testing::falling_contact_times();
  for (std::size_t last_list = 0; last_list < times.size(); ++last_list)
    for (std::size_t last = 0; last < times[last_list].size(); ++last) {
      const testing::FallingContacts scene = testing::falling_contacts(last_list, last);
      for (const double separation : {0.0, 1e-3}) {
        SCOPED_TRACE(::testing::Message() << "earliest at " << times[last_list][last] << " min_distance "
                                          << separation);
        const double expected = per_query_minimum(scene.view(), scene.candidates, separation);
        EXPECT_LT(expected, times[last_list][last]);
        EXPECT_GT(expected, 0.5 * times[last_list][last]);
        for (const int threads : {1, 2})
          EXPECT_EQ(ipc::collision_free_stepsize(scene.view(), scene.candidates, separation,
                                                 ipc::DEFAULT_CCD_TOLERANCE, ipc::DEFAULT_CCD_MAX_ITERATIONS,
                                                 ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING, threads),
                    expected)
              << threads << " threads";
      }
    }
}

TEST(CollisionFreeStepsize, BadInputIsRefusedOrStepsNowhere) {
  const SceneCase scene = cloth(73);
  const auto refused = [&](auto call, const std::string& words) {
    try {
      call();
      ADD_FAILURE() << "not refused: " << words;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
  };
  refused([&] { ipc::collision_free_stepsize(scene.mesh.view(), scene.candidates, -1.0); },
          "batchccd::ipc::collision_free_stepsize: min_distance must be >= 0 and finite, got -1");
  refused([&] { ipc::collision_free_stepsize(scene.mesh.view(), scene.candidates, 0.0, 0.0); },
          "tolerance must be positive and finite");
  refused([&] { ipc::collision_free_stepsize(scene.mesh.view(), scene.candidates, 0.0, 1e-6, 100, 1.5); },
          "conservative_rescaling must be in (0, 1]");
  Candidates bad = scene.candidates;
  bad.edge_edge.push_back({0, 1, 2, static_cast<int>(scene.mesh.positions_t0.rows())});
  refused([&] { ipc::collision_free_stepsize(scene.mesh.view(), bad, 0.0); }, "edge-edge candidate");
  // A NaN where a candidate reads it: no step is safe.
  scenes::MovingMesh broken = scene.mesh;
  broken.positions_t1(scene.candidates.edge_edge[0][0], 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ipc::collision_free_stepsize(broken.view(), scene.candidates, 0.0), 0.0);
  // A bad id batches after the step is known to be 0 is still refused.
  Candidates bad_later = scene.candidates;
  bad_later.edge_edge.resize(bad_later.edge_edge.size() + 2 * 2048, bad_later.edge_edge.back());
  bad_later.edge_edge.push_back(bad.edge_edge.back());
  refused([&] { ipc::collision_free_stepsize(broken.view(), bad_later, 0.0, 1e-6, 100, 0.8, 1); },
          "edge-edge candidate");
}

}  // namespace
}  // namespace batchccd

// The code a simulator copies: hand batchccd a step's mesh and the broad
// phase's candidate pairs, get back the earliest time of impact.
//
//   first_contact                 a tiny scene built in code
//   first_contact SCENE_DIRECTORY a scene on disk (t0.ply, t1.ply, vf.csv, ee.csv)
#include <array>
#include <cstdio>
#include <exception>
#include <vector>

#include <batchccd/batchccd.hpp>

namespace {

void report(const char* scene, const batchccd::BatchResult& result) {
  const batchccd::Counters& c = result.counters;
  std::printf("%s: %lld candidates, %lld culled by the filter, %lld solved, %lld hits\n", scene,
              static_cast<long long>(c.candidates), static_cast<long long>(c.culled),
              static_cast<long long>(c.solved), static_cast<long long>(c.hits));
  if (result.earliest_toi <= 1.0)
    std::printf("earliest TOI: %.9g (of the step, never after the first contact)\n",
                result.earliest_toi);
  else
    std::printf("earliest TOI: none, the step is free of contact\n");
}

// What a simulator holds: positions at the start and end of the step, faces,
// edges, and the broad phase's pairs. Triangle (3, 4, 5) falls through the
// still triangle (0, 1, 2) from z = 1 to z = -1: first contact at t = 1/2.
batchccd::BatchResult built_in_scene(const batchccd::Options& options) {
  Eigen::MatrixXd x0(6, 3), x1(6, 3);
  x0 << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, 1, 0.25, -1, 1, -1, 0.25, 1;
  x1 << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, -1, 0.25, -1, -1, -1, 0.25, -1;
  Eigen::MatrixXi faces(2, 3), edges(6, 2);
  faces << 0, 1, 2, 3, 4, 5;
  edges << 0, 1, 1, 2, 2, 0, 3, 4, 4, 5, 5, 3;
  const std::vector<std::array<int, 2>> vertex_face = {{3, 0}, {4, 0}, {5, 0},
                                                       {0, 1}, {1, 1}, {2, 1}};
  const std::vector<std::array<int, 2>> edge_edge = {{0, 3}, {0, 4}, {0, 5}, {1, 3}, {1, 4},
                                                     {1, 5}, {2, 3}, {2, 4}, {2, 5}};
  return batchccd::mesh_ccd({x0, x1, faces, edges}, {vertex_face, edge_edge}, options);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    batchccd::Options options;               // conservative: never misses a contact
    options.per_candidate_results = false;   // only the earliest TOI and the counters
    if (argc > 1) {
      const batchccd::Scene scene = batchccd::read_scene(argv[1]);
      report(argv[1], batchccd::mesh_ccd({scene.positions_t0, scene.positions_t1, scene.faces},
                                         scene.candidates, options));
    } else {
      report("built-in scene", built_in_scene(options));
    }
    std::printf("batchccd %s\n", BATCHCCD_VERSION);
    return 0;
  } catch (const std::exception& error) {  // unreadable scene, bad ids: a message, not a crash
    std::fprintf(stderr, "first_contact: %s\n", error.what());
    return 1;
  }
}

// The scheduler's promises: the same answers whatever the thread count or
// the order in which batches finish, a caller's arena respected, calls from
// several host threads at once, and earliest-TOI-only calls.
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "batchccd/batchccd.hpp"
#include "scenes.hpp"
#include "broad_phase.hpp"

namespace batchccd {
namespace {

struct MeshCase {
  std::string name;
  Eigen::MatrixXd t0, t1;
  Eigen::MatrixXi faces;
  Candidates candidates;
  MeshView view() const { return {t0, t1, faces}; }
};

std::vector<MeshCase> mesh_cases() {
  std::vector<MeshCase> cases;
  for (const scenes::MovingMesh& mesh :
       {scenes::cloth_scene({.resolution = 24}), scenes::rigid_scene({.resolution = 3})}) {
    const MeshView view = mesh.view();
    cases.push_back({mesh.name, mesh.positions_t0, mesh.positions_t1, mesh.faces,
                     scenes::swept_box_candidates(view, scenes::mean_edge_length(view))});
  }
  const std::filesystem::path data = BATCHCCD_SHARED_DATA;
  if (std::filesystem::is_directory(data / "scenes"))
    for (const auto& entry : std::filesystem::directory_iterator(data / "scenes"))
      if (is_scene_directory(entry.path())) {
        Scene scene = read_scene(entry.path());
        cases.push_back({entry.path().filename().string(), scene.positions_t0, scene.positions_t1,
                         scene.faces, scene.candidates});
      }
  return cases;
}

void expect_identical(const BatchResult& a, const BatchResult& b, const std::string& what) {
  ASSERT_EQ(a.results.size(), b.results.size()) << what;
  for (std::size_t i = 0; i < a.results.size(); ++i) {
    ASSERT_EQ(a.results[i].hit, b.results[i].hit) << what << " candidate " << i;
    ASSERT_EQ(a.results[i].toi, b.results[i].toi) << what << " candidate " << i;
  }
  EXPECT_EQ(a.earliest_toi, b.earliest_toi) << what;
  EXPECT_EQ(a.counters.candidates, b.counters.candidates) << what;
  EXPECT_EQ(a.counters.culled, b.counters.culled) << what;
  EXPECT_EQ(a.counters.culled_by_sign, b.counters.culled_by_sign) << what;
  EXPECT_EQ(a.counters.culled_by_separation, b.counters.culled_by_separation) << what;
  EXPECT_EQ(a.counters.hits, b.counters.hits) << what;
}

TEST(Scheduler, ResultsDoNotDependOnTheThreadCount) {
  for (const MeshCase& mesh : mesh_cases()) {
    Options one;
    one.threads = 1;
    const BatchResult reference = mesh_ccd(mesh.view(), mesh.candidates, one);
    EXPECT_GT(reference.counters.candidates, 0) << mesh.name;
    for (int threads : {2, 8}) {
      Options many;
      many.threads = threads;
      expect_identical(reference, mesh_ccd(mesh.view(), mesh.candidates, many),
                       mesh.name + " threads " + std::to_string(threads));
    }
  }
}

TEST(Scheduler, RawQueriesDoNotDependOnTheThreadCount) {
  const std::filesystem::path data = BATCHCCD_SHARED_DATA;
  if (!std::filesystem::is_directory(data)) GTEST_SKIP() << data << " is absent";
  for (const auto& entry : std::filesystem::recursive_directory_iterator(data / "sample-queries")) {
    if (entry.path().extension() != ".csv") continue;
    const QueryFile file = read_query_csv(entry.path(), *kind_from_path(entry.path()));
    Options one, eight;
    one.threads = 1;
    eight.threads = 8;
    expect_identical(batch_ccd(file.kind, file.queries, one), batch_ccd(file.kind, file.queries, eight),
                     entry.path().string());
  }
}

TEST(Scheduler, RespectsTheCallersArena) {
  const MeshCase mesh = mesh_cases().front();
  Options options;  // threads = 0: the caller's arena
  const BatchResult reference = mesh_ccd(mesh.view(), mesh.candidates, options);
  tbb::task_arena single(1);
  BatchResult inside;
  single.execute([&] { inside = mesh_ccd(mesh.view(), mesh.candidates, options); });
  expect_identical(reference, inside, "inside a one-thread arena");
}

TEST(Scheduler, CallsFromSeveralHostThreadsAtOnce) {
  const MeshCase mesh = mesh_cases().front();
  const BatchResult reference = mesh_ccd(mesh.view(), mesh.candidates, {});
  std::vector<BatchResult> results(4);
  std::vector<std::thread> hosts;
  for (std::size_t k = 0; k < results.size(); ++k)
    hosts.emplace_back([&, k] {
      Options options;
      options.threads = static_cast<int>(k % 2) + 1;
      results[k] = mesh_ccd(mesh.view(), mesh.candidates, options);
    });
  for (std::thread& host : hosts) host.join();
  for (std::size_t k = 0; k < results.size(); ++k)
    expect_identical(reference, results[k], "host thread " + std::to_string(k));
}

TEST(Scheduler, EarliestToiOnlyCallsWriteNoResults) {
  const MeshCase mesh = mesh_cases().front();
  Options options;
  const BatchResult full = mesh_ccd(mesh.view(), mesh.candidates, options);
  options.per_candidate_results = false;
  const BatchResult earliest = mesh_ccd(mesh.view(), mesh.candidates, options);
  EXPECT_TRUE(earliest.results.empty());
  EXPECT_EQ(earliest.earliest_toi, full.earliest_toi);
  EXPECT_EQ(earliest.counters.hits, full.counters.hits);
  EXPECT_GT(full.counters.hits, 0);  // the cloth scene's step holds contacts
}

}  // namespace
}  // namespace batchccd

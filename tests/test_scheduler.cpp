// The scheduler's promises: the same answers whatever the thread count or
// the order in which batches finish, a caller's arena respected, calls from
// several host threads at once, and earliest-TOI-only calls.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "scenes.hpp"
#include "broad_phase.hpp"
#include "same_answers.hpp"
#include "shared_data.hpp"

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
  for (const std::filesystem::path& directory : testing::shared_scene_directories()) {
    Scene scene = read_scene(directory);
    cases.push_back({directory.filename().string(), scene.positions_t0, scene.positions_t1, scene.faces,
                     scene.candidates});
  }
  return cases;
}

void expect_identical(const BatchResult& a, const BatchResult& b, const std::string& what) {
  testing::expect_same_answers(a, b, what);
  EXPECT_EQ(a.earliest_toi, b.earliest_toi) << what;
  testing::expect_same_counts(a, b, what);
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
  if (!testing::shared_data_present()) GTEST_SKIP() << testing::kSharedData << " is absent";
  int files = 0;
  for (const std::filesystem::path& path : testing::shared_query_files()) {
    const QueryFile file = read_query_csv(path, *kind_from_path(path));
    Options one, eight;
    one.threads = 1;
    eight.threads = 8;
    expect_identical(batch_ccd(file.kind, file.queries, one), batch_ccd(file.kind, file.queries, eight),
                     path.string());
    ++files;
  }
  EXPECT_GT(files, 0) << "no query file under " << testing::kSharedData;
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
  // Its survivors are asked in a shrinking window (batch.hpp): fewer hits found.
  EXPECT_LE(earliest.counters.hits, full.counters.hits);
  EXPECT_GT(earliest.counters.hits, 0);  // the cloth scene's step holds contacts
}

// The hit list is the sparse form of the per-candidate results, in candidate
// order, for every thread count, filtered or not (the cubic baseline); alone
// it writes no results.
TEST(Scheduler, HitListsAreTheHitsOfTheResultsInOrder) {
  for (const MeshCase& mesh : mesh_cases()) {
    for (const lab::Method& method : {lab::kConservative, lab::kCubic}) {
      for (const int threads : {1, 2, 8}) {
        const std::string what =
            mesh.name + " " + lab::to_string(method) + " threads " + std::to_string(threads);
        Options options;
        options.threads = threads;
        options.hit_list = true;
        const BatchResult both = lab::mesh_ccd(mesh.view(), mesh.candidates, options, method.settings());
        std::vector<Hit> expected;
        for (std::size_t i = 0; i < both.results.size(); ++i)
          if (both.results[i].hit) expected.push_back({i, both.results[i].toi, both.results[i].status});
        ASSERT_EQ(both.hits.size(), expected.size()) << what;
        EXPECT_EQ(static_cast<std::int64_t>(both.hits.size()), both.counters.hits) << what;
        for (std::size_t k = 0; k < expected.size(); ++k) {
          ASSERT_EQ(both.hits[k].candidate, expected[k].candidate) << what;
          ASSERT_EQ(both.hits[k].toi, expected[k].toi) << what;
          ASSERT_EQ(both.hits[k].status, expected[k].status) << what;
        }
        options.per_candidate_results = false;
        const BatchResult hits_only = lab::mesh_ccd(mesh.view(), mesh.candidates, options, method.settings());
        EXPECT_TRUE(hits_only.results.empty()) << what;
        ASSERT_EQ(hits_only.hits.size(), expected.size()) << what;
        for (std::size_t k = 0; k < expected.size(); ++k)
          ASSERT_EQ(hits_only.hits[k].candidate, expected[k].candidate) << what;
      }
    }
  }
}

// A BatchResult passed back in gives what a fresh call gives, whatever it
// held before; a refused call leaves it as it was.
TEST(Scheduler, CallsIntoAnEarlierResultGiveWhatFreshCallsGive) {
  const std::vector<MeshCase> cases = mesh_cases();
  BatchResult reused;
  for (int round = 0; round < 2; ++round)
    for (const MeshCase& mesh : cases) {
      for (const bool dense : {true, false}) {
        Options options;
        options.threads = 2;
        options.per_candidate_results = dense;
        options.hit_list = !dense;
        mesh_ccd(mesh.view(), mesh.candidates, options, reused);
        const BatchResult fresh = mesh_ccd(mesh.view(), mesh.candidates, options);
        const std::string what = mesh.name + (dense ? " dense" : " hits");
        expect_identical(fresh, reused, what);
        ASSERT_EQ(fresh.hits.size(), reused.hits.size()) << what;
        for (std::size_t k = 0; k < fresh.hits.size(); ++k)
          ASSERT_EQ(fresh.hits[k].candidate, reused.hits[k].candidate) << what;
      }
    }
  const BatchResult before = reused;
  Candidates bad = cases.front().candidates;
  bad.edge_edge.push_back({0, 1, 2, -1});
  EXPECT_THROW(mesh_ccd(cases.front().view(), bad, Options{}, reused), std::invalid_argument);
  expect_identical(before, reused, "after a refused call");
}

TEST(Scheduler, RawQueryHitListsCountFromZero) {
  Query hit, miss;
  for (int k = 0; k < 4; ++k) {
    miss.points[k] = miss.points[k + 4] = Vec3(10.0 * k, 0, k == 3 ? 1 : 0);
  }
  // A vertex falling through the triangle (0,0,0), (1,0,0), (0,1,0) at t = 1/2.
  hit.points = {Vec3(0.25, 0.25, 1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                Vec3(0.25, 0.25, -1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const std::vector<Query> queries = {miss, hit, miss, hit};
  Options options;
  options.hit_list = true;
  const BatchResult result = batch_ccd(Kind::vertex_face, queries, options);
  ASSERT_EQ(result.hits.size(), 2u);
  EXPECT_EQ(result.hits[0].candidate, 1u);
  EXPECT_EQ(result.hits[1].candidate, 3u);
  EXPECT_LE(result.hits[0].toi, 0.5);
  EXPECT_GT(result.hits[0].toi, 0.5 - 1e-6);
}

}  // namespace
}  // namespace batchccd

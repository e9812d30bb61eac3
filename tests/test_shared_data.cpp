// The benchmark data of ../shared/data through the library's readers and
// batch calls. Conservative mode must never miss a collision; every mode's
// counters must agree with its per-query results. False positives and time
// per query are printed for the record, not asserted.
#include <gtest/gtest.h>

#include <cstdio>

#include "shared_data.hpp"

namespace batchccd {
namespace {

using testing::DataRun;

std::vector<DataRun> run_all_data(const lab::Method& method) { return testing::run_shared_data(method); }

void record(const std::vector<DataRun>& runs, const lab::Method& method) {
  std::int64_t queries = 0, false_positives = 0, false_negatives = 0;
  double seconds = 0;
  for (const DataRun& run : runs) {
    queries += static_cast<std::int64_t>(run.results.size());
    false_positives += run.false_positives();
    false_negatives += run.false_negatives();
    seconds += run.seconds;
  }
  std::printf("[ record   ] %s: %lld queries, %lld false positives, %lld false negatives, "
              "%.2f us per query\n",
              lab::to_string(method), static_cast<long long>(queries),
              static_cast<long long>(false_positives), static_cast<long long>(false_negatives),
              queries ? 1e6 * seconds / static_cast<double>(queries) : 0.0);
}

// What the counters say must be what the results say.
void expect_counters_match_results(const DataRun& run) {
  std::int64_t hits = 0;
  for (const QueryResult& result : run.results) hits += result.hit;
  EXPECT_EQ(run.counters.hits, hits) << run.input << " " << to_string(run.kind);
  EXPECT_EQ(run.counters.candidates, static_cast<std::int64_t>(run.results.size())) << run.input;
  EXPECT_EQ(run.counters.solved + run.counters.culled, run.counters.candidates) << run.input;
}

class SharedData : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!testing::shared_data_present()) GTEST_SKIP() << testing::kSharedData << " is absent";
  }
};

TEST_F(SharedData, ConservativeModeMissesNoCollision) {
  const std::vector<DataRun> runs = run_all_data(lab::kConservative);
  ASSERT_FALSE(runs.empty());
  for (const DataRun& run : runs) {
    ASSERT_TRUE(run.truth.has_value()) << run.input << " has no ground truth";
    ASSERT_EQ(run.truth->size(), run.results.size()) << run.input;
    EXPECT_EQ(run.false_negatives(), 0) << run.input << " " << to_string(run.kind);
    expect_counters_match_results(run);
  }
  record(runs, lab::kConservative);
}

// The stages not on by default, at their strongest: 8 pieces and the swept
// boxes cull more, and still no collision.
TEST_F(SharedData, EveryFilterStageMissesNoCollision) {
  const std::vector<DataRun> runs =
      testing::run_shared_data(lab::kConservative, {}, {.filter_pieces = 8, .swept_box_filter = true});
  ASSERT_FALSE(runs.empty());
  std::int64_t by_pieces = 0, by_boxes = 0;
  for (const DataRun& run : runs) {
    ASSERT_TRUE(run.truth.has_value()) << run.input << " has no ground truth";
    EXPECT_EQ(run.false_negatives(), 0) << run.input << " " << to_string(run.kind);
    expect_counters_match_results(run);
    by_pieces += run.counters.culled_by_pieces;
    by_boxes += run.counters.culled_by_swept_box;
  }
  EXPECT_GT(by_pieces, 0);
  EXPECT_GT(by_boxes, 0);
}

TEST_F(SharedData, BaselinesCountersMatchTheirResults) {
  for (const lab::Method& method : {lab::kFast, lab::kCubic}) {
    const std::vector<DataRun> runs = run_all_data(method);
    ASSERT_FALSE(runs.empty());
    for (const DataRun& run : runs) {
      ASSERT_TRUE(run.truth.has_value()) << run.input;
      expect_counters_match_results(run);
      EXPECT_EQ(run.counters.exact_escalations, 0) << run.input << ": no exact stage in " << lab::to_string(method);
    }
    record(runs, method);
  }
}

}  // namespace
}  // namespace batchccd

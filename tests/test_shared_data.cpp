// The benchmark data of ../shared/data through exactly the code path of
// `batchccd run`. Conservative mode must never miss a collision; the other
// modes must run and count their own errors honestly. False positives and
// time per query are printed for the record, not asserted.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "run.hpp"

namespace batchccd {
namespace {

const std::filesystem::path kData = BATCHCCD_SHARED_DATA;

cli::RunOutcome run_all_data(Mode mode) {
  cli::RunSettings settings;
  settings.inputs = {kData / "sample-queries"};
  for (const auto& entry : std::filesystem::directory_iterator(kData / "scenes"))
    if (entry.is_directory()) settings.inputs.push_back(entry.path());
  settings.options.mode = mode;
  std::ostringstream errors;
  cli::RunOutcome outcome = cli::run_inputs(settings, errors);
  EXPECT_FALSE(outcome.any_error) << errors.str();
  return outcome;
}

void record(const cli::RunOutcome& outcome, Mode mode) {
  std::int64_t queries = 0, false_positives = 0, false_negatives = 0;
  double seconds = 0;
  for (const cli::InputReport& report : outcome.reports) {
    queries += report.queries;
    false_positives += report.false_positives.value_or(0);
    false_negatives += report.false_negatives.value_or(0);
    seconds += report.seconds;
  }
  std::printf("[ record   ] %s: %lld queries, %lld false positives, %lld false negatives, "
              "%.2f us per query\n",
              to_string(mode), static_cast<long long>(queries),
              static_cast<long long>(false_positives), static_cast<long long>(false_negatives),
              queries ? 1e6 * seconds / static_cast<double>(queries) : 0.0);
}

class SharedData : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::is_directory(kData)) GTEST_SKIP() << kData << " is absent";
  }
};

TEST_F(SharedData, ConservativeModeMissesNoCollision) {
  const cli::RunOutcome outcome = run_all_data(Mode::conservative);
  ASSERT_FALSE(outcome.reports.empty());
  for (const cli::InputReport& report : outcome.reports) {
    ASSERT_TRUE(report.false_negatives.has_value()) << report.input << " has no ground truth";
    EXPECT_EQ(*report.false_negatives, 0) << report.input << " " << to_string(report.kind);
    EXPECT_EQ(report.queries, static_cast<std::int64_t>(report.results.size()));
  }
  record(outcome, Mode::conservative);
}

TEST_F(SharedData, BaselineModesRunAndCountTheirErrors) {
  for (Mode mode : {Mode::fast, Mode::cubic}) {
    const cli::RunOutcome outcome = run_all_data(mode);
    ASSERT_FALSE(outcome.reports.empty());
    for (const cli::InputReport& report : outcome.reports) {
      ASSERT_TRUE(report.false_negatives.has_value());
      // The counts must add up with the per-query results.
      std::int64_t hits = 0;
      for (const QueryResult& result : report.results) hits += result.hit;
      EXPECT_EQ(hits, report.hits) << report.input;
      EXPECT_EQ(*report.positives - *report.false_negatives + *report.false_positives, report.hits)
          << report.input;
    }
    record(outcome, mode);
  }
}

}  // namespace
}  // namespace batchccd

#pragma once

// Two batch results that must give every candidate the same answer, bit for
// bit (another layout, another instruction set, a reused result), and the
// same counts where the work must be the same too.

#include <cstddef>
#include <string>

#include <gtest/gtest.h>

#include "batchccd/batch.hpp"

namespace batchccd::testing {

// One failure for all the candidates that differ, naming how many and the
// first (a failure per candidate would bury the report).
inline void expect_same_answers(const BatchResult& actual, const BatchResult& expected,
                                const std::string& what = "") {
  ASSERT_EQ(actual.results.size(), expected.results.size()) << what;
  std::size_t differing = 0, first = 0;
  for (std::size_t i = 0; i < expected.results.size(); ++i) {
    const QueryResult& a = actual.results[i];
    const QueryResult& e = expected.results[i];
    if (a.hit != e.hit || a.toi != e.toi) {
      if (differing == 0) first = i;
      ++differing;
    }
  }
  EXPECT_EQ(differing, 0u) << what << ": first at candidate " << first << ", hit "
                           << actual.results[first].hit << " toi " << actual.results[first].toi
                           << " where expected hit " << expected.results[first].hit << " toi "
                           << expected.results[first].toi;
}

// The same candidates, culled by the same filters, the same survivors and
// hits: what no thread count, instruction set or equivalent call changes.
inline void expect_same_counts(const BatchResult& actual, const BatchResult& expected, const std::string& what = "") {
  EXPECT_EQ(actual.counters.candidates, expected.counters.candidates) << what;
  EXPECT_EQ(actual.counters.culled, expected.counters.culled) << what;
  EXPECT_EQ(actual.counters.culled_by_sign, expected.counters.culled_by_sign) << what;
  EXPECT_EQ(actual.counters.culled_by_separation, expected.counters.culled_by_separation) << what;
  EXPECT_EQ(actual.counters.culled_by_pieces, expected.counters.culled_by_pieces) << what;
  EXPECT_EQ(actual.counters.culled_by_swept_box, expected.counters.culled_by_swept_box) << what;
  EXPECT_EQ(actual.counters.solved, expected.counters.solved) << what;
  EXPECT_EQ(actual.counters.hits, expected.counters.hits) << what;
}

}  // namespace batchccd::testing

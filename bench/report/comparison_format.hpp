#pragma once

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "compare.hpp"

// How the comparison commands show their tallies: an aligned table and CSV
// (plot.hpp draws the CSV).
namespace batchccd::bench {

// One row per method: seconds, candidates/s, speed-up against the cubic
// row (when there is one), cull ratio, false negatives and positives, TOI
// error max and mean.
void print_comparison(std::ostream& out, const std::vector<MethodTally>& tallies);

// CSV with a header line; each row a label (an input, or "total") and a
// method's figures, numbers round-trippable.
void write_comparison_csv(std::ostream& out,
                          const std::vector<std::pair<std::string, MethodTally>>& rows);

}  // namespace batchccd::bench

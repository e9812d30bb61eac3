#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "batchccd/batch.hpp"
#include "batchccd/lab.hpp"

// The stiff and extreme suite: queries built to stress one numerical extreme
// each (tiny motion against large coordinates, very fast motion, coordinates
// near 1e-300 and 1e300, nearly coplanar motion, nearly parallel edges,
// contact at exactly t = 0 or t = 1, vertices that do not move), and the
// evaluation of every mode on them against exact mode. Deterministic: fixed
// seeds and an own generator, so the same numbers on every machine.
namespace batchccd::scenes {

// One item of the suite, one kind of query.
struct ExtremeCategory {
  std::string name;         // short, e.g. "stiff 1e-10"
  std::string description;  // one line: what the queries are
  Kind kind = Kind::vertex_face;
  std::vector<Query> queries;
  // Per query, what the construction proves in real arithmetic on the double
  // inputs: 1 contact, 0 no contact, -1 unknown (left to exact mode).
  std::vector<signed char> constructed_truth;
  // Per query: the first contact time rounded down to a double where
  // constructed_truth is 1 (so a TOI t is after the contact iff t > this),
  // +inf elsewhere.
  std::vector<double> constructed_first_contact;
};

// The whole suite: every item above with vertex-face and edge-edge queries
// (nearly parallel edges: edge-edge only), `queries_per_category` each,
// hits and misses mixed, near misses on both sides of zero distance.
std::vector<ExtremeCategory> extreme_categories(int queries_per_category = 64);

// One mode on one category, with exact mode's decisions as ground truth.
struct ExtremeRow {
  std::string category;
  Kind kind = Kind::vertex_face;
  lab::Method method = lab::kExact;
  std::int64_t queries = 0;
  std::int64_t agree = 0;            // decisions equal to exact mode's
  std::int64_t false_negatives = 0;  // exact says contact, this mode says none
  std::int64_t false_positives = 0;
  std::int64_t nan_tois = 0;
  // Not NaN, yet neither in [0, 1] on a hit nor +inf on a miss.
  std::int64_t malformed_tois = 0;
  // Against the construction, over queries with constructed_truth >= 0.
  std::int64_t truth_known = 0;
  std::int64_t truth_disagreements = 0;
  std::int64_t late_tois = 0;  // a hit reported after the constructed first contact
  BatchResult batch;           // the call's per-query results and counters
};

// Runs batch_ccd on every category in exact and conservative mode and the
// fast and cubic baselines (in that order, four rows a category) with
// `options`, except that each call gets its method and asks for
// time_queries and per-candidate results.
std::vector<ExtremeRow> evaluate_extreme(const std::vector<ExtremeCategory>& categories,
                                         const Options& options = {});

// An aligned plain-text table, one line per row, for a terminal.
void write_extreme_table(std::ostream& out, const std::vector<ExtremeRow>& rows);

}  // namespace batchccd::scenes

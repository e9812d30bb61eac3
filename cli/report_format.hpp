#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run.hpp"

// How `batchccd run` shows its reports: JSON lines, an aligned table, and
// the per-query results file of --out.
namespace batchccd::cli {

// input, kind, mode, min_distance, tmax, isa, threads, queries, hits, positives,
// false_positives, false_negatives (null without ground truth, or with truth
// labelled for another min_distance or tmax), truth_min_distance, truth_tmax
// (what the truth is labelled for; null without), culled, seconds,
// queries_per_second, exact_escalations, max_query_seconds.
nlohmann::ordered_json json_object(const InputReport& report);

// json_object on one line. Bytes of the input path that are not UTF-8 (paths
// are bytes) become U+FFFD; a non-finite number is null.
std::string json_line(const InputReport& report);

// One row per report and a totals row, columns aligned (a min_distance
// column when the rows differ in it), then a note for each input whose truth
// is not scored; nothing when there are no reports.
void print_table(std::ostream& out, const std::vector<InputReport>& reports);

// "hit,toi": hit 0/1, toi round-trippable, "inf" when there is no hit.
std::string result_line(const QueryResult& result);

// Every report's results, one line each, in order. Written to FILE.tmp-<pid>
// and renamed over FILE, so FILE is either the old file or complete.
// Throws std::runtime_error when it cannot (no temporary file is left).
void write_results_file(const std::filesystem::path& file,
                        const std::vector<InputReport>& reports);

}  // namespace batchccd::cli

#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "run.hpp"

// How `batchccd run` shows its reports: JSON lines, an aligned table, and
// the per-query results file of --out.
namespace batchccd::cli {

// A JSON string literal, quotes included. Control characters are escaped;
// bytes that are not valid UTF-8 (paths are bytes) become U+FFFD.
std::string json_string(std::string_view text);

// The shortest decimal that reads back as the same double; "inf" / "-inf" /
// "nan" for the non-finite values.
std::string round_trip_decimal(double value);

// One JSON object, no newline: input, kind, mode, isa, threads, queries,
// hits, positives, false_positives, false_negatives (null without ground
// truth), culled, seconds, queries_per_second, exact_escalations,
// max_query_seconds.
std::string json_line(const InputReport& report);

// One row per report and a totals row, columns aligned; nothing when there
// are no reports.
void print_table(std::ostream& out, const std::vector<InputReport>& reports);

// "hit,toi": hit 0/1, toi round-trippable, "inf" when there is no hit.
std::string result_line(const QueryResult& result);

// Every report's results, one line each, in order. Written to FILE.tmp-<pid>
// and renamed over FILE, so FILE is either the old file or complete.
// Throws std::runtime_error when it cannot (no temporary file is left).
void write_results_file(const std::filesystem::path& file,
                        const std::vector<InputReport>& reports);

}  // namespace batchccd::cli

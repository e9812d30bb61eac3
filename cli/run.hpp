#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"

// `batchccd run` without its command line: find the inputs, read them, run
// the narrow phase on each and collect one report per input and kind. The
// executable, the tests and later commands all go through run_inputs.
namespace batchccd::cli {

// What ground truth is labelled for: a contact is the primitives coming
// within min_distance at some t in [0, tmax].
struct TruthLabels {
  double min_distance = 0;
  double tmax = 1;
};

// The file in which a data set states the separation its truth is labelled
// for (one number), beside its query files or in its scene directory, as in
// ../shared/data/min-distance/unit-ms1e-3. Without it, truth is labelled
// for touching (0); for tmax 1 always (no data states another).
inline constexpr const char* stated_separation_file = "ms.txt";

struct RunSettings {
  // Query CSVs, directories searched recursively, scene directories; run in
  // this order.
  std::vector<std::filesystem::path> inputs;
  // --kind: the kind of a query file whose path names none.
  std::optional<Kind> kind;
  // --truth: ground truth for query files (replaces a truth column).
  std::optional<std::filesystem::path> truth;
  // mode, min_distance, tmax, isa and threads as given; the per-call
  // switches are set per input.
  Options options;
  // No --min-distance: each input takes the separation its data states
  // (stated_separation_file), options.min_distance where it states none.
  bool min_distance_from_data = false;
  // Keep every query's result in InputReport::results (--out needs them).
  bool keep_results = false;
  // --repeat: each input's call made this many times into the same result,
  // its best time reported (first touch and allocation out, as in a
  // simulator's frame loop).
  int repeat = 1;
  // --time-queries: time every query for InputReport::max_query_seconds
  // (two clock reads a query the scalar path evaluates).
  bool time_queries = false;
};

// The outcome of one input and one kind (a scene gives two to four).
struct InputReport {
  std::string input;  // the path as given or as found under a directory
  Kind kind = Kind::vertex_face;
  Mode mode = Mode::conservative;
  double min_distance = 0;  // Options::min_distance and tmax of the call
  double tmax = 1;
  Isa isa = Isa::scalar;  // the instruction set actually used
  int threads = 1;        // worker threads asked of the library
  std::int64_t queries = 0;
  std::int64_t hits = 0;
  std::int64_t culled = 0;
  // What the input's ground truth is labelled for; none without truth.
  std::optional<TruthLabels> truth_labels;
  // Known only when the input has ground truth labelled for this call's
  // min_distance and tmax (truth for other ones would count wrong answers).
  std::optional<std::int64_t> positives;
  std::optional<std::int64_t> false_positives;
  std::optional<std::int64_t> false_negatives;
  double seconds = 0;  // the narrow-phase call alone, reading excluded; the best of --repeat
  // Exact and conservative modes: queries whose decision (or TOI) exact
  // arithmetic settled (0 in the other modes).
  std::int64_t exact_escalations = 0;
  // Wall-clock time of the call's slowest single query (0 without queries),
  // with --time-queries.
  std::optional<double> max_query_seconds;
  // One per query in input order (a scene: one kind's candidates), filled
  // when RunSettings::keep_results is set or the input has ground truth.
  std::vector<QueryResult> results;

  // 0 when nothing was timed.
  double queries_per_second() const;
  // The input has truth, labelled for another min_distance or tmax.
  bool truth_not_scored() const;
};

struct RunOutcome {
  std::vector<InputReport> reports;  // in the order processed
  bool any_error = false;            // some input failed; told on `errors`
};

// One unit of work behind a command-line input.
struct FoundInput {
  std::filesystem::path path;
  bool is_scene = false;  // a scene directory; else a query CSV
};

// What an input stands for: itself (a query file or a scene directory), or
// the query files and scenes found under a directory, in sorted path order.
// A plain file that is not a CSV is passed over with a note on `notes`.
// Throws InputError when the input does not exist or a directory holds
// nothing to run.
std::vector<FoundInput> find_inputs(const std::filesystem::path& input,
                                    const std::optional<Kind>& fallback_kind, std::ostream& notes);

// The kind of a query file: the one its path names, else `fallback_kind`.
// Throws InputError when there is neither.
Kind kind_of_query_file(const std::filesystem::path& file, const std::optional<Kind>& fallback_kind);

// Runs every input; an input that fails is reported on `errors` (one line
// naming the file and, where there is one, the line) and the rest still run.
RunOutcome run_inputs(const RunSettings& settings, std::ostream& errors);

}  // namespace batchccd::cli

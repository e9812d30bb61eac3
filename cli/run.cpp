#include "run.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <limits>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

namespace batchccd::cli {

namespace fs = std::filesystem;

double InputReport::queries_per_second() const {
  return seconds > 0 ? static_cast<double>(queries) / seconds : 0.0;
}

bool InputReport::truth_not_scored() const { return truth_labels && !false_negatives; }

namespace {

bool is_query_file_candidate(const fs::directory_entry& entry,
                             const std::optional<Kind>& fallback_kind) {
  return entry.is_regular_file() && entry.path().extension() == ".csv" &&
         (kind_from_path(entry.path()) || fallback_kind);
}

// Scenes are taken whole: their own vf.csv, ee.csv and queries_*.csv are
// part of the scene, not query files of their own.
std::vector<FoundInput> find_inputs_in_directory(const fs::path& root,
                                                 const std::optional<Kind>& fallback_kind) {
  std::vector<FoundInput> found;
  for (auto entry = fs::recursive_directory_iterator(root);
       entry != fs::recursive_directory_iterator(); ++entry) {
    if (entry->is_directory() && is_scene_directory(entry->path())) {
      found.push_back({entry->path(), true});
      entry.disable_recursion_pending();
    } else if (is_query_file_candidate(*entry, fallback_kind)) {
      found.push_back({entry->path(), false});
    }
  }
  // Directory iteration order is the file system's: sort for stable output.
  std::sort(found.begin(), found.end(),
            [](const FoundInput& a, const FoundInput& b) { return a.path < b.path; });
  if (found.empty()) {
    throw InputError(root.string(), 0,
                     "no query files (*.csv under a path naming vertex-face/vf, edge-edge/ee, "
                     "vertex-edge/ve or vertex-vertex/vv) and no scenes found");
  }
  return found;
}

int threads_asked(const Options& options) {
  if (options.threads > 0) return options.threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// The separation `directory`'s data states, if it states one.
std::optional<double> stated_separation(const fs::path& directory) {
  const fs::path file = directory / stated_separation_file;
  std::error_code unreadable;
  if (!fs::is_regular_file(file, unreadable)) return std::nullopt;
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(file.string(), 0, "cannot be read");
  const std::string content = text.str();
  constexpr const char* blanks = " \t\r\n";
  const std::size_t first = content.find_first_not_of(blanks);
  const std::string number =
      first == std::string::npos ? "" : content.substr(first, content.find_last_not_of(blanks) - first + 1);
  double separation = 0;
  const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), separation);
  if (error != std::errc() || end != number.data() + number.size() || !(separation >= 0) ||
      !std::isfinite(separation))
    throw InputError(file.string(), 1,
                     "must hold one separation, a number >= 0 and finite, not '" + number + "'");
  return separation;
}

// What a data set's truth is labelled for: the separation it states, else
// touching; the whole step.
TruthLabels data_labels(std::optional<double> stated_separation) { return {stated_separation.value_or(0), 1}; }

// The call's options for an input whose data states `stated_separation`.
Options options_for_call(const RunSettings& settings, std::optional<double> stated_separation, bool truth_known) {
  Options options = settings.options;
  if (settings.min_distance_from_data) options.min_distance = stated_separation.value_or(options.min_distance);
  // Per-query results cost memory: ask for them only when they are used.
  options.per_candidate_results = settings.keep_results || truth_known;
  options.time_queries = settings.time_queries;
  return options;
}

struct TimedResult {
  BatchResult result;
  double seconds = 0;
};

// The call `repeat` times into one result, timed each time: the best time.
TimedResult timed(int repeat, const std::function<void(BatchResult&)>& narrow_phase) {
  TimedResult timed_result{{}, std::numeric_limits<double>::infinity()};
  for (int round = 0; round < std::max(repeat, 1); ++round) {
    const auto start = std::chrono::steady_clock::now();
    narrow_phase(timed_result.result);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    timed_result.seconds = std::min(timed_result.seconds, elapsed.count());
  }
  return timed_result;
}

void compare_with_truth(const std::vector<bool>& truth, InputReport& report) {
  std::int64_t positives = 0, false_positives = 0, false_negatives = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const bool hit = report.results[i].hit;
    positives += truth[i] ? 1 : 0;
    false_positives += (hit && !truth[i]) ? 1 : 0;
    false_negatives += (!hit && truth[i]) ? 1 : 0;
  }
  report.positives = positives;
  report.false_positives = false_positives;
  report.false_negatives = false_negatives;
}

// Ground truth and what it is labelled for.
struct Truth {
  const std::optional<std::vector<bool>>& per_query;
  TruthLabels labelled_for;
};

InputReport make_report(std::string input, Kind kind, std::size_t query_count,
                        TimedResult timed_result, const Options& options, const Truth& truth) {
  InputReport report;
  report.input = std::move(input);
  report.kind = kind;
  report.mode = options.mode;
  report.min_distance = options.min_distance;
  report.tmax = options.tmax;
  report.isa = resolve_isa(options.isa);
  report.threads = threads_asked(options);
  report.queries = static_cast<std::int64_t>(query_count);
  report.hits = timed_result.result.counters.hits;
  report.culled = timed_result.result.counters.culled;
  report.exact_escalations = timed_result.result.counters.exact_escalations;
  if (options.time_queries) report.max_query_seconds = timed_result.result.counters.max_query_seconds;
  report.seconds = timed_result.seconds;
  report.results = std::move(timed_result.result.results);
  if (options.per_candidate_results && report.results.size() != query_count) {
    throw std::runtime_error(report.input + ": the library returned " +
                             std::to_string(report.results.size()) + " results for " +
                             std::to_string(query_count) + " queries");
  }
  if (truth.per_query) {
    report.truth_labels = truth.labelled_for;
    if (truth.labelled_for.min_distance == options.min_distance && truth.labelled_for.tmax == options.tmax)
      compare_with_truth(*truth.per_query, report);
  }
  return report;
}

std::vector<bool> read_truth_for(const fs::path& truth_file, const QueryFile& queries) {
  std::vector<bool> truth = read_truth(truth_file);
  if (truth.size() != queries.queries.size()) {
    throw InputError(truth_file.string(), 0,
                     "has " + std::to_string(truth.size()) + " entries but " + queries.path +
                         " has " + std::to_string(queries.queries.size()) + " queries");
  }
  return truth;
}

std::vector<InputReport> run_query_file(const fs::path& file, const RunSettings& settings) {
  const Kind kind = kind_of_query_file(file, settings.kind);
  QueryFile queries = read_query_csv(file, kind);
  const std::optional<double> stated = stated_separation(file.parent_path());
  if (settings.truth) queries.truth = read_truth_for(*settings.truth, queries);
  const Options options = options_for_call(settings, stated, queries.truth.has_value());
  // --truth is given for this very run; a truth column is the data's.
  const TruthLabels labelled_for =
      settings.truth ? TruthLabels{options.min_distance, options.tmax} : data_labels(stated);
  TimedResult timed_result = timed(settings.repeat, [&](BatchResult& out) {
    batch_ccd(kind, queries.queries, options, out);
  });
  return {make_report(file.string(), kind, queries.queries.size(), std::move(timed_result),
                      options, {queries.truth, labelled_for})};
}

// A scene's candidate list and truth of one kind.
struct SceneList {
  std::size_t count;
  const std::optional<std::vector<bool>>& truth;
};

SceneList scene_list(const Scene& scene, Kind kind) {
  switch (kind) {
    case Kind::vertex_face: return {scene.candidates.vertex_face.size(), scene.vertex_face_truth};
    case Kind::edge_edge: return {scene.candidates.edge_edge.size(), scene.edge_edge_truth};
    case Kind::vertex_edge: return {scene.candidates.vertex_edge.size(), scene.vertex_edge_truth};
    case Kind::vertex_vertex: break;
  }
  return {scene.candidates.vertex_vertex.size(), scene.vertex_vertex_truth};
}

InputReport run_scene_kind(const Scene& scene, Kind kind, const RunSettings& settings,
                           std::optional<double> stated) {
  const SceneList list = scene_list(scene, kind);
  // One kind per call, so that time and counters are per kind.
  Options options = options_for_call(settings, stated, list.truth.has_value());
  options.vertex_face = kind == Kind::vertex_face;
  options.edge_edge = kind == Kind::edge_edge;
  options.vertex_edge = kind == Kind::vertex_edge;
  options.vertex_vertex = kind == Kind::vertex_vertex;
  const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
  TimedResult timed_result =
      timed(settings.repeat, [&](BatchResult& out) { mesh_ccd(mesh, scene.candidates, options, out); });
  return make_report(scene.path, kind, list.count, std::move(timed_result), options,
                     {list.truth, data_labels(stated)});
}

// vf and ee always (an absent list is an empty one, as ever); ve and vv when
// the scene has their file, so that triangle-mesh scenes report as before.
std::vector<InputReport> run_scene(const fs::path& directory, const RunSettings& settings) {
  if (settings.truth) {
    throw InputError(directory.string(), 0,
                     "--truth is for query files; a scene has vf_truth.txt, ee_truth.txt, "
                     "ve_truth.txt and vv_truth.txt");
  }
  Scene scene = read_scene(directory);
  scene.path = directory.string();  // report the path as given
  const std::optional<double> stated = stated_separation(directory);
  std::vector<InputReport> reports{run_scene_kind(scene, Kind::vertex_face, settings, stated),
                                   run_scene_kind(scene, Kind::edge_edge, settings, stated)};
  std::error_code unreadable;
  if (fs::is_regular_file(directory / "ve.csv", unreadable))
    reports.push_back(run_scene_kind(scene, Kind::vertex_edge, settings, stated));
  if (fs::is_regular_file(directory / "vv.csv", unreadable))
    reports.push_back(run_scene_kind(scene, Kind::vertex_vertex, settings, stated));
  return reports;
}

// Readers name file and line in their message; other failures get the input.
void report_error(std::ostream& errors, const fs::path& input, const std::exception& error) {
  errors << "batchccd: error: ";
  if (dynamic_cast<const InputError*>(&error) == nullptr) errors << input.string() << ": ";
  errors << error.what() << '\n';
}

// Runs `step`; a failure is reported and marks the outcome, and the caller
// goes on with the next input.
void run_guarded(const fs::path& input, RunOutcome& outcome, std::ostream& errors,
                 const std::function<void()>& step) {
  try {
    step();
  } catch (const std::exception& error) {
    report_error(errors, input, error);
    outcome.any_error = true;
  }
}

}  // namespace

Kind kind_of_query_file(const fs::path& file, const std::optional<Kind>& fallback_kind) {
  if (auto named = kind_from_path(file)) return *named;
  if (fallback_kind) return *fallback_kind;
  throw InputError(file.string(), 0,
                   "the path names no kind (vertex-face/vf, edge-edge/ee, vertex-edge/ve or "
                   "vertex-vertex/vv): use --kind");
}

std::vector<FoundInput> find_inputs(const fs::path& input, const std::optional<Kind>& fallback_kind,
                                    std::ostream& notes) {
  // A shell glob over a data folder also names its LICENSE or README: a
  // plain file that is no CSV is passed over, said once, not an error.
  // (The error_code form: a path the system cannot even stat is an input
  // error thrown below.)
  std::error_code unreadable;
  if (fs::is_regular_file(input, unreadable) && input.extension() != ".csv") {
    notes << "note: " << input.string() << ": skipped, not a query file (*.csv) or a scene\n";
    return {};
  }
  if (!fs::exists(input)) throw InputError(input.string(), 0, "no such file or directory");
  if (is_scene_directory(input)) return {{input, true}};
  if (fs::is_directory(input)) return find_inputs_in_directory(input, fallback_kind);
  return {{input, false}};
}

RunOutcome run_inputs(const RunSettings& settings, std::ostream& errors) {
  RunOutcome outcome;
  for (const fs::path& input : settings.inputs) {
    std::vector<FoundInput> found;
    run_guarded(input, outcome, errors, [&] { found = find_inputs(input, settings.kind, errors); });
    for (const FoundInput& item : found) {
      run_guarded(item.path, outcome, errors, [&] {
        std::vector<InputReport> reports = item.is_scene ? run_scene(item.path, settings)
                                                         : run_query_file(item.path, settings);
        for (InputReport& report : reports) outcome.reports.push_back(std::move(report));
      });
    }
  }
  return outcome;
}

}  // namespace batchccd::cli

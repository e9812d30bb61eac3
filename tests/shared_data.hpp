#pragma once

// ../shared/data run through the library's own readers and batch calls, for
// the reference-data tests. Every *.csv under sample-queries (kind from its
// path) and every scene directory under scenes (its vf list, then its ee list).

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"

namespace batchccd::testing {

inline const std::filesystem::path kSharedData = BATCHCCD_SHARED_DATA;

inline bool shared_data_present() {
  return std::filesystem::is_directory(kSharedData / "sample-queries") &&
         std::filesystem::is_directory(kSharedData / "scenes");
}

// The one traversal of the reference data, each list sorted: every *.csv
// under sample-queries (its kind named by its path), and every scene
// directory under scenes. Empty where the data is absent.
inline std::vector<std::filesystem::path> shared_query_files() {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  if (!fs::is_directory(kSharedData / "sample-queries")) return files;
  for (const auto& entry : fs::recursive_directory_iterator(kSharedData / "sample-queries"))
    if (entry.path().extension() == ".csv") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

inline std::vector<std::filesystem::path> shared_scene_directories() {
  namespace fs = std::filesystem;
  std::vector<fs::path> scenes;
  if (!fs::is_directory(kSharedData / "scenes")) return scenes;
  for (const auto& entry : fs::directory_iterator(kSharedData / "scenes"))
    if (is_scene_directory(entry.path())) scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// One input and kind, run once.
struct DataRun {
  std::string input;
  Kind kind = Kind::vertex_face;
  std::vector<QueryResult> results;        // one per query, in file order
  std::optional<std::vector<bool>> truth;  // the file's, when it has one
  Counters counters;
  double seconds = 0;

  std::int64_t false_negatives() const { return errors(true); }
  std::int64_t false_positives() const { return errors(false); }

 private:
  std::int64_t errors(bool missed) const {
    std::int64_t count = 0;
    for (std::size_t i = 0; i < results.size(); ++i)
      count += truth->at(i) == missed && results[i].hit != missed;
    return count;
  }
};

template <class Call>
DataRun timed_run(std::string input, Kind kind, std::optional<std::vector<bool>> truth, Call call) {
  DataRun run{std::move(input), kind, {}, std::move(truth), {}, 0};
  const auto start = std::chrono::steady_clock::now();
  BatchResult result = call();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.results = std::move(result.results);
  run.counters = result.counters;
  if (run.truth) {
    EXPECT_EQ(run.results.size(), run.truth->size()) << run.input << " " << to_string(kind);
  }
  return run;
}

// Every input by `method` with `options` (per-candidate results and query
// timing on) and the filter stages of `stages`.
inline std::vector<DataRun> run_shared_data(const lab::Method& method, Options options = {},
                                            lab::Settings stages = {}) {
  options = method.applied_to(options);
  lab::Settings settings = stages;
  settings.baseline = method.baseline;
  namespace fs = std::filesystem;
  options.per_candidate_results = true;
  options.time_queries = true;
  std::vector<DataRun> runs;
  for (const fs::path& file : shared_query_files()) {
    const std::optional<Kind> kind = kind_from_path(file);
    EXPECT_TRUE(kind.has_value()) << file << " names no kind";
    if (!kind) continue;
    const QueryFile queries = read_query_csv(file, *kind);
    runs.push_back(timed_run(file.string(), *kind, queries.truth,
                             [&] { return lab::batch_ccd(*kind, queries.queries, options, settings); }));
  }
  for (const fs::path& directory : shared_scene_directories()) {
    const Scene scene = read_scene(directory);
    const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      Options one_kind = options;
      one_kind.vertex_face = kind == Kind::vertex_face;
      one_kind.edge_edge = kind == Kind::edge_edge;
      one_kind.vertex_edge = one_kind.vertex_vertex = false;  // their results would follow this kind's
      runs.push_back(timed_run(directory.string(), kind,
                               one_kind.vertex_face ? scene.vertex_face_truth : scene.edge_edge_truth,
                               [&] { return lab::mesh_ccd(mesh, scene.candidates, one_kind, settings); }));
    }
  }
  return runs;
}

}  // namespace batchccd::testing

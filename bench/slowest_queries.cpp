// The slowest single queries of each mode over the stiff and extreme suite
// and ../shared/data (sample queries and the scenes' candidate lists), each
// query timed alone through query_ccd (filters, solver, exact stage) as the
// best of three runs on one thread. Prints the five slowest per mode with
// where they come from, how many take longer than 0.5 ms, and what the
// queries the exact stage settled cost (their count, mean and slowest),
// with the exact stage as it is and with its integers alone
// (lab::Settings::expansion_stage off), in the same run. Asserts nothing.
// Usage: batchccd_slowest_queries [shared-data-dir]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "extreme_suite.hpp"
#include "shared_data_inputs.hpp"

namespace {

using namespace batchccd;
namespace fs = std::filesystem;

struct Input {
  std::string name;
  Kind kind;
  std::vector<Query> queries;
};

struct Timing {
  double seconds;
  const Input* input;
  std::size_t index;
  bool hit;
  bool escalated;
};

double best_of_three(Kind kind, const Query& query, const Options& options, const lab::Settings& settings,
                     QueryResult& result) {
  double best = 1e300;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    result = lab::query_ccd(kind, query, options, settings);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

std::vector<Input> inputs(const fs::path& data) {
  std::vector<Input> all;
  for (scenes::ExtremeCategory& category : scenes::extreme_categories())
    all.push_back({"extreme: " + category.name, category.kind, std::move(category.queries)});
  const scenes::SharedDataInputs shared = scenes::shared_data_inputs(data);
  for (const fs::path& file : shared.query_files) {
    const Kind kind = *kind_from_path(file);
    all.push_back({fs::relative(file, data).string(), kind, read_query_csv(file, kind).queries});
  }
  for (const fs::path& directory : shared.scenes) {
    const Scene scene = read_scene(directory);
    const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
    Input vertex_face{fs::relative(directory, data).string(), Kind::vertex_face, {}};
    Input edge_edge{vertex_face.name, Kind::edge_edge, {}};
    for (const auto& candidate : scene.candidates.vertex_face)
      vertex_face.queries.push_back(vertex_face_query(mesh, candidate));
    for (const auto& candidate : scene.candidates.edge_edge)
      edge_edge.queries.push_back(edge_edge_query(mesh, candidate));
    all.push_back(std::move(vertex_face));
    all.push_back(std::move(edge_edge));
  }
  return all;
}

// Times every query alone in one mode and prints what the header says.
void report(const std::vector<Input>& all, std::size_t count, Mode mode, bool expansions) {
  const lab::Settings settings{.expansion_stage = expansions};
  std::vector<Timing> timings;
  double total = 0;
  for (const Input& input : all)
    for (std::size_t i = 0; i < input.queries.size(); ++i) {
      QueryResult result;
      const Options options{.mode = mode, .threads = 1};
      const double seconds = best_of_three(input.kind, input.queries[i], options, settings, result);
      total += seconds;
      const bool escalated =
          lab::batch_ccd(input.kind, std::span(&input.queries[i], 1), options, settings).counters.exact_escalations > 0;
      timings.push_back({seconds, &input, i, result.hit, escalated});
    }
  std::sort(timings.begin(), timings.end(), [](const Timing& a, const Timing& b) { return a.seconds > b.seconds; });
  const auto slow = std::count_if(timings.begin(), timings.end(), [](const Timing& t) { return t.seconds > 0.5e-3; });
  std::printf("\n%s, exact stage %s: mean %.2f us, over 0.5 ms: %td; slowest:\n", to_string(mode),
              expansions ? "as it is" : "integers alone", total / static_cast<double>(count) * 1e6, slow);
  for (std::size_t k = 0; k < std::min<std::size_t>(5, timings.size()); ++k)
    std::printf("  %9.1f us  %-5s %-9s %s %s #%zu\n", timings[k].seconds * 1e6, timings[k].hit ? "hit" : "miss",
                timings[k].escalated ? "escalated" : "", timings[k].input->name.c_str(),
                to_string(timings[k].input->kind), timings[k].index);
  std::size_t escalated = 0;
  double escalated_total = 0, escalated_max = 0;
  for (const Timing& timing : timings)
    if (timing.escalated) {
      ++escalated;
      escalated_total += timing.seconds;
      escalated_max = std::max(escalated_max, timing.seconds);
    }
  std::printf("  escalated to the exact stage: %zu queries, mean %.1f us, slowest %.1f us\n", escalated,
              escalated ? escalated_total / static_cast<double>(escalated) * 1e6 : 0.0, escalated_max * 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path data = argc > 1 ? fs::path(argv[1]) : fs::path(BATCHCCD_SHARED_DATA);
  const std::vector<Input> all = inputs(data);
  std::size_t count = 0;
  for (const Input& input : all) count += input.queries.size();
  std::printf("%zu queries (stiff and extreme suite, %s), each the best of 3 runs, one thread\n", count,
              data.string().c_str());
  for (const Mode mode : {Mode::conservative, Mode::exact})
    for (const bool expansions : {true, false}) report(all, count, mode, expansions);
  return 0;
}

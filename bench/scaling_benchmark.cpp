// Thread scaling of whole batch calls (conservative mode, best instruction
// set): 1 thread against 2 (and more where the machine has them), on the
// built-in cloth scene's candidates (mesh and its positions cache-resident,
// index lists streamed) and on the same candidates as raw queries (192 bytes
// each, streamed from memory: bandwidth, not cores, is the limit there).
//
//   build/bench/batchccd_scaling_benchmark
//
// After the table it prints each suite's candidates per second at N threads
// over 1 thread, from the same run (the medians with --benchmark_repetitions;
// --benchmark_enable_random_interleaving=true spreads a noisy machine's
// drift over all thread counts).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "broad_phase.hpp"
#include "scenes.hpp"

namespace batchccd {
namespace {

struct Workload {
  scenes::MovingMesh mesh;
  Candidates candidates;
  std::vector<Query> edge_edge_queries;
};

// About 2.2 million candidates (resolution 96).
const Workload& workload() {
  static const Workload data = [] {
    Workload w;
    w.mesh = scenes::cloth_scene({.resolution = 96});
    const MeshView view = w.mesh.view();
    w.candidates = scenes::swept_box_candidates(view, scenes::mean_edge_length(view));
    for (const auto& pair : w.candidates.edge_edge)
      w.edge_edge_queries.push_back(batchccd::edge_edge_query(view, pair));
    return w;
  }();
  return data;
}

Options with_threads(const benchmark::State& state) {
  Options options;
  options.threads = static_cast<int>(state.range(0));
  options.per_candidate_results = false;  // the earliest TOI and counters only
  return options;
}

void mesh_scene(benchmark::State& state) {
  const Workload& w = workload();
  const Options options = with_threads(state);
  BatchResult result;
  for (auto _ : state) {
    result = mesh_ccd(w.mesh.view(), w.candidates, options);
    benchmark::DoNotOptimize(result.earliest_toi);
  }
  state.SetItemsProcessed(state.iterations() * result.counters.candidates);
  state.counters["threads"] = static_cast<double>(options.threads);
}

void streamed_queries(benchmark::State& state) {
  const Workload& w = workload();
  const Options options = with_threads(state);
  BatchResult result;
  for (auto _ : state) {
    result = batch_ccd(Kind::edge_edge, w.edge_edge_queries, options);
    benchmark::DoNotOptimize(result.earliest_toi);
  }
  state.SetItemsProcessed(state.iterations() * result.counters.candidates);
  state.SetBytesProcessed(state.iterations() * result.counters.candidates *
                          static_cast<std::int64_t>(sizeof(Query)));
}

void thread_counts(benchmark::internal::Benchmark* b) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int threads = 1; threads <= std::max(2, cores); threads *= 2) b->Arg(threads);
  b->UseRealTime();  // several threads: wall time is what a caller waits
}

BENCHMARK(mesh_scene)->Apply(thread_counts)->Unit(benchmark::kMillisecond);
BENCHMARK(streamed_queries)->Apply(thread_counts)->Unit(benchmark::kMillisecond);

// The console table, and each run's rate kept by suite and thread count.
class ScalingReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      // With repetitions the median is reported last, so it is what stays.
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.error_occurred || (run.run_type != Run::RT_Iteration && !median)) continue;
      const std::string name = run.benchmark_name();  // "suite/threads/real_time"
      const auto slash = name.find('/');
      const auto found = run.counters.find("items_per_second");
      if (slash == std::string::npos || found == run.counters.end()) continue;
      rates_[name.substr(0, slash)][std::stoi(name.substr(slash + 1))] = found->second.value;
    }
  }

  void print_ratios() const {
    for (const auto& [suite, by_threads] : rates_) {
      const auto one = by_threads.find(1);
      if (one == by_threads.end() || one->second <= 0) continue;
      for (const auto& [threads, rate] : by_threads)
        if (threads != 1)
          std::printf("%s: %d threads / 1 thread = %.2fx (%.3g vs %.3g candidates/s)\n", suite.c_str(),
                      threads, rate / one->second, rate, one->second);
    }
  }

 private:
  std::map<std::string, std::map<int, double>> rates_;
};

}  // namespace
}  // namespace batchccd

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  batchccd::ScalingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print_ratios();
  benchmark::Shutdown();
  return 0;
}

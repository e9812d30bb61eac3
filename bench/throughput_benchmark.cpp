// Throughput of the lane filter and of whole calls (docs/design.md §10): the sign
// filter per instruction set against the scalar reference filter, against a
// plain read of the same bytes, and end to end against the unfiltered cubic
// solver. Candidates come from the built-in cloth scene's broad phase.
//
//   build/bench/batchccd_throughput_benchmark [--benchmark_filter=REGEX]
//
// One thread throughout (Options::threads = 1): the scaling suite is
// separate. Ratios are only meaningful within one run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "broad_phase.hpp"
#include "scenes.hpp"
#include "simd/filter.hpp"

namespace batchccd {
namespace {

struct ClothCandidates {
  scenes::MovingMesh mesh;
  Candidates candidates;
  std::vector<Query> vertex_face_queries;  // the same candidates as raw queries
};

const ClothCandidates& cloth() {
  static const ClothCandidates data = [] {
    ClothCandidates d;
    d.mesh = scenes::cloth_scene({});
    d.candidates = scenes::swept_box_candidates(d.mesh.view(), scenes::mean_edge_length(d.mesh.view()));
    for (const auto& pair : d.candidates.vertex_face)
      d.vertex_face_queries.push_back(batchccd::vertex_face_query(d.mesh.view(), pair));
    return d;
  }();
  return data;
}

// Raw queries repeated up to `count`: 4096 stay in cache, 2^20 (192 MiB) stream.
std::vector<Query> raw_queries(std::size_t count) {
  const auto& source = cloth().vertex_face_queries;
  std::vector<Query> queries(count);
  for (std::size_t i = 0; i < count; ++i) queries[i] = source[i % source.size()];
  return queries;
}

const std::vector<Query>& cached_queries() {
  static const std::vector<Query> queries = raw_queries(4096);
  return queries;
}
const std::vector<Query>& streamed_queries() {
  static const std::vector<Query> queries = raw_queries(std::size_t(1) << 20);
  return queries;
}

// Which filters a benchmark runs: its range(0) (0 the sign filter alone,
// 1 the separation filter alone, 2 every stage a call runs: the boxes, both
// filters, their pieces).
reference::FilterSettings settings(const benchmark::State& state) {
  const auto which = state.range(0);
  if (which == 2) return {};
  return {.sign = which == 0, .separation = which == 1, .pieces = 1, .swept_box = false};
}

void set_counters(benchmark::State& state, std::size_t candidates, double bytes_per_candidate,
                  std::size_t survivors) {
  const auto total = static_cast<std::int64_t>(candidates) * state.iterations();
  state.SetItemsProcessed(total);
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes_per_candidate * static_cast<double>(total)));
  state.counters["bytes_per_candidate"] = bytes_per_candidate;
  state.counters["survivor_fraction"] = static_cast<double>(survivors) / static_cast<double>(candidates);
}

// filter(begin, end) over [0, count) in the scheduler's batches, as a
// worker runs it; returns the survivors of all.
template <class Filter>
std::size_t in_batches(std::size_t count, const Filter& filter) {
  std::size_t kept = 0;
  for (std::size_t begin = 0; begin < count; begin += simd::kFilterBatch)
    kept += filter(begin, std::min(count, begin + simd::kFilterBatch));
  return kept;
}

// The certified filters over raw queries (192 bytes each).
void filter_raw(benchmark::State& state, Isa isa, const std::vector<Query>& queries) {
  const simd::FilterKernels& kernels = simd::filter_kernels(isa);
  std::vector<std::uint32_t> survivors(queries.size());
  std::vector<std::uint8_t> free_pieces(queries.size());
  const simd::RawQueries source = simd::raw_queries(Kind::vertex_face, queries.data(), queries.size());
  std::size_t kept = 0;
  for (auto _ : state) {
    simd::FilterCounts counts;
    kept = in_batches(queries.size(), [&](std::size_t begin, std::size_t end) {
      return kernels.raw(source, begin, end, settings(state), survivors.data(), free_pieces.data(), counts);
    });
    benchmark::DoNotOptimize(kept);
  }
  set_counters(state, queries.size(), sizeof(Query), kept);
}

// A plain read of the same bytes: the memory system's own limit.
void streaming_read(benchmark::State& state, const std::vector<Query>& queries) {
  const auto* words = reinterpret_cast<const std::uint64_t*>(queries.data());
  const std::size_t count = queries.size() * sizeof(Query) / sizeof(std::uint64_t);
  for (auto _ : state) {
    std::uint64_t mix = 0;
    for (std::size_t i = 0; i < count; ++i) mix ^= words[i];
    benchmark::DoNotOptimize(mix);
  }
  set_counters(state, queries.size(), sizeof(Query), queries.size());
}

// The filter over the mesh's index lists: positions stay in cache, the
// index list streams (8 bytes a vertex-face pair, 16 an edge-edge one).
void filter_mesh(benchmark::State& state, Isa isa, Kind kind) {
  const simd::FilterKernels& kernels = simd::filter_kernels(isa);
  const ClothCandidates& data = cloth();
  const MeshView view = data.mesh.view();
  const simd::PackedPositions packed(view.positions_t0, view.positions_t1);
  const simd::MeshPositions positions = packed.view();
  const simd::PackedFaces faces(view.faces, view.faces.rows());
  const std::size_t count = kind == Kind::vertex_face ? data.candidates.vertex_face.size()
                                                      : data.candidates.edge_edge.size();
  std::vector<std::uint32_t> survivors(count);
  std::vector<std::uint8_t> free_pieces(count);
  std::size_t kept = 0;
  simd::FilterCounts counts;
  for (auto _ : state) {
    kept = in_batches(count, [&](std::size_t begin, std::size_t end) {
      return kind == Kind::vertex_face
                 ? kernels.vertex_face({positions, faces.view(), data.candidates.vertex_face.data()}, begin,
                                       end, settings(state), survivors.data(), free_pieces.data(), counts)
                 : kernels.edge_edge({positions, data.candidates.edge_edge.data()}, begin, end,
                                     settings(state), survivors.data(), free_pieces.data(), counts);
    });
    benchmark::DoNotOptimize(kept);
  }
  set_counters(state, count, kind == Kind::vertex_face ? 8.0 : 16.0, kept);
}

// A whole mesh call, one thread: filter, solver, results.
void end_to_end(benchmark::State& state, const lab::Method& method, Isa isa) {
  const ClothCandidates& data = cloth();
  Options options = method.applied_to({});
  options.isa = isa;
  options.threads = 1;
  BatchResult result;
  for (auto _ : state) {
    result = lab::mesh_ccd(data.mesh.view(), data.candidates, options, method.settings());
    benchmark::DoNotOptimize(result.earliest_toi);
  }
  const std::size_t count = data.candidates.vertex_face.size() + data.candidates.edge_edge.size();
  set_counters(state, count, 0, static_cast<std::size_t>(result.counters.solved));
  state.counters["hits"] = static_cast<double>(result.counters.hits);
}

void register_all() {
  // Every instruction set this build and processor offer (scalar, sse4,
  // avx2, avx512 on x86; scalar, neon on AArch64), each filter under its name.
  // Arg: 0 the sign filter alone, 1 the separation filter alone, 2 every stage.
  for (const Isa isa : available_isas()) {
    const std::string suffix = std::string("/") + to_string(isa);
    benchmark::RegisterBenchmark(("Filter/raw/cached" + suffix).c_str(),
                                 [isa = isa](benchmark::State& s) { filter_raw(s, isa, cached_queries()); })
        ->Arg(0)->Arg(2);
    benchmark::RegisterBenchmark(("Filter/raw/streamed" + suffix).c_str(),
                                 [isa = isa](benchmark::State& s) { filter_raw(s, isa, streamed_queries()); })
        ->Arg(0)->Arg(2);
    benchmark::RegisterBenchmark(("Filter/mesh_vf" + suffix).c_str(),
                                 [isa = isa](benchmark::State& s) { filter_mesh(s, isa, Kind::vertex_face); })
        ->Arg(0)->Arg(1)->Arg(2);
    benchmark::RegisterBenchmark(("Filter/mesh_ee" + suffix).c_str(),
                                 [isa = isa](benchmark::State& s) { filter_mesh(s, isa, Kind::edge_edge); })
        ->Arg(0)->Arg(1)->Arg(2);
  }
  benchmark::RegisterBenchmark("StreamingRead/cached", [](benchmark::State& s) { streaming_read(s, cached_queries()); });
  benchmark::RegisterBenchmark("StreamingRead/streamed", [](benchmark::State& s) { streaming_read(s, streamed_queries()); });
  benchmark::RegisterBenchmark("EndToEnd/cubic", [](benchmark::State& s) { end_to_end(s, lab::kCubic, Isa::scalar); });
  benchmark::RegisterBenchmark("EndToEnd/conservative/scalar", [](benchmark::State& s) { end_to_end(s, lab::kConservative, Isa::scalar); });
  benchmark::RegisterBenchmark("EndToEnd/conservative/auto", [](benchmark::State& s) { end_to_end(s, lab::kConservative, Isa::automatic); });
  benchmark::RegisterBenchmark("EndToEnd/fast/auto", [](benchmark::State& s) { end_to_end(s, lab::kFast, Isa::automatic); });
}

}  // namespace
}  // namespace batchccd

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  batchccd::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

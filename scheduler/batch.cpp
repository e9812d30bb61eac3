#include "batchccd/batch.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <vector>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/partitioner.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "mesh_validation.hpp"
#include "reference/reference.hpp"
#include "simd/filter.hpp"
#include "simd/sources.hpp"

namespace batchccd {
namespace {

struct Partial {
  Counters counters;
  double earliest_toi = std::numeric_limits<double>::infinity();
};

// Candidates a worker filters at once: the survivor list stays in cache and
// the scheduler has enough pieces to balance two or more threads.
constexpr std::size_t kBatchSize = 2048;

void tally(const reference::Evaluation& e, Partial& partial) {
  Counters& c = partial.counters;
  c.solved += !e.culled && e.result.status == Status::ok;
  c.hits += e.result.hit;
  c.undecided += e.undecided;
  c.invalid += e.result.status != Status::ok;
  reference::count_exact_stage_and_time(e, c);
  if (e.result.hit) partial.earliest_toi = std::min(partial.earliest_toi, e.result.toi);
}

// Evaluates candidates [0, count) of a source: the lane filter over batches,
// then the scalar path for each survivor, writing results[offset + i] when
// per-candidate results are asked for. Results land at fixed places and the
// reductions (sums, minimum) do not depend on order, so the outcome is the
// same for any thread count.
template <class Source>
void run_source(const Source& source, std::size_t count, simd::FilterFunction<Source> filter,
                const Options& options, std::size_t offset, BatchResult& batch) {
  const bool filtered = options.mode != Mode::cubic;  // the baseline runs unfiltered
  const reference::FilterSettings settings = reference::filter_settings(options);
  tbb::combinable<Partial> partials;
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> survivor_buffers;
  auto work = [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, count, kBatchSize),
        [&](const tbb::blocked_range<std::size_t>& range) {
          std::vector<std::uint32_t>& survivors = survivor_buffers.local();
          if (survivors.size() < range.size()) survivors.resize(std::max(range.size(), kBatchSize));
          std::size_t kept = range.size();
          simd::FilterCounts culls;
          if (filtered) {
            kept = filter(source, range.begin(), range.end(), settings, survivors.data(), culls);
          } else {
            std::iota(survivors.begin(), survivors.begin() + static_cast<std::ptrdiff_t>(kept), 0u);
          }
          Partial& partial = partials.local();
          partial.counters.candidates += static_cast<std::int64_t>(range.size());
          partial.counters.culled += static_cast<std::int64_t>(range.size() - kept);
          partial.counters.culled_by_sign += static_cast<std::int64_t>(culls.sign);
          partial.counters.culled_by_separation += static_cast<std::int64_t>(culls.separation);
          for (std::size_t j = 0; j < kept; ++j) {
            const std::size_t i = range.begin() + survivors[j];
            const reference::Evaluation e =
                reference::evaluate_query(source.kind, simd::query_at(source, i), options, filtered);
            tally(e, partial);
            if (options.per_candidate_results) batch.results[offset + i] = e.result;
          }
        },
        tbb::simple_partitioner());
  };
  if (options.threads > 0) {
    tbb::task_arena arena(options.threads);
    arena.execute(work);
  } else {
    work();  // the caller's arena
  }
  partials.combine_each([&](const Partial& partial) {
    batch.counters += partial.counters;
    batch.earliest_toi = std::min(batch.earliest_toi, partial.earliest_toi);
  });
}

}  // namespace

Isa resolve_isa(Isa requested) { return simd::filter_kernels(requested).isa; }

std::vector<Isa> available_isas() {
  std::vector<Isa> isas;
  for (const Isa isa : {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512}) {
    try {
      simd::filter_kernels(isa);
      isas.push_back(isa);
    } catch (const std::invalid_argument&) {
      // not on this processor
    }
  }
  return isas;
}

BatchResult batch_ccd(Kind kind, std::span<const Query> queries, const Options& options) {
  const simd::FilterKernels& kernels = simd::filter_kernels(options.isa);
  BatchResult batch;
  if (options.per_candidate_results) batch.results.resize(queries.size());
  if (!queries.empty())
    run_source(simd::RawQueries{kind, queries.data()}, queries.size(), kernels.raw, options, 0, batch);
  return batch;
}

BatchResult mesh_ccd(const MeshView& mesh, const Candidates& candidates, const Options& options) {
  const simd::FilterKernels& kernels = simd::filter_kernels(options.isa);
  check_mesh(mesh, candidates);
  const std::size_t vertex_face = options.vertex_face ? candidates.vertex_face.size() : 0;
  const std::size_t edge_edge = options.edge_edge ? candidates.edge_edge.size() : 0;
  BatchResult batch;
  if (options.per_candidate_results) batch.results.resize(vertex_face + edge_edge);
  const simd::PackedPositions packed(mesh.positions_t0.data(), mesh.positions_t1.data(),
                                    mesh.positions_t0.rows());
  const simd::MeshPositions positions = packed.view();
  run_source(simd::MeshVertexFace{positions, mesh.faces.data(), mesh.faces.rows(),
                                  candidates.vertex_face.data()},
             vertex_face, kernels.vertex_face, options, 0, batch);
  run_source(simd::MeshEdgeEdge{positions, candidates.edge_edge.data()}, edge_edge,
             kernels.edge_edge, options, vertex_face, batch);
  return batch;
}

}  // namespace batchccd

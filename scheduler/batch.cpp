#include "batchccd/batch.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "mesh_validation.hpp"
#include "reference/reference.hpp"

namespace batchccd {
namespace {

struct Partial {
  Counters counters;
  double earliest_toi = std::numeric_limits<double>::infinity();
};

// Evaluates queries [0, count) of one kind, writing results[offset + i] when
// per-candidate results are asked for. query_at(i) builds the i-th query.
template <class QueryAt>
void run_queries(Kind kind, std::size_t count, const QueryAt& query_at, const Options& options,
                 std::size_t offset, BatchResult& batch) {
  tbb::combinable<Partial> partials;
  auto work = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        Partial& partial = partials.local();
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const reference::Evaluation e =
                              reference::evaluate_query(kind, query_at(i), options);
                          Counters& c = partial.counters;
                          ++c.candidates;
                          c.culled += e.culled;
                          c.solved += !e.culled && e.result.status == Status::ok;
                          c.hits += e.result.hit;
                          c.undecided += e.undecided;
                          c.invalid += e.result.status != Status::ok;
                          if (e.result.hit)
                            partial.earliest_toi = std::min(partial.earliest_toi, e.result.toi);
                          if (options.per_candidate_results) batch.results[offset + i] = e.result;
                        }
                      });
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

Query gather(const MeshView& mesh, const std::array<int, 4>& vertices) {
  Query query;
  for (int k = 0; k < 4; ++k) {
    query.points[k] = mesh.positions_t0.row(vertices[k]).transpose();
    query.points[k + 4] = mesh.positions_t1.row(vertices[k]).transpose();
  }
  return query;
}

}  // namespace

Isa resolve_isa(Isa requested) {
  // Only the scalar reference path exists so far; the lane kernels come with
  // the SIMD issue.
  if (requested == Isa::automatic || requested == Isa::scalar) return Isa::scalar;
  throw std::invalid_argument(std::string("instruction set ") + to_string(requested) +
                              " is not available in this build (available: scalar)");
}

BatchResult batch_ccd(Kind kind, std::span<const Query> queries, const Options& options) {
  resolve_isa(options.isa);
  BatchResult batch;
  if (options.per_candidate_results) batch.results.resize(queries.size());
  run_queries(kind, queries.size(), [&](std::size_t i) -> const Query& { return queries[i]; },
              options, 0, batch);
  return batch;
}

BatchResult mesh_ccd(const MeshView& mesh, const Candidates& candidates, const Options& options) {
  resolve_isa(options.isa);
  check_mesh(mesh, candidates);
  const std::size_t vertex_face = options.vertex_face ? candidates.vertex_face.size() : 0;
  const std::size_t edge_edge = options.edge_edge ? candidates.edge_edge.size() : 0;
  BatchResult batch;
  if (options.per_candidate_results) batch.results.resize(vertex_face + edge_edge);
  run_queries(
      Kind::vertex_face, vertex_face,
      [&](std::size_t i) {
        const auto [vertex, face] = candidates.vertex_face[i];
        return gather(mesh, {vertex, mesh.faces(face, 0), mesh.faces(face, 1), mesh.faces(face, 2)});
      },
      options, 0, batch);
  run_queries(
      Kind::edge_edge, edge_edge, [&](std::size_t i) { return gather(mesh, candidates.edge_edge[i]); },
      options, vertex_face, batch);
  return batch;
}

}  // namespace batchccd

#include "batchccd/batch.hpp"
#include "batchccd/ipc_stepsize.hpp"
#include "batchccd/lab.hpp"
#include "batchccd/names.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <vector>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>
#include <tbb/partitioner.h>
#include <tbb/parallel_for.h>

#include "arena.hpp"
#include "horizons.hpp"
#include "mesh_validation.hpp"
#include "decider.hpp"
#include "ipc_rules.hpp"
#include "reference/reference.hpp"
#include "reference/scaled_query.hpp"
#include "separation_check.hpp"
#include "shrinking_window.hpp"
#include "simd/filter.hpp"
#include "simd/sources.hpp"

namespace batchccd {
namespace {

struct Partial {
  Counters counters;
  double earliest_toi = std::numeric_limits<double>::infinity();
  std::vector<Hit> hits;  // Options::hit_list, in the order found
};

// Survivors a worker solves at once (for_each_survivor).
constexpr std::size_t kSolverGrain = 8;

void tally(const reference::Evaluation& e, Partial& partial) {
  Counters& c = partial.counters;
  c.solved += !e.culled && e.result.status == Status::ok;
  c.hits += e.result.hit;
  c.undecided += e.undecided;
  c.invalid += e.result.status != Status::ok;
  reference::count_exact_stage_and_time(e, c);
  if (e.result.hit) partial.earliest_toi = std::min(partial.earliest_toi, e.result.toi);
}

// A call runs in two phases, each in the current arena. First the lane
// filters over every source, which keep their survivors and counts to
// themselves: a refusal on the way (an index out of range) leaves the
// caller's BatchResult as it was. Then the results: defaults for the culled
// candidates, the scalar path for the survivors. Results land at fixed
// places and the reductions (sums, minimum) do not depend on order, so the
// outcome is the same for any thread count.

// Each worker's Partial, by its slot in the current arena: storage the
// caller keeps (CallStorage), so that a repeated call allocates nothing.
class Partials {
 public:
  // Slots are never dropped: a call with fewer workers keeps the others'
  // lists for the next call with more.
  explicit Partials(std::vector<Partial>& slots) : slots_(slots) {
    const auto workers = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
    if (slots_.size() < workers) slots_.resize(workers);
    for (Partial& partial : slots_) {
      partial.counters = {};
      partial.earliest_toi = std::numeric_limits<double>::infinity();
      partial.hits.clear();
    }
  }
  // The calling worker's (a thread outside any arena, before the work
  // starts: the first slot, which no worker holds then).
  Partial& local() {
    const int slot = tbb::this_task_arena::current_thread_index();
    return slots_[slot >= 0 ? static_cast<std::size_t>(slot) : 0];
  }
  template <class F>
  void combine_each(const F& f) const {
    for (const Partial& partial : slots_) f(partial);
  }
  // Room for `hits` in every worker's list: the next call may find them
  // spread over the workers otherwise.
  void reserve_hits(std::size_t hits) {
    for (Partial& partial : slots_) partial.hits.reserve(hits);
  }

 private:
  std::vector<Partial>& slots_;
};

// A candidate the lane filters kept, and the pieces of its step they
// proved free of contact (reference::FilterVerdict::free_pieces).
struct Survivor {
  std::size_t candidate;
  std::uint8_t free_pieces;
  reference::FilterVerdict verdict() const { return {.free_pieces = free_pieces}; }
};

// What a call keeps for the next one on the same host thread, so that a
// frame loop allocates nothing once these have grown: the lanes' survivors
// batch by batch, each list's survivors, the workers' partial results, a
// mesh's packed rows and faces, its point candidates as edge pairs, and a
// 2D call's queries lifted.
struct CallStorage {
  // Room for the lanes' survivors of `count` candidates.
  void reserve_kept(std::size_t count) {
    if (kept_in_batch.size() < count) kept_in_batch.resize(count);
    if (free_in_batch.size() < count) free_in_batch.resize(count);
  }

  std::vector<std::uint32_t> kept_in_batch;  // the lanes' survivors, batch b's from b * kFilterBatch
  std::vector<std::uint8_t> free_in_batch;   // beside each, the pieces of its step proven free
  std::vector<std::size_t> kept_counts;      // how many each batch kept
  std::array<std::vector<Survivor>, 4> survivors;
  std::vector<Partial> partials;
  simd::PackedPositions packed;
  simd::PackedFaces faces;
  std::vector<std::array<int, 4>> point_pairs;
  std::vector<Query> lifted_queries;  // a 2D call's queries in the plane z = 0
  Horizons horizons;                        // packed rows over the part of the step a window leaves open
  std::vector<double> grown_separations;    // per-candidate separations plus the horizons' margin
  bool in_use = false;
};

// Runs `work(CallStorage&)` with the calling thread's storage, or with
// storage of its own where a call is already using that one (a call made
// from a task that TBB ran while the host thread waited in another).
template <class Work>
void with_call_storage(const Work& work) {
  thread_local CallStorage kept;
  if (kept.in_use) {
    CallStorage own;
    own.in_use = true;
    work(own);
    return;
  }
  kept.in_use = true;
  struct Release {
    CallStorage& storage;
    ~Release() { storage.in_use = false; }
  } release{kept};
  work(kept);
}

// A list's minimum separations: one for all, or one per candidate.
struct Separations {
  double all = 0;
  const double* each = nullptr;  // one per candidate, when not null
  bool any() const { return all > 0 || each != nullptr; }
  double at(std::size_t i) const { return each ? each[i] : all; }
};

// A batch's culls, `culled` in all and by filter, into `counters`.
void count_culls(std::size_t culled, const simd::FilterCounts& culls, Counters& counters) {
  counters.culled += static_cast<std::int64_t>(culled);
  counters.culled_by_sign += static_cast<std::int64_t>(culls.sign);
  counters.culled_by_separation += static_cast<std::int64_t>(culls.separation);
  counters.culled_by_pieces += static_cast<std::int64_t>(culls.pieces);
  counters.culled_by_swept_box += static_cast<std::int64_t>(culls.swept_box);
}

// The lane filters over candidates [0, count) of a source of `kind`'s
// candidates (a point kind's as edge-edge queries), in batches of
// kFilterBatch: the survivors' indices, in increasing order, into
// `survivors`.
template <class Source>
void filter_source(Kind kind, const Source& source, std::size_t count, simd::FilterFunction<Source> lanes,
                   const Options& options, const lab::Settings& lab, const Separations& separations,
                   CallStorage& storage, Partials& partials, std::vector<Survivor>& survivors) {
  reference::FilterSettings settings = reference::settings_for(kind, reference::filter_settings(options, lab));
  settings.within = separations.any();
  settings.min_distance = separations.all;
  settings.min_distances = separations.each;
  const std::size_t batches = (count + simd::kFilterBatch - 1) / simd::kFilterBatch;
  // A batch's lanes write within its own candidates' places (FilterFunction).
  storage.reserve_kept(count);
  if (storage.kept_counts.size() < batches) storage.kept_counts.resize(batches);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, batches, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t batch = range.begin(); batch < range.end(); ++batch) {
          const std::size_t begin = batch * simd::kFilterBatch, end = std::min(count, begin + simd::kFilterBatch);
          simd::FilterCounts culls;
          const std::size_t kept = lanes(source, begin, end, settings, storage.kept_in_batch.data() + begin,
                                         storage.free_in_batch.data() + begin, culls);
          storage.kept_counts[batch] = kept;
          count_culls(end - begin - kept, culls, partials.local().counters);
        }
      },
      tbb::simple_partitioner());
  std::size_t total = 0;
  for (std::size_t batch = 0; batch < batches; ++batch) total += storage.kept_counts[batch];
  survivors.resize(total);
  std::size_t next = 0;
  for (std::size_t batch = 0; batch < batches; ++batch) {
    const std::size_t begin = batch * simd::kFilterBatch;
    for (std::size_t j = 0; j < storage.kept_counts[batch]; ++j)
      survivors[next++] = {begin + storage.kept_in_batch[begin + j], storage.free_in_batch[begin + j]};
  }
}

// Only the earliest TOI is asked for (no per-candidate results, no hit
// list, located TOIs): the survivors can be asked in a shrinking window.
bool earliest_toi_only(const Options& options) {
  return !options.per_candidate_results && !options.hit_list && options.need_toi;
}

// Survivors in small pieces, in parallel: their costs vary by orders of
// magnitude and cluster where the meshes touch, so small pieces balance.
template <class Evaluate>
void for_each_survivor(const std::vector<Survivor>& survivors, Evaluate evaluate) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, survivors.size(), kSolverGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k < range.end(); ++k) evaluate(survivors[k]);
                    },
                    tbb::simple_partitioner());
}

// Results for candidates [0, count) of a source, at results[offset + i]
// when per-candidate results are asked for: the scalar path over
// `survivors` (nullptr: every candidate, the unfiltered baseline), defaults
// for the rest. With a `window` (only the earliest TOI asked for), each
// survivor is asked over the window (window_tmax), and none once a contact
// at 0 is known.
template <class Source>
void solve_source(const Source& source, std::size_t count, const std::vector<Survivor>* survivors,
                  const Options& options, const lab::Settings& lab, const Separations& separations,
                  std::size_t offset, BatchResult& batch, Partials& partials, ShrinkingWindow* window = nullptr) {
  const bool filtered = survivors != nullptr;
  // Candidate i, `kept` what the filters said of it (null: unfiltered).
  const auto evaluate = [&](std::size_t i, const reference::FilterVerdict* kept, Partial& partial) {
    Options own = options;  // a candidate's own separation
    own.min_distance = separations.at(i);
    const Query query = simd::query_at(source, i);
    if (window != nullptr) {
      if (!(window->earliest() > 0)) {  // closed: only bad input is still counted
        partial.counters.invalid += !reference::all_finite(query);
        return;
      }
      own.tmax = window_tmax(window->earliest(), options);
    }
    const reference::Evaluation e = reference::evaluate_query(source.kind, query, own, lab, kept);
    if (window != nullptr && e.result.hit) window->lower_to(e.result.toi);
    tally(e, partial);
    if (options.per_candidate_results) batch.results[offset + i] = e.result;
    if (options.hit_list && e.result.hit) partial.hits.push_back({offset + i, e.result.toi, e.result.status});
  };
  partials.local().counters.candidates += static_cast<std::int64_t>(count);
  if (!filtered) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, simd::kFilterBatch),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        Partial& partial = partials.local();
                        for (std::size_t i = range.begin(); i < range.end(); ++i) evaluate(i, nullptr, partial);
                      },
                      tbb::simple_partitioner());
    return;
  }
  // Defaults, in parallel (the storage may be the caller's from an earlier
  // call); the survivors' own results overwrite theirs below.
  if (options.per_candidate_results)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, simd::kFilterBatch),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        const auto first = batch.results.begin() + static_cast<std::ptrdiff_t>(offset);
                        std::fill(first + static_cast<std::ptrdiff_t>(range.begin()),
                                  first + static_cast<std::ptrdiff_t>(range.end()), QueryResult{});
                      });
  for_each_survivor(*survivors, [&](const Survivor& survivor) {
    const reference::FilterVerdict kept = survivor.verdict();
    evaluate(survivor.candidate, &kept, partials.local());
  });
}

void combine(Partials& partials, BatchResult& batch) {
  partials.combine_each([&](const Partial& partial) {
    batch.counters += partial.counters;
    batch.earliest_toi = std::min(batch.earliest_toi, partial.earliest_toi);
    batch.hits.insert(batch.hits.end(), partial.hits.begin(), partial.hits.end());
  });
  partials.reserve_hits(batch.hits.size());
}

// Workers find hits in any order; the list is in candidate order.
void sort_hits(BatchResult& batch) {
  std::sort(batch.hits.begin(), batch.hits.end(),
            [](const Hit& a, const Hit& b) { return a.candidate < b.candidate; });
}

}  // namespace

Counters& Counters::operator+=(const Counters& other) {
  candidates += other.candidates;
  culled += other.culled;
  culled_by_sign += other.culled_by_sign;
  culled_by_separation += other.culled_by_separation;
  culled_by_pieces += other.culled_by_pieces;
  culled_by_swept_box += other.culled_by_swept_box;
  solved += other.solved;
  hits += other.hits;
  undecided += other.undecided;
  invalid += other.invalid;
  exact_escalations += other.exact_escalations;
  max_query_seconds = std::max(max_query_seconds, other.max_query_seconds);
  solved_seconds += other.solved_seconds;
  escalated_seconds += other.escalated_seconds;
  return *this;
}

Isa resolve_isa(Isa requested) { return simd::filter_kernels(requested).isa; }

std::vector<Isa> available_isas() {
  std::vector<Isa> isas;
  for (const auto& [name, isa] : isa_names()) {  // scalar first, then the vector sets
    if (isa == Isa::automatic) continue;
    try {
      simd::filter_kernels(isa);
      isas.push_back(isa);
    } catch (const std::invalid_argument&) {
      // not on this processor
    }
  }
  return isas;
}

// Empties `out` for a call of `count` candidates, keeping its storage.
void reset(BatchResult& out, std::size_t count, const Options& options) {
  out.results.resize(options.per_candidate_results ? count : 0);
  out.hits.clear();
  out.earliest_toi = std::numeric_limits<double>::infinity();
  out.counters = {};
}

// The separations of one list: checked (length, values) and wrapped.
Separations separations_of(std::span<const double> each, std::size_t count, const char* list,
                           const Options& options, const lab::Settings& lab) {
  if (each.empty()) return {options.min_distance, nullptr};
  if (each.size() != count)
    throw std::invalid_argument(std::string("batchccd: ") + list + " min_distances has " +
                                std::to_string(each.size()) + " values for " + std::to_string(count) +
                                " candidates");
  for (std::size_t i = 0; i < each.size(); ++i)
    if (const char* expected = separation_problem(each[i], decider_of(options, lab))) {
      std::ostringstream message;  // the value as the caller wrote it: -1, not -1.000000
      message << "batchccd: " << list << " candidate " << i << ": min_distance must be " << expected << ", got "
              << each[i];
      throw std::invalid_argument(message.str());
    }
  // Separation 0 for every candidate is the call without a separation: the
  // filters' separation variants would change the fast baseline's answers.
  if (std::all_of(each.begin(), each.end(), [](double s) { return s == 0; })) return {0, nullptr};
  return {0, each.data()};
}

namespace {

// A raw-query call in the calling thread's storage, the options checked.
void batch_in(Kind kind, std::span<const Query> queries, const Separations& separations, const Options& options,
              const lab::Settings& lab, CallStorage& storage, BatchResult& out) {
  const simd::FilterKernels& kernels = simd::filter_kernels(options.isa);
  const bool filtered = decider_of(options, lab) != Decider::cubic;  // the baseline runs unfiltered
  const simd::RawQueries source =
      simd::raw_queries(reference::evaluated_kind(kind), queries.data(), queries.size());
  in_arena(options.threads, [&] {
    Partials partials(storage.partials);
    std::vector<Survivor>& survivors = storage.survivors[0];
    if (filtered)
      filter_source(kind, source, queries.size(), kernels.raw, options, lab, separations, storage, partials,
                    survivors);
    reset(out, queries.size(), options);
    ShrinkingWindow window(options.tmax);
    solve_source(source, queries.size(), filtered ? &survivors : nullptr, options, lab, separations, 0, out,
                 partials, filtered && earliest_toi_only(options) ? &window : nullptr);
    combine(partials, out);
  });
  sort_hits(out);
}

}  // namespace

void lab::batch_ccd(Kind kind, std::span<const Query> queries, std::span<const double> min_distances,
                    const Options& options, const Settings& lab, BatchResult& out) {
  validate(options, lab);
  const Separations separations =
      separations_of(min_distances, queries.size(), batchccd::to_string(kind), options, lab);
  with_call_storage([&](CallStorage& storage) { batch_in(kind, queries, separations, options, lab, storage, out); });
}

void lab::batch_ccd(Kind kind, std::span<const Query2D> queries, std::span<const double> min_distances,
                    const Options& options, const Settings& lab, BatchResult& out) {
  validate(options, lab);
  const Separations separations =
      separations_of(min_distances, queries.size(), batchccd::to_string(kind), options, lab);
  simd::filter_kernels(options.isa);  // refuses an unavailable ISA before any work
  with_call_storage([&](CallStorage& storage) {
    std::vector<Query>& in_plane = storage.lifted_queries;
    in_plane.resize(queries.size());
    in_arena(options.threads, [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size(), simd::kFilterBatch),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i) in_plane[i] = lifted(queries[i]);
                        });
    });
    batch_in(kind, in_plane, separations, options, lab, storage, out);
  });
}

BatchResult lab::batch_ccd(Kind kind, std::span<const Query> queries, const Options& options,
                           const Settings& lab) {
  BatchResult batch;
  batch_ccd(kind, queries, {}, options, lab, batch);
  return batch;
}

void batch_ccd(Kind kind, std::span<const Query> queries, std::span<const double> min_distances,
               const Options& options, BatchResult& out) {
  lab::batch_ccd(kind, queries, min_distances, options, {}, out);
}

void batch_ccd(Kind kind, std::span<const Query> queries, const Options& options, BatchResult& out) {
  lab::batch_ccd(kind, queries, {}, options, {}, out);
}

BatchResult batch_ccd(Kind kind, std::span<const Query> queries, const Options& options) {
  return lab::batch_ccd(kind, queries, options, {});
}

void batch_ccd(Kind kind, std::span<const Query2D> queries, std::span<const double> min_distances,
               const Options& options, BatchResult& out) {
  lab::batch_ccd(kind, queries, min_distances, options, {}, out);
}

void batch_ccd(Kind kind, std::span<const Query2D> queries, const Options& options, BatchResult& out) {
  lab::batch_ccd(kind, queries, {}, options, {}, out);
}

BatchResult batch_ccd(Kind kind, std::span<const Query2D> queries, const Options& options) {
  BatchResult batch;
  batch_ccd(kind, queries, options, batch);
  return batch;
}

namespace {

// Point-edge and point-point candidates as the edge-edge candidates they
// are (Query's layout): the point a zero-length edge. Into `pairs`, whose
// storage is kept.
void as_edge_edge(const CandidateLists& candidates, const Options& options, std::vector<std::array<int, 4>>& pairs) {
  pairs.clear();
  if (options.vertex_edge)
    for (const auto& [vertex, e0, e1] : candidates.vertex_edge) pairs.push_back({vertex, vertex, e0, e1});
  if (options.vertex_vertex)
    for (const auto& [p, q] : candidates.vertex_vertex) pairs.push_back({p, p, q, q});
}

// A mesh call's four lists, packed for the lanes: where each list's
// candidates come from and how many there are (0 when Options switches the
// list off).
struct MeshSources {
  const simd::MeshVertexFace& vertex_face;
  const simd::MeshEdgeEdge& edge_edge;
  const simd::MeshEdgeEdge& vertex_edge;
  const simd::MeshEdgeEdge& vertex_vertex;
  std::array<std::size_t, 4> counts;
};

// Checks the mesh (all but the ids of the lists in `filtered`, which the
// lane filters check on the way), packs the positions, faces and point
// candidates into the calling thread's storage, then
// `then(const MeshSources&, CallStorage&)` in the arena of Options::threads.
template <class Then>
void with_mesh_sources(const MeshView& mesh, const CandidateLists& candidates, const Options& options,
                       bool filtered, Then then) {
  const std::array<std::size_t, 4> counts{options.vertex_face ? candidates.vertex_face.size() : 0,
                                          options.edge_edge ? candidates.edge_edge.size() : 0,
                                          options.vertex_edge ? candidates.vertex_edge.size() : 0,
                                          options.vertex_vertex ? candidates.vertex_vertex.size() : 0};
  with_call_storage([&](CallStorage& storage) {
    in_arena(options.threads, [&] {
      check_mesh(mesh, candidates, {.vertex_face = !filtered || !options.vertex_face,
                                    .edge_edge = !filtered || !options.edge_edge,
                                    .vertex_edge = !filtered || !options.vertex_edge,
                                    .vertex_vertex = !filtered || !options.vertex_vertex});
      simd::PackedPositions& packed = storage.packed;
      packed.resize(mesh.positions_t0.rows());
      tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, mesh.positions_t0.rows(), 1 << 14),
                        [&](const tbb::blocked_range<std::int64_t>& rows) {
                          packed.pack(mesh.positions_t0, mesh.positions_t1, rows.begin(), rows.end());
                        });
      // Faces only where the vertex-face list is read.
      storage.faces.assign(mesh.faces, counts[0] > 0 ? mesh.faces.rows() : 0);
      as_edge_edge(candidates, options, storage.point_pairs);
      const std::array<int, 4>* point_pairs = storage.point_pairs.data();
      const simd::MeshVertexFace vertex_face{packed.view(), storage.faces.view(), candidates.vertex_face.data()};
      const simd::MeshEdgeEdge edge_edge{packed.view(), candidates.edge_edge.data()};
      const simd::MeshEdgeEdge vertex_edge{packed.view(), point_pairs};
      const simd::MeshEdgeEdge vertex_vertex{packed.view(), point_pairs + counts[2]};
      then(MeshSources{vertex_face, edge_edge, vertex_edge, vertex_vertex, counts}, storage);
    });
  });
}

// Runs `filters()`, which may meet an id out of range, then names the
// first bad id (check_mesh) in the exception the caller gets.
template <class Filters>
void naming_bad_ids(const MeshView& mesh, const CandidateLists& candidates, const Filters& filters) {
  try {
    filters();
  } catch (const simd::IndexOutOfRange&) {
    check_mesh(mesh, candidates);
    throw std::logic_error("mesh_ccd: a filter found an index out of range that check_mesh did not");
  }
}

// The four lists' separations, checked.
std::array<Separations, 4> list_separations(const CandidateLists& candidates, const MinDistances& min_distances,
                                            const Options& options, const lab::Settings& lab) {
  return {separations_of(min_distances.vertex_face, candidates.vertex_face.size(), "vertex-face", options, lab),
          separations_of(min_distances.edge_edge, candidates.edge_edge.size(), "edge-edge", options, lab),
          separations_of(min_distances.vertex_edge, candidates.vertex_edge.size(), "vertex-edge", options, lab),
          separations_of(min_distances.vertex_vertex, candidates.vertex_vertex.size(), "vertex-vertex", options,
                         lab)};
}

// A mesh call's four lists once the lane filters have run: the sources,
// their separations, and their survivors (all of them for the unfiltered
// baseline: `filtered` false).
struct FilteredMesh {
  const MeshSources& sources;
  std::array<Separations, 4> separations;
  std::array<std::vector<Survivor>, 4>& survivors;
  bool filtered;
};

// Checks the mesh and the options, packs the positions, runs the lane
// filters over every list, then `then(FilteredMesh&, Partials&)`, all in
// the arena of Options::threads. A refusal leaves the caller's results as
// they were.
template <class Then>
void filter_mesh(const MeshView& mesh, const CandidateLists& candidates, const MinDistances& min_distances,
                 const Options& options, const lab::Settings& lab, Then then) {
  validate(options, lab);
  const simd::FilterKernels& kernels = simd::filter_kernels(options.isa);
  const bool filtered = decider_of(options, lab) != Decider::cubic;  // the baseline runs unfiltered
  const std::array<Separations, 4> separations = list_separations(candidates, min_distances, options, lab);
  with_mesh_sources(mesh, candidates, options, filtered, [&](const MeshSources& sources, CallStorage& storage) {
    const auto& counts = sources.counts;
    Partials partials(storage.partials);
    std::array<std::vector<Survivor>, 4>& survivors = storage.survivors;
    if (filtered)
      naming_bad_ids(mesh, candidates, [&] {
        filter_source(Kind::vertex_face, sources.vertex_face, counts[0], kernels.vertex_face, options, lab,
                      separations[0], storage, partials, survivors[0]);
        filter_source(Kind::edge_edge, sources.edge_edge, counts[1], kernels.edge_edge, options, lab,
                      separations[1], storage, partials, survivors[1]);
        filter_source(Kind::vertex_edge, sources.vertex_edge, counts[2], kernels.edge_edge, options, lab,
                      separations[2], storage, partials, survivors[2]);
        filter_source(Kind::vertex_vertex, sources.vertex_vertex, counts[3], kernels.edge_edge, options, lab,
                      separations[3], storage, partials, survivors[3]);
      });
    FilteredMesh lists{sources, separations, survivors, filtered};
    then(lists, partials);
  });
}

// One list of an earliest-TOI-only call, filtered and asked batch by batch
// (docs/design.md §12): each batch through the lane filters (`settings`,
// at `separations`) over the part of the step the window still asks about,
// then at once `decide(survivor, tmax, partial)` for each survivor, tmax the
// window's (`tmax_of(earliest)`). `narrow`: the filters may take the
// horizons' rows (certified filters only: they add a margin for the rows'
// rounding). Once the window is closed (a contact at 0) the batches left
// only have their ids checked and their candidates with a coordinate that
// is not finite counted as invalid: nothing lowers 0.
template <class Source, class TmaxOf, class Decide>
void filter_in_window(Kind kind, const Source& whole, std::size_t count, simd::FilterFunction<Source> lanes,
                      reference::FilterSettings settings, const Separations& separations, bool narrow,
                      CallStorage& storage, Partials& partials, ShrinkingWindow& window, const TmaxOf& tmax_of,
                      const Decide& decide) {
  settings = reference::settings_for(kind, settings);
  settings.within = separations.any();
  settings.min_distance = separations.all;
  settings.min_distances = separations.each;
  const std::size_t batches = (count + simd::kFilterBatch - 1) / simd::kFilterBatch;
  storage.reserve_kept(count);
  if (separations.each != nullptr && storage.grown_separations.size() < count)
    storage.grown_separations.resize(count);
  partials.local().counters.candidates += static_cast<std::int64_t>(count);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, batches, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t batch = range.begin(); batch < range.end(); ++batch) {
          const std::size_t begin = batch * simd::kFilterBatch, end = std::min(count, begin + simd::kFilterBatch);
          Counters& counters = partials.local().counters;
          if (!(window.earliest() > 0)) {  // closed
            for (std::size_t i = begin; i < end; ++i) simd::row_starts(whole, i);
            if (!whole.positions.finite)
              for (std::size_t i = begin; i < end; ++i)
                counters.invalid += !reference::all_finite(simd::query_at(whole, i));
            continue;
          }
          Source within = whole;
          reference::FilterSettings own = settings;
          if (narrow) {
            const Horizons::Rows rows = storage.horizons.over(tmax_of(window.earliest()));
            within.positions = rows.positions;
            if (rows.margin > 0) {
              // The margin added, rounded up: it may lie far below a separation's ulp.
              const auto grown = [&](double s) { return std::nextafter(s + rows.margin, HUGE_VAL); };
              own.within = true;
              own.min_distance = grown(separations.all);
              if (separations.each != nullptr) {
                for (std::size_t i = begin; i < end; ++i)
                  storage.grown_separations[i] = grown(separations.each[i]);
                own.min_distances = storage.grown_separations.data();
              }
            }
          }
          simd::FilterCounts culls;
          std::uint32_t* kept = storage.kept_in_batch.data() + begin;
          std::uint8_t* free_pieces = storage.free_in_batch.data() + begin;
          const std::size_t survivors = lanes(within, begin, end, own, kept, free_pieces, culls);
          count_culls(end - begin - survivors, culls, counters);
          // Pieces of a horizon's rows are pieces of its part of the step, not of the whole.
          const bool whole_step = within.positions.rows == whole.positions.rows;
          for (std::size_t j = 0; j < survivors; ++j) {
            const std::size_t i = begin + kept[j];
            if (!(window.earliest() > 0)) {
              counters.invalid += !reference::all_finite(simd::query_at(whole, i));
              continue;
            }
            decide(Survivor{i, whole_step ? free_pieces[j] : std::uint8_t{0}}, tmax_of(window.earliest()),
                   partials.local());
          }
        }
      },
      tbb::simple_partitioner());
}

}  // namespace

namespace {

// A filtered mesh call that asks only for the earliest TOI: every list
// filtered and asked batch by batch in one shrinking window
// (filter_in_window), each survivor as the scalar path asks it.
void mesh_earliest_toi(const MeshView& mesh, const CandidateLists& candidates, const MinDistances& min_distances,
                       const Options& options, const lab::Settings& lab, BatchResult& out) {
  validate(options, lab);
  const simd::FilterKernels& kernels = simd::filter_kernels(options.isa);
  const std::array<Separations, 4> separations = list_separations(candidates, min_distances, options, lab);
  const bool certified = decider_of(options, lab) != Decider::fast;
  ShrinkingWindow window(options.tmax);
  const auto tmax_of = [&](double earliest) { return window_tmax(earliest, options); };
  with_mesh_sources(mesh, candidates, options, true, [&](const MeshSources& sources, CallStorage& storage) {
    storage.horizons.reset(storage.packed);
    Partials partials(storage.partials);
    const auto& counts = sources.counts;
    const auto pass = [&](Kind kind, const auto& source, auto lanes, int list) {
      const Separations& separation = separations[static_cast<std::size_t>(list)];
      filter_in_window(kind, source, counts[static_cast<std::size_t>(list)], lanes,
                       reference::filter_settings(options, lab), separation, certified, storage, partials, window,
                       tmax_of, [&](const Survivor& survivor, double tmax, Partial& partial) {
                         Options own = options;
                         own.min_distance = separation.at(survivor.candidate);
                         own.tmax = tmax;
                         const reference::FilterVerdict kept = survivor.verdict();
                         const reference::Evaluation e = reference::evaluate_query(
                             source.kind, simd::query_at(source, survivor.candidate), own, lab, &kept);
                         if (e.result.hit) window.lower_to(e.result.toi);
                         tally(e, partial);
                       });
    };
    naming_bad_ids(mesh, candidates, [&] {
      pass(Kind::vertex_face, sources.vertex_face, kernels.vertex_face, 0);
      pass(Kind::edge_edge, sources.edge_edge, kernels.edge_edge, 1);
      pass(Kind::vertex_edge, sources.vertex_edge, kernels.edge_edge, 2);
      pass(Kind::vertex_vertex, sources.vertex_vertex, kernels.edge_edge, 3);
    });
    reset(out, counts[0] + counts[1] + counts[2] + counts[3], options);
    combine(partials, out);
  });
}

}  // namespace

void lab::mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const MinDistances& min_distances,
                   const Options& options, const Settings& lab, BatchResult& out) {
  if (decider_of(options, lab) != Decider::cubic && earliest_toi_only(options)) {
    mesh_earliest_toi(mesh, candidates, min_distances, options, lab, out);
    return;
  }
  filter_mesh(mesh, candidates, min_distances, options, lab, [&](FilteredMesh& lists, Partials& partials) {
    const MeshSources& sources = lists.sources;
    const auto& [vertex_face, edge_edge, vertex_edge, vertex_vertex] = sources.counts;
    reset(out, vertex_face + edge_edge + vertex_edge + vertex_vertex, options);
    const auto solved = [&](int list) { return lists.filtered ? &lists.survivors[list] : nullptr; };
    solve_source(sources.vertex_face, vertex_face, solved(0), options, lab, lists.separations[0], 0, out, partials);
    solve_source(sources.edge_edge, edge_edge, solved(1), options, lab, lists.separations[1], vertex_face, out,
                 partials);
    solve_source(sources.vertex_edge, vertex_edge, solved(2), options, lab, lists.separations[2],
                 vertex_face + edge_edge, out, partials);
    solve_source(sources.vertex_vertex, vertex_vertex, solved(3), options, lab, lists.separations[3],
                 vertex_face + edge_edge + vertex_edge, out, partials);
    combine(partials, out);
  });
  sort_hits(out);
}

BatchResult lab::mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const Options& options,
                          const Settings& lab) {
  BatchResult batch;
  mesh_ccd(mesh, candidates, MinDistances{}, options, lab, batch);
  return batch;
}

void mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const MinDistances& min_distances,
              const Options& options, BatchResult& out) {
  lab::mesh_ccd(mesh, candidates, min_distances, options, {}, out);
}

void mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const Options& options,
              BatchResult& out) {
  lab::mesh_ccd(mesh, candidates, MinDistances{}, options, {}, out);
}

BatchResult mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const Options& options) {
  return lab::mesh_ccd(mesh, candidates, options, {});
}

double ipc::collision_free_stepsize(const MeshView& mesh, const CandidateLists& candidates, double min_distance,
                                    double tolerance, long max_iterations, double conservative_rescaling,
                                    int threads) {
  constexpr const char* call = "batchccd::ipc::collision_free_stepsize";
  rules::require_arguments(call, min_distance, 1.0, tolerance, conservative_rescaling);
  // The lanes cull at the largest separation a candidate may ask for, plus
  // the distance tolerance: a culled candidate cannot even come within the
  // band where a per-query call may report a contact it did not prove.
  const Separations separation{min_distance + rules::kLargestRescalingSeparation + tolerance};
  Options options;
  options.threads = threads;
  const simd::FilterKernels& kernels = simd::filter_kernels(options.isa);
  const reference::FilterSettings settings = reference::filter_settings(options, {});
  ShrinkingWindow window(1.0);
  const auto tmax_of = [&](double earliest) { return ipc_window_tmax(earliest, conservative_rescaling); };
  with_mesh_sources(mesh, candidates, options, true, [&](const MeshSources& sources, CallStorage& storage) {
    storage.horizons.reset(storage.packed);
    Partials partials(storage.partials);
    const auto pass = [&](Kind kind, const auto& source, std::size_t count, auto lanes) {
      filter_in_window(kind, source, count, lanes, settings, separation, true, storage, partials, window, tmax_of,
                       [&](const Survivor& survivor, double tmax, Partial&) {
                         if (double toi = 1; rules::decide(kind, simd::query_at(source, survivor.candidate), toi,
                                                           min_distance, tmax, tolerance, max_iterations,
                                                           conservative_rescaling))
                           window.lower_to(toi);
                       });
    };
    naming_bad_ids(mesh, candidates, [&] {
      pass(Kind::vertex_face, sources.vertex_face, sources.counts[0], kernels.vertex_face);
      pass(Kind::edge_edge, sources.edge_edge, sources.counts[1], kernels.edge_edge);
      pass(Kind::vertex_edge, sources.vertex_edge, sources.counts[2], kernels.edge_edge);
      pass(Kind::vertex_vertex, sources.vertex_vertex, sources.counts[3], kernels.edge_edge);
    });
  });
  return window.earliest();
}

}  // namespace batchccd

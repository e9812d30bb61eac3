#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"
#include "batchccd/views.hpp"

namespace batchccd {

// What a batch call did, summed over the candidates it evaluated.
struct Counters {
  std::int64_t candidates = 0;  // queries evaluated
  std::int64_t culled = 0;      // removed by the lane filters
  std::int64_t culled_by_sign = 0;        // of those, by the sign filter (it sees what the boxes kept)
  std::int64_t culled_by_separation = 0;  // by the separation filter (it sees what the sign filter kept)
  std::int64_t culled_by_pieces = 0;      // by both over pieces of the step (4 pieces of the step)
  std::int64_t culled_by_swept_box = 0;   // by the swept boxes, the first filter (counted before the others)
  std::int64_t solved = 0;      // sent to the solver (candidates - culled)
  std::int64_t hits = 0;
  // Reported as hits without a decision: with min_distance > 0, the search
  // ran out of Options::max_iterations or (exact mode) the query lies in the
  // undecided band; or the exact stage reached its bound.
  std::int64_t undecided = 0;
  std::int64_t invalid = 0;     // Status::invalid_input
  // Exact and conservative modes: queries whose decision (or, exact mode,
  // TOI) the certified path left uncertain and exact arithmetic settled.
  std::int64_t exact_escalations = 0;
  // Wall-clock seconds of the slowest query the scalar path evaluated (the
  // lane filters' culls take nanoseconds), when Options::time_queries is set;
  // 0 otherwise. Adding counters keeps the larger.
  double max_query_seconds = 0;
  // With Options::time_queries, where a call's time goes: the seconds the
  // scalar path spent on the queries it evaluated (the filters' survivors;
  // summed over threads), and of those on the queries exact arithmetic
  // settled (exact_escalations). 0 otherwise. Adding counters sums them.
  double solved_seconds = 0;
  double escalated_seconds = 0;

  Counters& operator+=(const Counters& other);
};

// A candidate that hits, as Options::hit_list lists it.
struct Hit {
  std::size_t candidate = 0;  // its index in the order of BatchResult::results
  double toi = 0;
  Status status = Status::ok;  // invalid_input: a NaN or infinite coordinate (toi 0)
};

struct BatchResult {
  // One per candidate, in input order (a mesh call: vertex-face candidates
  // first, then edge-edge, vertex-edge and vertex-vertex). Empty when Options::per_candidate_results is false.
  std::vector<QueryResult> results;
  // The candidates that hit, in increasing candidate order, when
  // Options::hit_list is set (empty otherwise). Equal to the hits among
  // `results` whatever the thread count.
  std::vector<Hit> hits;
  // Earliest TOI over all candidates, +inf when nothing collides (0 when a
  // candidate has a NaN or infinite coordinate: see Status::invalid_input).
  double earliest_toi = std::numeric_limits<double>::infinity();
  Counters counters;
};

// Earliest-TOI-only calls: with Options::per_candidate_results and
// Options::hit_list false (and need_toi true), nothing but the earliest TOI
// is asked for, and a mesh call filters and asks its candidates batch by
// batch in a shrinking window: once a contact at t is known, a candidate is
// filtered over the first 1/16, 1/256 or 1/4096 of the step where t lies
// within it (certified modes), a survivor is asked over [0, t] only and its
// solver stops at t, and none is asked once t is 0 (docs/design.md §12).
// A raw-query call filters first and asks its survivors in the same window.
// earliest_toi is the minimum of what the per-candidate results would hold,
// for any thread count. The culls and the solver's counters -- solved,
// hits, undecided, exact_escalations and the times -- then count what the
// window let through, and depend on the thread count and on the order in
// which threads find contacts; candidates and invalid do not.

// The instruction set a batch call with `requested` runs: automatic picks
// the best this processor and build have. Throws std::invalid_argument when
// a forced one is not available.
Isa resolve_isa(Isa requested);

// Every instruction set a batch call can be forced to on this processor and
// build, the scalar reference path first.
std::vector<Isa> available_isas();

// Raw queries, all of one kind (Query's layout for that kind), evaluated in
// parallel (Options::threads).
// Per query, the promises of ccd.hpp. Throws std::invalid_argument when
// options.isa is not available or the options fail validate(); a query with a NaN or infinite coordinate
// only gets Status::invalid_input (hit, toi 0), the others are unaffected.
BatchResult batch_ccd(Kind kind, std::span<const Query> queries,
                      const Options& options = {});

// Raw queries of a 2D scene (Query2D): the same calls, options, promises
// and bad-input contract as for the queries lifted to the plane z = 0
// (batch_ccd above and below), where they are decided in the plane. The
// lifted queries are written once into the working storage each host thread
// keeps, so a frame loop still allocates nothing once it has grown.
BatchResult batch_ccd(Kind kind, std::span<const Query2D> queries, const Options& options = {});

// A mesh as a simulator holds it, viewed in place (views.hpp: double or
// float positions, any storage order or strides; nothing is copied, the
// arrays must outlive the view): vertex positions at t0 and t1 (n x 3, any
// length unit), triangles (m x 3 vertex ids) and, for candidates given by
// edge id (mesh_edges.hpp), edges (k x 2 vertex ids). Faces or edges a call
// does not read may be left empty.
// A 2D mesh has positions n x 2 at both times: every call, option and
// promise is the same, as for the mesh lifted to the plane z = 0. A 2D
// simulator's candidates are vertex-edge (a vertex against a boundary
// segment: the first contact of two 2D bodies is always one) and, at a
// separation, vertex-vertex; edge-edge (segments crossing) and vertex-face
// (a vertex inside a triangle) mean what they mean in the plane. Motion in
// a plane is decided there (docs/design.md §5a).
struct MeshView {
  PositionsView positions_t0;
  PositionsView positions_t1;
  IdsView faces{};
  IdsView edges{};
};

// Broad-phase candidates over a mesh by vertex ids, views of the caller's
// buffers (a std::vector, or any contiguous array of these rows).
struct CandidateLists {
  std::span<const std::array<int, 2>> vertex_face{};    // vertex id, face id
  std::span<const std::array<int, 4>> edge_edge{};      // a0, a1, b0, b1 vertex ids
  std::span<const std::array<int, 3>> vertex_edge{};    // vertex id, the edge's two vertex ids
  std::span<const std::array<int, 2>> vertex_vertex{};  // two vertex ids
};

// The same lists, owned: what a broad phase that keeps its own vectors
// fills. Converts to CandidateLists (only while it lives: not a temporary).
struct Candidates {
  std::vector<std::array<int, 2>> vertex_face{};
  std::vector<std::array<int, 4>> edge_edge{};
  std::vector<std::array<int, 3>> vertex_edge{};
  std::vector<std::array<int, 2>> vertex_vertex{};

  operator CandidateLists() const& { return {vertex_face, edge_edge, vertex_edge, vertex_vertex}; }  // NOLINT
  operator CandidateLists() const&& = delete;
};

// One minimum separation per candidate, replacing Options::min_distance
// (ipc-toolkit takes a fraction of each pair's initial distance). Views of
// the caller's buffers; each list's span is empty (Options::min_distance
// for all of that list) or exactly as long as the list. Every value must be
// >= 0 and finite.
struct MinDistances {
  std::span<const double> vertex_face{};
  std::span<const double> edge_edge{};
  std::span<const double> vertex_edge{};
  std::span<const double> vertex_vertex{};
};

// Bad input (tests/test_bad_input.cpp). The whole call is refused, before
// any result is written, with std::invalid_argument naming the first bad
// item, when the options fail validate(), positions_t0 and positions_t1
// differ in row count or in column count, positions with rows have neither
// 3 nor 2 columns, faces with rows do not have 3, or an index is out of range: a face's
// vertex, or a candidate's vertex or face id (negative or too large), in
// every candidate list, also one that Options switches off. An empty mesh
// (0 rows; default-constructed views too) is valid; with no
// candidates, as with no queries in batch_ccd, the result is empty
// (earliest_toi = +inf, counters 0). Per candidate (Status in query.hpp): a
// NaN or infinite position makes exactly the candidates that read that vertex
// invalid_input; faces with repeated vertices, a vertex of its own face and
// edges sharing a vertex are evaluated as their geometry.
BatchResult mesh_ccd(const MeshView& mesh, const CandidateLists& candidates,
                     const Options& options = {});

// The same calls writing into `out`, whose vectors keep their storage: a
// frame loop that passes one BatchResult every step allocates nothing once
// its results (and the working storage each host thread keeps for its
// calls) have grown to size, and they are written in parallel. What a call refuses (the exceptions above) leaves `out` as it was.
void batch_ccd(Kind kind, std::span<const Query> queries, const Options& options, BatchResult& out);
void batch_ccd(Kind kind, std::span<const Query2D> queries, const Options& options, BatchResult& out);
void mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const Options& options,
              BatchResult& out);

// With one minimum separation per query or candidate (MinDistances). A
// span of the wrong length, or a negative, NaN or infinite value, refuses
// the whole call with std::invalid_argument naming the list, the index and
// the value.
void batch_ccd(Kind kind, std::span<const Query> queries, std::span<const double> min_distances,
               const Options& options, BatchResult& out);
void batch_ccd(Kind kind, std::span<const Query2D> queries, std::span<const double> min_distances,
               const Options& options, BatchResult& out);
void mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const MinDistances& min_distances,
              const Options& options, BatchResult& out);

}  // namespace batchccd

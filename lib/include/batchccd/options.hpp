#pragma once

#include <cstdint>

namespace batchccd {

// How decisions are made (docs/design.md §7). A contact is the closed primitives
// coming within Options::min_distance of each other (Euclidean distance;
// touching when it is 0, the default) at some t in [0, Options::tmax];
// QueryResult::toi is then the reported time of impact. What each mode
// promises of both (the uncertified baselines the benchmarks compare with,
// fast and cubic, are not modes: they may miss contacts):
enum class Mode {
  // Certified floating point: never a false negative on any finite input; a
  // false positive only when the primitives come within `tolerance` (relative
  // to the query's size) of each other, or with min_distance > 0 within
  // min_distance + `tolerance` times the query's size, at some t in [0, tmax]
  // -- or when they do so less than toi_tolerance after tmax. The default.
  // A query the floating-point search cannot settle within
  // `exact_stage_iterations` boxes (nearly parallel edges, nearly coplanar
  // motion) goes to exact mode's exact stage rather than being reported as
  // a guessed contact, and is counted in Counters::exact_escalations.
  // TOI: never after the first contact (a lower bound). At most
  // toi_tolerance before it when the contact is a clean crossing (a certain
  // root of the cubic with the primitives certainly overlapping around it,
  // located exactly when its signs are too close to call in double: a
  // multiple root, slow motion), less than 2^-40 before it when the exact
  // stage found it; earlier when a
  // near miss within about `tolerance` comes first, which is then where the
  // reported contact is. Queries counted in Counters::undecided report a
  // lower bound only.
  conservative,
  // Decisions equal to exact arithmetic on the inputs (doubles are dyadic
  // rationals): no false positive and no false negative on any finite input.
  // The certified path runs first; every query whose decision it leaves
  // uncertain (a near miss within `tolerance`, a degenerate configuration,
  // `exact_stage_iterations` exhausted) is settled with exact arithmetic
  // (floating-point expansions where they suffice, GMP integers otherwise)
  // and counted in Counters::exact_escalations. Each such query costs a
  // bounded amount of work (loops bounded by the degrees and bit sizes of
  // its polynomials).
  // TOI: never after the first contact, and less than 1e-12 (2^-40) of the
  // step before it. With need_toi = false, as there: some lower bound.
  // With min_distance > 0 the contact condition is a distance, not a root:
  // a hit is then proven by a certified witness (a time and a pair of points
  // of the two primitives at most min_distance apart), a miss by certified
  // exclusion of every time in [0, tmax]; a query neither settles within
  // 2^-40 of its size (the primitives' closest approach lies within
  // [min_distance, min_distance + 2^-40 size]) is reported as a hit, never
  // missed, and counted in Counters::undecided. With min_distance > 0 a
  // hit's TOI, decided or not, is never after the first time the primitives
  // come within min_distance, and at most 2^-40 before the first time they
  // come within that band's upper end (on a slow approach that can be
  // several times 2^-40 before the distance reaches min_distance).
  exact,
};

// Instruction set for the batch kernels. `scalar` is the reference path;
// `automatic` picks the best this processor and build have. A batch call
// with one that is not available throws std::invalid_argument (resolve_isa,
// batch.hpp); single-query calls always run the scalar path.
// sse4, avx2 and avx512 exist in x86-64 builds, neon (64-bit ARM) in
// AArch64 builds; the scalar path in every build.
enum class Isa { automatic, scalar, sse4, avx2, avx512, neon };

// Lower-case names as the command-line tool spells them ("conservative",
// "auto", "avx2", ...); "?" for a value outside the enum. Never null.
const char* to_string(Mode mode);
const char* to_string(Isa isa);

// Every knob of a call, with its default. Every call checks min_distance
// and tmax (validate, below); the other values are not validated, and the
// comments say what an out-of-range one does.

struct Options {
  Mode mode = Mode::conservative;

  // The separation that counts as a contact, absolute, in the caller's length
  // units (ipc-toolkit's min_distance, Tight Inclusion's ms): the primitives
  // collide when their Euclidean distance is <= min_distance at some t in
  // [0, tmax]. >= 0 and finite. Batch calls can also take one per candidate
  // (batch.hpp), which replaces this one.
  double min_distance = 0;
  // The end of the time window, in (0, 1]: a contact after tmax is not a
  // hit. Conservative mode may count one less than toi_tolerance after it;
  // exact mode compares with it exactly (with min_distance > 0, but for its
  // undecided band).
  double tmax = 1;

  // false: only hit/no-hit is needed; the solver stops at the first contact
  // it finds, and a hit's toi is then only some lower bound (possibly 0).
  bool need_toi = true;

  // Mesh batches: which candidate lists to evaluate (a list left out gets
  // no results and no counts).
  bool vertex_face = true;
  bool edge_edge = true;
  bool vertex_edge = true;
  bool vertex_vertex = true;

  // Batch calls: write one QueryResult per candidate (false: only the
  // earliest TOI and the counters). It costs a result's 24 bytes a candidate,
  // written and first initialised in one piece: for lists of millions of
  // mostly free candidates, as much as filtering them.
  bool per_candidate_results = true;
  // Batch calls: list the candidates that hit (BatchResult::hits), the sparse
  // form of the same answers, costing only what there is to list.
  bool hit_list = false;

  Isa isa = Isa::automatic;

  // Worker threads for batch calls; 0 (or negative) = as many as the calling
  // thread's task arena has: all the machine has unless the caller limited it.
  int threads = 0;

  // The certified solver (conservative mode; exact mode's first pass): a
  // contact is reported when the primitives are within `tolerance` of each
  // other, measured relative to the query's size (its largest coordinate
  // difference from the first point) around that time -- over the time
  // interval the solver examines, not the whole step, so a vertex moving far
  // does not widen the tolerance where the primitives meet (never wider than
  // over the whole step). Zero, negative or NaN: nothing is within
  // tolerance, so near contacts go to the exact stage.
  double tolerance = 1e-9;
  // Conservative mode: width of the time interval at which the first
  // contact is located (the reported TOI lies at most this much before it).
  // A fraction of the step [0, 1]; values below 2^-45 (and NaN) act as 2^-45.
  double toi_tolerance = 1e-7;
  // With min_distance > 0 (no exact stage there): boxes the search examines
  // on one query before giving up; the query is then reported as a hit at
  // the earliest time not yet excluded and counted in Counters::undecided.
  // Also a cap on exact_stage_iterations. Zero or negative: the search gives
  // up at the first box it examines. Motion in an axis plane and point kinds
  // are first decided by a search of their own over time intervals
  // (docs/design.md §5a), bounded without it; only what that leaves open
  // comes to the box search.
  std::int64_t max_iterations = 1 << 20;
  // Exact and conservative modes: boxes the certified solver may examine on
  // one query before the query goes to exact arithmetic (no answer is ever
  // guessed: this only trades floating-point search for the bounded exact
  // stage; zero or negative sends every query the solver cannot settle at
  // once there).
  std::int64_t exact_stage_iterations = 32;

  // Batch calls: time each query's evaluation and report the slowest in
  // Counters::max_query_seconds, the worst single-query latency on the
  // caller's own data (a near-degenerate query settled exactly can cost
  // milliseconds where most take nanoseconds). Changes no answer; costs two
  // clock reads a query, so it is off unless asked for (the command-line
  // tool asks).
  bool time_queries = false;
};

// Throws std::invalid_argument naming the field and its value when
// min_distance is negative, NaN or infinite, or tmax is not in (0, 1].
// Every call does this first.
void validate(const Options& options);

}  // namespace batchccd

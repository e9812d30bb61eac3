#pragma once

#include <cstdint>

namespace batchccd {

// How decisions are made (DESIGN.md §3).
enum class Mode {
  // Certified floating point: never a false negative on any finite input; a
  // false positive only when the primitives come within `tolerance` (relative
  // to the query's size) of each other. The default.
  conservative,
  // The same filter and solver in plain double arithmetic, without error
  // bounds: what most engines ship. May miss contacts.
  fast,
  // The standard unfiltered cubic solver (roots of the coplanarity cubic in
  // double, then an inside test at each root): the seed paper's baseline.
  // May miss contacts.
  cubic,
};

// Instruction set for the batch kernels. `scalar` is the reference path.
enum class Isa { automatic, scalar, sse4, avx2, avx512 };

const char* to_string(Mode mode);
const char* to_string(Isa isa);

struct Options {
  Mode mode = Mode::conservative;

  // false: only hit/no-hit is needed; the solver stops at the first contact
  // it finds, and a hit's toi is then only some lower bound (possibly 0).
  bool need_toi = true;

  // Mesh batches: which candidate lists to evaluate.
  bool vertex_face = true;
  bool edge_edge = true;

  // Batch calls: write one QueryResult per candidate (false: only the
  // earliest TOI and the counters).
  bool per_candidate_results = true;

  Isa isa = Isa::automatic;

  // Worker threads for batch calls; 0 = all the machine has.
  int threads = 0;

  // Conservative/fast solver: a contact is reported when the primitives are
  // within `tolerance` of each other, measured relative to the query's size
  // (its largest coordinate difference from the first point).
  double tolerance = 1e-9;
  // Conservative/fast solver: width of the time interval at which the first
  // contact is located (the reported TOI lies at most this much before it).
  double toi_tolerance = 1e-7;
  // Conservative/fast solver: boxes examined before giving up on one query;
  // a query that reaches it is reported as a hit at the earliest time not
  // yet excluded (conservative), and counted in Counters::undecided.
  std::int64_t max_iterations = 1 << 20;
};

}  // namespace batchccd

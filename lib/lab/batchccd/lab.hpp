#pragma once

#include <span>

#include "batchccd/batch.hpp"
#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

// The engine as the benchmark tools, the tests and the fuzzers drive it:
// never installed. A user sets Options (options.hpp); these settings add
// what only measuring needs -- baselines that decide in a mode's place, and
// the lane filters switched off one at a time. The public calls are these
// calls with Settings{}: one code path.
namespace batchccd::lab {

// What decides a call in place of Options::mode. Neither baseline keeps a
// mode's promise: both may miss contacts (tests/test_baselines.cpp: a
// contact at t = 0 the modes must find, and both baselines missed), and
// neither bounds its TOI.
enum class Baseline {
  none,  // Options::mode decides
  // The certified filters and solver in plain double, without error bounds:
  // what most engines ship. With min_distance > 0 the same search as
  // conservative mode without error bounds; a query it cannot settle within
  // Options::max_iterations boxes is reported as a hit (Counters::undecided).
  // No exact stage.
  fast,
  // The standard unfiltered cubic solver (roots of the coplanarity cubic in
  // double, then an inside test at each root): the seed paper's baseline.
  // Runs no lane filter. TOI: the double estimate of the first root that
  // passes the inside test. It finds roots, not distances: min_distance > 0
  // is refused (validate below).
  cubic,
};

struct Settings {
  Baseline baseline = Baseline::none;
  // The lane filters (docs/design.md §3-4), each certified in the modes;
  // switch one off to measure the other. The cubic baseline runs none.
  bool sign_filter = true;  // Bernstein sign test on the coplanarity cubic
  // The sign test's V = 2 step (subdivision at t = 1/2 when the four signs
  // are mixed); false leaves the four signs alone, the DNF-style filter of
  // Tang et al. 2010.
  bool sign_filter_subdivision = true;
  bool separation_filter = true;  // distance at t0 against the largest displacement
  // With the separation filter, what both keep is filtered again over 2, 4
  // or 8 equal pieces of the step: culled when each piece is free by either
  // filter there (docs/design.md §4a). 1 (or any other value): the whole
  // step only.
  int filter_pieces = 4;
  // Before all of them, the swept boxes of the two primitives in the frame
  // of one vertex (their points at t0 and t1 relative to x1): apart along
  // an axis, no contact. Comparisons only; the relative frame makes them
  // tighter than a broad phase's world boxes.
  bool swept_box_filter = true;
  // Planar motion decided in its plane (docs/design.md §5a); false sends it
  // down the generic path, where the exact stage decides it.
  bool planar_path = true;
  // A point against a segment or a point in 3D decided by its vertex-segment
  // conditions (docs/design.md §5a): at a separation first, without one
  // to prove the misses the search over (t, u, v) leaves uncertain. false:
  // that search alone.
  bool point_search = true;
  // The exact stage tries floating-point expansions before GMP integers
  // (docs/design.md §6a); false: integers alone. Decisions are the same.
  bool expansion_stage = true;
};

// A mode or a baseline: what the tools run side by side.
struct Method {
  Mode mode = Mode::conservative;  // decides when baseline is none
  Baseline baseline = Baseline::none;
  Options applied_to(Options options) const {
    options.mode = mode;
    return options;
  }
  Settings settings() const { return {.baseline = baseline}; }
  friend bool operator==(const Method&, const Method&) = default;
};
inline constexpr Method kConservative{Mode::conservative};
inline constexpr Method kExact{Mode::exact};
inline constexpr Method kFast{Mode::conservative, Baseline::fast};
inline constexpr Method kCubic{Mode::conservative, Baseline::cubic};

// "none", "fast", "cubic"; "?" for a value outside the enum.
const char* to_string(Baseline baseline);
// The baseline's name, or with none the mode's.
const char* to_string(const Method& method);

// batchccd::validate, and the cubic baseline with min_distance > 0 refused
// (std::invalid_argument naming the field and value).
void validate(const Options& options, const Settings& settings);

// The calls of ccd.hpp and batch.hpp, with settings.
QueryResult query_ccd(Kind kind, const Query& query, const Options& options, const Settings& settings);
void batch_ccd(Kind kind, std::span<const Query> queries, std::span<const double> min_distances,
               const Options& options, const Settings& settings, BatchResult& out);
void batch_ccd(Kind kind, std::span<const Query2D> queries, std::span<const double> min_distances,
               const Options& options, const Settings& settings, BatchResult& out);
void mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const MinDistances& min_distances,
              const Options& options, const Settings& settings, BatchResult& out);
BatchResult batch_ccd(Kind kind, std::span<const Query> queries, const Options& options,
                      const Settings& settings);
BatchResult mesh_ccd(const MeshView& mesh, const CandidateLists& candidates, const Options& options,
                     const Settings& settings);

}  // namespace batchccd::lab

#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "workload.hpp"

// The methods the comparison commands (demo, report) set side by side, and
// what each gets wrong against ground truth, summed over workloads.
namespace batchccd::bench {

enum class Method {
  exact,         // Mode::exact
  conservative,  // Mode::conservative, every lane filter
  fast,          // lab::Baseline::fast
  cubic,         // lab::Baseline::cubic: the unfiltered cubic solver, the baseline
  dnf,           // conservative with the DNF-style filter alone: four signs, no V = 2 step, no other filter
  fcl,           // FCL 0.7's fcl::detail::Intersect, an outside peer
};

// In report order; fcl only when this build has FCL.
std::vector<Method> compared_methods();
std::string_view name_of(Method method);
std::string_view description_of(Method method);

// One method's answers on one workload, and the wall-clock time of the call.
struct MethodRun {
  std::vector<QueryResult> results;  // one per candidate
  double seconds = 0;
  std::int64_t culled = 0;  // candidates the lane filters removed (0 without filters)
};

// How often a call is timed: the fastest of `runs` (at least 1) calls, a busy
// machine only ever adding time; but a call that took `repeat_below_seconds`
// or longer is not repeated (a moment's disturbance is a small share of it).
struct Timing {
  int runs = 1;
  double repeat_below_seconds = std::numeric_limits<double>::infinity();
};

// Seconds of the fastest call of `work`, timed as `timing` says.
double fastest_of(const Timing& timing, const std::function<void()>& work);

// Runs `method` on every candidate with `threads` workers (0: all), timed as
// `timing` says (fastest_of); the answers are the last run's.
MethodRun run_method(Method method, const Workload& workload, int threads, const Timing& timing = {});

// A method's figures, summed over the workloads added.
struct MethodTally {
  Method method = Method::conservative;
  double seconds = 0;
  std::int64_t candidates = 0;
  std::int64_t culled = 0;
  std::int64_t false_negatives = 0;
  std::int64_t false_positives = 0;
  // TOI error |toi - reference toi| over the candidates where the method and
  // the reference (exact mode) both report a hit.
  std::int64_t toi_compared = 0;
  double toi_error_max = 0;
  double toi_error_sum = 0;

  // `truth`: the true decision of each candidate; `reference`: exact mode's
  // results, whose TOI lies within 1e-12 before the first contact.
  void add(const MethodRun& run, const std::vector<bool>& truth,
           const std::vector<QueryResult>& reference);
  MethodTally& operator+=(const MethodTally& other);  // the same method's
  double candidates_per_second() const;
  double cull_ratio() const;
  double toi_error_mean() const;
};

// Decisions of a run, as ground truth (exact mode's, for generated scenes).
std::vector<bool> decisions(const MethodRun& run);

}  // namespace batchccd::bench

#include "compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "peers/fcl_peer.hpp"
#include "scheduler/arena.hpp"

namespace batchccd::bench {
namespace {

struct MethodEntry {
  Method method;
  std::string_view name;
  std::string_view description;
};

constexpr MethodEntry kMethods[] = {
    {Method::exact, "exact", "decisions of exact arithmetic (certified path, GMP for the uncertain)"},
    {Method::conservative, "conservative", "certified floating point (GMP where it cannot settle), every lane filter (default)"},
    {Method::fast, "fast", "the same filters and solver in plain double arithmetic"},
    {Method::cubic, "cubic", "unfiltered cubic solver, roots in double (the baseline)"},
    {Method::dnf, "dnf", "conservative with only a DNF-style filter: four signs, no V = 2 step, no boxes"},
    {Method::fcl, "fcl", "FCL 0.7 fcl::detail::Intersect (interval Newton), an outside peer"},
};

const MethodEntry& entry(Method method) {
  for (const MethodEntry& e : kMethods)
    if (e.method == method) return e;
  throw std::invalid_argument("unknown method");
}

// A method of the engine's: a mode, or a baseline (lab.hpp).
struct EngineCall {
  Options options;
  lab::Settings settings;
};

// Every method hands back its hits only, as a simulator would ask: one
// result per candidate (24 bytes, most of them "no contact") would cost as
// much as the filters, and the same for every method.
EngineCall engine_call(Method method, int threads) {
  EngineCall call;
  Options& options = call.options;
  options.threads = threads;
  options.per_candidate_results = false;
  options.hit_list = true;
  switch (method) {
    case Method::exact: options.mode = Mode::exact; break;
    case Method::conservative: options.mode = Mode::conservative; break;
    case Method::fast: call.settings.baseline = lab::Baseline::fast; break;
    case Method::cubic: call.settings.baseline = lab::Baseline::cubic; break;
    case Method::dnf:
      options.mode = Mode::conservative;
      call.settings.sign_filter_subdivision = false;
      call.settings.separation_filter = false;
      call.settings.swept_box_filter = false;
      break;
    case Method::fcl: throw std::invalid_argument("fcl is not one of batchccd's modes");
  }
  return call;
}

// The peer on every candidate, parallel like the engine (FCL is thread-safe
// here: Intersect's functions are static and keep no state); its hits.
std::vector<Hit> run_fcl(const Workload& workload, int threads) {
  tbb::enumerable_thread_specific<std::vector<Hit>> found;
  auto work = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, workload.size(), 2048),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<Hit>& mine = found.local();
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                          const peers::PeerResult r =
                              peers::fcl_ccd(workload.kind_at(i), workload.query_at(i));
                          if (r.hit) mine.push_back({i, r.toi, Status::ok});
                        }
                      });
  };
  in_arena(threads, work);
  std::vector<Hit> hits;
  for (const std::vector<Hit>& mine : found) hits.insert(hits.end(), mine.begin(), mine.end());
  return hits;
}

// One result per candidate from a hit list (after the clock stopped).
std::vector<QueryResult> dense_results(const std::vector<Hit>& hits, std::size_t count) {
  std::vector<QueryResult> results(count);
  for (const Hit& hit : hits) results[hit.candidate] = {true, hit.toi, hit.status};
  return results;
}

}  // namespace

std::vector<Method> compared_methods() {
  std::vector<Method> methods;
  for (const MethodEntry& e : kMethods)
    if (e.method != Method::fcl || peers::fcl_available()) methods.push_back(e.method);
  return methods;
}

std::string_view name_of(Method method) { return entry(method).name; }
std::string_view description_of(Method method) { return entry(method).description; }

double fastest_of(const Timing& timing, const std::function<void()>& work) {
  double fastest = 0;
  for (int k = 0; k < std::max(timing.runs, 1); ++k) {
    const auto start = std::chrono::steady_clock::now();
    work();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fastest = k == 0 ? seconds : std::min(fastest, seconds);
    if (seconds >= timing.repeat_below_seconds) break;
  }
  return fastest;
}

MethodRun run_method(Method method, const Workload& workload, int threads, const Timing& timing) {
  MethodRun run;
  std::vector<Hit> hits;
  run.seconds = fastest_of(timing, [&] {
    if (method == Method::fcl) {
      hits = run_fcl(workload, threads);
    } else {
      const EngineCall call = engine_call(method, threads);
      BatchResult batch = workload.run(call.options, call.settings);
      hits = std::move(batch.hits);
      run.culled = batch.counters.culled;
    }
  });
  run.results = dense_results(hits, workload.size());
  return run;
}

std::vector<bool> decisions(const MethodRun& run) {
  std::vector<bool> hits(run.results.size());
  for (std::size_t i = 0; i < hits.size(); ++i) hits[i] = run.results[i].hit;
  return hits;
}

void MethodTally::add(const MethodRun& run, const std::vector<bool>& truth,
                      const std::vector<QueryResult>& reference) {
  if (run.results.size() != truth.size() || reference.size() != truth.size())
    throw std::logic_error("a method, the truth and the reference differ in length");
  seconds += run.seconds;
  candidates += static_cast<std::int64_t>(truth.size());
  culled += run.culled;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const QueryResult& r = run.results[i];
    false_negatives += truth[i] && !r.hit;
    false_positives += !truth[i] && r.hit;
    if (r.hit && reference[i].hit && std::isfinite(reference[i].toi)) {
      const double error = std::abs(r.toi - reference[i].toi);
      ++toi_compared;
      toi_error_max = std::max(toi_error_max, error);
      toi_error_sum += error;
    }
  }
}

MethodTally& MethodTally::operator+=(const MethodTally& other) {
  seconds += other.seconds;
  candidates += other.candidates;
  culled += other.culled;
  false_negatives += other.false_negatives;
  false_positives += other.false_positives;
  toi_compared += other.toi_compared;
  toi_error_max = std::max(toi_error_max, other.toi_error_max);
  toi_error_sum += other.toi_error_sum;
  return *this;
}

double MethodTally::candidates_per_second() const {
  return seconds > 0 ? static_cast<double>(candidates) / seconds : 0.0;
}

double MethodTally::cull_ratio() const {
  return candidates > 0 ? static_cast<double>(culled) / static_cast<double>(candidates) : 0.0;
}

double MethodTally::toi_error_mean() const {
  return toi_compared > 0 ? toi_error_sum / static_cast<double>(toi_compared) : 0.0;
}

}  // namespace batchccd::bench

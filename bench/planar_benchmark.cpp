// Coplanar motion (docs/design.md §5a): vertex-face and edge-edge queries
// whose eight points stay in one plane, decided by the planar path, against
// the same queries sent down the generic path (the exact stage decides
// them there), in one run. Planes: z = 0 and the tilted z = x + 2y + 1.75;
// random in-plane motions with 15-40 % contacts.
//
//   build/bench/batchccd_planar_benchmark [--benchmark_filter=REGEX]
//
// One thread, per-candidate results into a reused BatchResult (a frame
// loop's steady state). Counters: hits, exact-stage escalations, and the
// time per query (us_per_query).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"

namespace batchccd {
namespace {

// Points (s, t) of a plane as origin + s u + t v; small integer u, v and
// dyadic s, t keep every coordinate exact.
struct Plane {
  const char* name;
  Vec3 origin, u, v;
  Vec3 operator()(double s, double t) const { return origin + s * u + t * v; }
};
const Plane kPlanes[] = {{"z0", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                         {"tilted", {0.25, -0.5, 1}, {1, 0, 1}, {0, 1, 2}}};

// Random primitives in the unit square, moving by up to half its side (VF)
// or a quarter (EE): about a quarter (VF) to a third (EE) of them touch
// during the step.
std::vector<Query> planar_queries(Kind kind, const Plane& plane, int count) {
  std::mt19937_64 random(kind == Kind::vertex_face ? 11 : 12);
  const int largest_motion = kind == Kind::vertex_face ? 1 << 19 : 1 << 18;
  std::uniform_int_distribution<int> coordinate(0, 1 << 20), motion(-largest_motion, largest_motion);
  const auto dyadic = [](int value) { return std::ldexp(static_cast<double>(value), -20); };
  std::vector<Query> queries(count);
  for (Query& query : queries)
    for (int i = 0; i < 4; ++i) {
      const double s = dyadic(coordinate(random)), t = dyadic(coordinate(random));
      query.points[i] = plane(s, t);
      query.points[i + 4] = plane(s + dyadic(motion(random)), t + dyadic(motion(random)));
    }
  return queries;
}

void planar(benchmark::State& state, Kind kind, const Plane& plane, Mode mode, bool planar_path) {
  const std::vector<Query> queries = planar_queries(kind, plane, 5000);
  Options options;
  options.mode = mode;
  options.threads = 1;
  options.per_candidate_results = true;
  lab::Settings settings;
  settings.planar_path = planar_path;
  BatchResult result;
  for (auto _ : state) {
    lab::batch_ccd(kind, queries, {}, options, settings, result);
    benchmark::DoNotOptimize(result.results.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(queries.size()) * state.iterations());
  state.counters["hits"] = static_cast<double>(result.counters.hits);
  state.counters["escalations"] = static_cast<double>(result.counters.exact_escalations);
  state.counters["us_per_query"] = benchmark::Counter(
      static_cast<double>(queries.size()) * 1e-6, benchmark::Counter::kIsIterationInvariantRate |
                                                      benchmark::Counter::kInvert);
}

void register_all() {
  for (const Plane& plane : kPlanes)
    for (const auto& [kind_name, kind] : {std::pair{"vf", Kind::vertex_face}, std::pair{"ee", Kind::edge_edge}})
      for (const auto& [mode_name, mode] : {std::pair{"conservative", Mode::conservative}, std::pair{"exact", Mode::exact}})
        for (const bool planar_path : {true, false}) {
          const std::string name = std::string("Planar/") + plane.name + "/" + kind_name + "/" + mode_name +
                                   (planar_path ? "/planar_path" : "/generic_path");
          auto* benchmark = benchmark::RegisterBenchmark(
              name.c_str(), [&plane, kind = kind, mode = mode, planar_path](benchmark::State& s) {
                planar(s, kind, plane, mode, planar_path);
              });
          benchmark->Unit(benchmark::kMillisecond);
          if (!planar_path) benchmark->Iterations(1);  // about half a second a pass
        }
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

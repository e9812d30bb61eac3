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
// Points: 2D point-edge and point-point lists (mesh_ccd on n x 2 positions)
// against the same lists in 3D, candidates per second.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
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

// A 2D scene: segments (vertex pairs) scattered in the unit square, moving
// by up to 2 % of it, and the vertex-edge and vertex-vertex pairs whose
// swept boxes, grown by 1 %, overlap (a broad phase's list). `lift`: the
// same scene in 3D, each vertex at a random height within 1 % (a
// comparable 3D list: the same pairs, no longer planar).
struct PointScene {
  Eigen::MatrixXd x0, x1;
  Candidates candidates;
};

PointScene point_scene(bool lift) {
  constexpr int n = 4000;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(0, 1), motion(-0.02, 0.02), height(0, 0.01);
  PointScene scene;
  scene.x0.resize(n, lift ? 3 : 2);
  scene.x1.resize(n, lift ? 3 : 2);
  for (int v = 0; v < n; ++v) {
    scene.x0(v, 0) = unit(random), scene.x0(v, 1) = unit(random);
    scene.x1(v, 0) = scene.x0(v, 0) + motion(random), scene.x1(v, 1) = scene.x0(v, 1) + motion(random);
  }
  if (lift) {
    std::mt19937_64 heights(4);
    for (int v = 0; v < n; ++v) scene.x0(v, 2) = height(heights), scene.x1(v, 2) = height(heights);
  }
  constexpr double margin = 0.01;
  struct Box {
    double low[2], high[2];
  };
  const auto box = [&](std::initializer_list<int> vertices) {
    Box b{{1e9, 1e9}, {-1e9, -1e9}};
    for (const int v : vertices)
      for (int c = 0; c < 2; ++c) {
        b.low[c] = std::min({b.low[c], scene.x0(v, c) - margin, scene.x1(v, c) - margin});
        b.high[c] = std::max({b.high[c], scene.x0(v, c) + margin, scene.x1(v, c) + margin});
      }
    return b;
  };
  const auto overlap = [](const Box& a, const Box& b) {
    return a.low[0] <= b.high[0] && b.low[0] <= a.high[0] && a.low[1] <= b.high[1] && b.low[1] <= a.high[1];
  };
  for (int v = 0; v < n; ++v) {
    const auto point = box({v});
    for (int e = 0; e + 1 < n; e += 2)
      if (v != e && v != e + 1 && overlap(point, box({e, e + 1}))) scene.candidates.vertex_edge.push_back({v, e, e + 1});
    for (int w = v + 1; w < n; ++w)
      if (overlap(point, box({w}))) scene.candidates.vertex_vertex.push_back({v, w});
  }
  return scene;
}

void points(benchmark::State& state, bool lift, Kind kind, double min_distance) {
  static const PointScene flat = point_scene(false), lifted = point_scene(true);
  const PointScene& scene = lift ? lifted : flat;
  const Eigen::MatrixXi no_faces;
  CandidateLists lists;
  if (kind == Kind::vertex_edge) lists.vertex_edge = scene.candidates.vertex_edge;
  else lists.vertex_vertex = scene.candidates.vertex_vertex;
  Options options;
  options.threads = 1;
  options.per_candidate_results = false;
  options.hit_list = true;
  options.min_distance = min_distance;
  BatchResult result;
  mesh_ccd({scene.x0, scene.x1, no_faces}, lists, options, result);
  for (auto _ : state) {
    mesh_ccd({scene.x0, scene.x1, no_faces}, lists, options, result);
    benchmark::DoNotOptimize(result.earliest_toi);
  }
  state.SetItemsProcessed(result.counters.candidates * state.iterations());
  state.counters["hits"] = static_cast<double>(result.counters.hits);
  state.counters["survivors"] = static_cast<double>(result.counters.solved);
}

void register_all() {
  for (const auto& [kind_name, kind] : {std::pair{"ve", Kind::vertex_edge}, std::pair{"vv", Kind::vertex_vertex}})
    for (const double min_distance : {0.0, 1e-3})
      for (const bool lift : {false, true}) {
        const std::string name = std::string("Points/") + kind_name + "/min_distance_" +
                                 (min_distance > 0 ? "0.001" : "0") + (lift ? "/3d" : "/2d");
        benchmark::RegisterBenchmark(name.c_str(), [lift, kind = kind, min_distance](benchmark::State& s) {
          points(s, lift, kind, min_distance);
        })->Unit(benchmark::kMillisecond);
      }
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

const bool registered = (register_all(), true);

}  // namespace
}  // namespace batchccd

BENCHMARK_MAIN();

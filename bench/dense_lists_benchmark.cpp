// What a frame loop pays on the dense candidate lists of the shared scenes
// (../shared/data/scenes, skipped when absent): mesh_ccd in conservative
// mode, hits only, results reused, one thread, at minimum separations of 0,
// 1e-3 and 1e-2 mean edge lengths. The lists are a swept-box broad phase's,
// boxes grown by one mean edge length (as batchccd_make_candidates writes
// them), made once outside the timing.
//
//   build/bench/batchccd_dense_lists_benchmark [--benchmark_filter=REGEX]
//
// Each list with the default filter stages (swept boxes first, 4 pieces
// last), then without the swept boxes (no_swept_box, the stages of 0.4.0),
// without them and the pieces (no_swept_box/pieces_1, those of 0.3.0), and
// with 2 and 8 pieces; and the point kinds' lists (vertex_edge,
// vertex_vertex: point_candidates) with the default stages, also as
// edge-edge candidates of a zero-length edge (as_edge_edge: how they were
// filtered before their own distances). Counters per call: candidates/s (items_per_second),
// the share culled by each lane filter stage, the survivors' share and the
// hits. Ratios between separations are only meaningful within one run.
// MethodOnDenseList: the modes and the cubic baseline at no separation,
// with where the time goes. EarliestToi: mesh_ccd asked for the earliest
// TOI alone (a shrinking window) against per-candidate results.
// CollisionFreeStep: ipc::collision_free_stepsize against narrow phases
// driven per candidate as ipc-toolkit's loop drives them -- batchccd's
// per-query calls, and Tight Inclusion when the build has it
// (cmake -DBATCHCCD_TIGHT_INCLUSION_DIR=<its sources>, bench/CMakeLists.txt).
#include <benchmark/benchmark.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "broad_phase.hpp"
#include "peers/tight_inclusion_peer.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace batchccd {
namespace {

const std::filesystem::path kScenes = BATCHCCD_SHARED_DATA "/scenes";
constexpr const char* kSceneNames[] = {"armadillo-rollers-326", "cloth-funnel-227", "rod-twist-3036"};
constexpr double kSeparations[] = {0, 1e-3, 1e-2};  // in mean edge lengths

struct DenseList {
  Scene scene;
  Candidates candidates;
  // Point-kind lists (vertex_edge and vertex_vertex only) of the same
  // broad phase (point_candidates), and the same as edge-edge candidates
  // with a zero-length edge (v, v, a, b) and (p, p, q, q): what the filters
  // made of them before they had their own distances.
  Candidates points;
  std::vector<std::array<int, 4>> vertex_edge_as_edge_edge, vertex_vertex_as_edge_edge;
  double mean_edge_length = 0;
};

// The vertex-edge and vertex-vertex candidates of the same broad phase: a
// vertex against an edge or vertex whose boxes (t0 and t1, grown by
// `margin`) overlap its own. An edge's box lies in each of its faces', so
// each such pair comes from a vertex-face candidate (the vertex against the
// face's edges and corners); vertices joined by an edge are left out, as
// edges sharing a vertex are.
Candidates point_candidates(const Scene& scene, const Candidates& candidates, double margin) {
  const Eigen::MatrixXd low = scene.positions_t0.cwiseMin(scene.positions_t1).array() - margin;
  const Eigen::MatrixXd high = scene.positions_t0.cwiseMax(scene.positions_t1).array() + margin;
  const auto overlap = [&](int v, int a, int b) {  // v's box against the box of a and b
    for (int c = 0; c < 3; ++c)
      if (low(v, c) > std::max(high(a, c), high(b, c)) || std::min(low(a, c), low(b, c)) > high(v, c)) return false;
    return true;
  };
  std::vector<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < scene.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = scene.faces(f, k), b = scene.faces(f, (k + 1) % 3);
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  Candidates points;
  for (const auto& [v, f] : candidates.vertex_face)
    for (int k = 0; k < 3; ++k) {
      const int a = scene.faces(f, k), b = scene.faces(f, (k + 1) % 3);
      if (overlap(v, a, b)) points.vertex_edge.push_back({v, std::min(a, b), std::max(a, b)});
      const std::pair<int, int> pair{std::min(v, a), std::max(v, a)};
      if (overlap(v, a, a) && !std::binary_search(edges.begin(), edges.end(), pair))
        points.vertex_vertex.push_back({pair.first, pair.second});
    }
  const auto unique = [](auto& list) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  };
  unique(points.vertex_edge);
  unique(points.vertex_vertex);
  return points;
}

const DenseList* dense_list(const std::string& name) {
  static std::map<std::string, DenseList> lists;
  if (const auto found = lists.find(name); found != lists.end()) return &found->second;
  const std::filesystem::path directory = kScenes / name;
  if (!is_scene_directory(directory)) return nullptr;
  DenseList list;
  list.scene = read_scene(directory);
  const MeshView view{list.scene.positions_t0, list.scene.positions_t1, list.scene.faces};
  list.mean_edge_length = scenes::mean_edge_length(view);
  list.candidates = scenes::swept_box_candidates(view, list.mean_edge_length);
  list.points = point_candidates(list.scene, list.candidates, list.mean_edge_length);
  for (const auto& [v, a, b] : list.points.vertex_edge) list.vertex_edge_as_edge_edge.push_back({v, v, a, b});
  for (const auto& [p, q] : list.points.vertex_vertex) list.vertex_vertex_as_edge_edge.push_back({p, p, q, q});
  return &lists.emplace(name, std::move(list)).first->second;
}

// The filter stages around the whole-step filters (lab::Settings::swept_box_filter
// before them, filter_pieces after): the default, and the variants to
// compare it with.
struct Stages {
  const char* name;  // "" for the default
  int pieces;
  bool swept_box;
};
constexpr Stages kStages[] = {{"", lab::Settings{}.filter_pieces, lab::Settings{}.swept_box_filter},
                              {"/no_swept_box", 4, false},
                              {"/no_swept_box/pieces_1", 1, false},
                              {"/pieces_2", 2, true},
                              {"/pieces_8", 8, true}};

// The lists a row evaluates: the broad phase's vertex-face and edge-edge
// lists, or one of the point kinds' (point_candidates).
// The edge-edge list alone, to compare the point kinds' with. As edge-edge
// candidates: the same point lists as edge-edge queries of a zero-length
// edge.
enum class Lists { faces_and_edges, edge_edge, vertex_edge, vertex_vertex, vertex_edge_as_ee, vertex_vertex_as_ee };

CandidateLists lists_of(const DenseList& list, Lists which) {
  switch (which) {
    case Lists::edge_edge: return {.edge_edge = list.candidates.edge_edge};
    case Lists::vertex_edge: return {.vertex_edge = list.points.vertex_edge};
    case Lists::vertex_vertex: return {.vertex_vertex = list.points.vertex_vertex};
    case Lists::vertex_edge_as_ee: return {.edge_edge = list.vertex_edge_as_edge_edge};
    case Lists::vertex_vertex_as_ee: return {.edge_edge = list.vertex_vertex_as_edge_edge};
    default: return list.candidates;
  }
}

void MeshCcdOnDenseList(benchmark::State& state, const std::string& name, double separation, Stages stages,
                        Lists which) {
  const DenseList* list = dense_list(name);
  if (list == nullptr) {
    state.SkipWithError("../shared/data/scenes is absent");
    return;
  }
  const CandidateLists candidates = lists_of(*list, which);
  Options options;
  options.threads = 1;
  options.per_candidate_results = false;
  options.hit_list = true;
  options.min_distance = separation * list->mean_edge_length;
  const lab::Settings settings{.filter_pieces = stages.pieces, .swept_box_filter = stages.swept_box};
  const MeshView view{list->scene.positions_t0, list->scene.positions_t1, list->scene.faces};
  BatchResult result;
  // First touch and allocation outside the timing.
  lab::mesh_ccd(view, candidates, MinDistances{}, options, settings, result);
  for (auto _ : state) {
    lab::mesh_ccd(view, candidates, MinDistances{}, options, settings, result);
    benchmark::DoNotOptimize(result.earliest_toi);
  }
  const Counters& c = result.counters;
  const auto share = [&](std::int64_t count) { return static_cast<double>(count) / static_cast<double>(c.candidates); };
  state.SetItemsProcessed(c.candidates * state.iterations());
  state.counters["sign_culled"] = share(c.culled_by_sign);
  state.counters["separation_culled"] = share(c.culled_by_separation);
  state.counters["pieces_culled"] = share(c.culled_by_pieces);
  state.counters["swept_box_culled"] = share(c.culled_by_swept_box);
  state.counters["survivors"] = share(c.solved);
  state.counters["hits"] = static_cast<double>(c.hits);
  state.counters["undecided"] = static_cast<double>(c.undecided);
  state.counters["candidates"] = static_cast<double>(c.candidates);
}

// Where the time goes, per method at no separation (and conservative mode at
// separations of 1e-3 and 1e-2 mean edge lengths): each mode with every
// query timed (Options::time_queries; two clock reads a survivor, so these
// rows run a little slower than the ones above) and the unfiltered cubic
// baseline, in the same run so that ratios between them mean something.
// Counters: survivors' share, the mean cost of a survivor (the scalar path,
// exact stage included), and the shares of the call's time spent by the
// filters (and scheduling: the rest), the scalar path and, within it, the
// queries exact arithmetic settled.
void MethodOnDenseList(benchmark::State& state, const std::string& name, lab::Method method, double separation) {
  const DenseList* list = dense_list(name);
  if (list == nullptr) {
    state.SkipWithError("../shared/data/scenes is absent");
    return;
  }
  Options options = method.applied_to({});
  options.threads = 1;
  options.per_candidate_results = false;
  options.hit_list = true;
  options.time_queries = method.baseline == lab::Baseline::none;
  options.min_distance = separation * list->mean_edge_length;
  const MeshView view{list->scene.positions_t0, list->scene.positions_t1, list->scene.faces};
  BatchResult result;
  lab::mesh_ccd(view, list->candidates, MinDistances{}, options, method.settings(), result);
  double seconds = 0, solved_seconds = 0, escalated_seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    lab::mesh_ccd(view, list->candidates, MinDistances{}, options, method.settings(), result);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    solved_seconds += result.counters.solved_seconds;
    escalated_seconds += result.counters.escalated_seconds;
  }
  const Counters& c = result.counters;
  state.SetItemsProcessed(c.candidates * state.iterations());
  state.counters["survivors"] = static_cast<double>(c.solved) / static_cast<double>(c.candidates);
  state.counters["hits"] = static_cast<double>(c.hits);
  state.counters["escalations"] = static_cast<double>(c.exact_escalations);
  if (options.time_queries && c.solved > 0) {
    const double solved = static_cast<double>(c.solved) * static_cast<double>(state.iterations());
    state.counters["us_per_survivor"] = solved_seconds / solved * 1e6;
    state.counters["filter_share"] = 1 - solved_seconds / seconds;
    state.counters["solver_share"] = (solved_seconds - escalated_seconds) / seconds;
    state.counters["exact_share"] = escalated_seconds / seconds;
  }
}

// The earliest TOI of a dense list through mesh_ccd, conservative mode, no
// separation, one thread: asked for alone (per_candidate_results and
// hit_list false: the survivors are asked in a shrinking window, batch.hpp),
// with a hit list (the same work without the window) and with
// per-candidate results, in the same run. Counters: the earliest TOI (the
// same for all three), the survivors asked and the hits found.
struct EarliestToiCall {
  const char* name;
  bool per_candidate_results;
  bool hit_list;
};
constexpr EarliestToiCall kEarliestToiCalls[] = {
    {"earliest_toi_only", false, false}, {"hit_list", false, true}, {"per_candidate_results", true, false}};

void EarliestToiOnDenseList(benchmark::State& state, const std::string& name, EarliestToiCall call) {
  const DenseList* list = dense_list(name);
  if (list == nullptr) {
    state.SkipWithError("../shared/data/scenes is absent");
    return;
  }
  Options options;
  options.threads = 1;
  options.per_candidate_results = call.per_candidate_results;
  options.hit_list = call.hit_list;
  const MeshView view{list->scene.positions_t0, list->scene.positions_t1, list->scene.faces};
  BatchResult result;
  mesh_ccd(view, list->candidates, options, result);
  for (auto _ : state) {
    mesh_ccd(view, list->candidates, options, result);
    // Read only: DoNotOptimize on a writable double may hand back garbage
    // (Debian's Google Benchmark, g++ 12), and the TOI is reported below.
    benchmark::DoNotOptimize(std::as_const(result.earliest_toi));
  }
  state.SetItemsProcessed(result.counters.candidates * state.iterations());
  state.counters["earliest_toi"] = result.earliest_toi;
  state.counters["solved"] = static_cast<double>(result.counters.solved);
  state.counters["hits"] = static_cast<double>(result.counters.hits);
}

// Who answers the collision-free step: the batch call, or a narrow phase
// driven per candidate as ipc-toolkit's loop drives it.
enum class StepDriver { batch, per_query_loop, tight_inclusion_loop };

const char* to_string(StepDriver driver) {
  switch (driver) {
    case StepDriver::batch: return "batch";
    case StepDriver::per_query_loop: return "per_query_loop";
    case StepDriver::tight_inclusion_loop: return "tight_inclusion_loop";
  }
  return "?";
}

// ipc-toolkit's collision-free step on a dense list, at min_distance =
// separation mean edge lengths, on `threads` threads: the batch call
// (ipc::collision_free_stepsize), against a narrow phase driven as
// ipc-toolkit's compute_collision_free_stepsize drives it (a parallel loop
// over the vertex-face and edge-edge candidates, each asked with tmax = the
// earliest toi so far, an atomic minimum, with ipc-toolkit's rules):
// batchccd's per-query calls (ipc.hpp), and Tight Inclusion
// (peers/tight_inclusion_peer.hpp; rows skipped when the build has not got
// it). Counter: the step.
void CollisionFreeStepOnDenseList(benchmark::State& state, const std::string& name, double separation,
                                  StepDriver driver, int threads) {
  const DenseList* list = dense_list(name);
  if (list == nullptr) {
    state.SkipWithError("../shared/data/scenes is absent");
    return;
  }
  if (driver == StepDriver::tight_inclusion_loop && !peers::tight_inclusion_available()) {
    state.SkipWithError("configured without Tight Inclusion (-DBATCHCCD_TIGHT_INCLUSION_DIR)");
    return;
  }
  const MeshView view{list->scene.positions_t0, list->scene.positions_t1, list->scene.faces};
  const double min_distance = separation * list->mean_edge_length;
  const auto narrow_phase = [&](Kind kind, const Query& q, double& toi, double tmax) {
    constexpr double tolerance = ipc::DEFAULT_CCD_TOLERANCE, rescaling = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING;
    constexpr long iterations = ipc::DEFAULT_CCD_MAX_ITERATIONS;
    if (driver == StepDriver::tight_inclusion_loop)
      return peers::tight_inclusion_ipc_ccd(kind, q, std::sqrt(squared_distance(kind, q, 0)), toi, min_distance, tmax,
                                            tolerance, iterations, rescaling);
    const auto& p = q.points;
    if (kind == Kind::vertex_face)
      return ipc::point_triangle_ccd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], toi, min_distance, tmax,
                                     tolerance, iterations, rescaling);
    return ipc::edge_edge_ccd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], toi, min_distance, tmax, tolerance,
                              iterations, rescaling);
  };
  const auto per_candidate_loop = [&] {
    std::atomic<double> earliest{1.0};
    const auto lower_to = [&](double toi) {
      double current = earliest.load();
      while (toi < current && !earliest.compare_exchange_weak(current, toi)) {
      }
    };
    const auto& vertex_face = list->candidates.vertex_face;
    const auto& edge_edge = list->candidates.edge_edge;
    tbb::task_arena arena(threads);
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, vertex_face.size() + edge_edge.size(), [&](std::size_t i) {
        double toi = 1;
        const bool hit = i < vertex_face.size()
                             ? narrow_phase(Kind::vertex_face, vertex_face_query(view, vertex_face[i]), toi,
                                            earliest.load())
                             : narrow_phase(Kind::edge_edge, edge_edge_query(view, edge_edge[i - vertex_face.size()]),
                                            toi, earliest.load());
        if (hit) lower_to(toi);
      });
    });
    return earliest.load();
  };
  const auto run = [&] {
    const CandidateLists lists{.vertex_face = list->candidates.vertex_face, .edge_edge = list->candidates.edge_edge};
    return driver == StepDriver::batch
               ? ipc::collision_free_stepsize(view, lists, min_distance, ipc::DEFAULT_CCD_TOLERANCE,
                                              ipc::DEFAULT_CCD_MAX_ITERATIONS,
                                              ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING, threads)
               : per_candidate_loop();
  };
  double step = run();
  for (auto _ : state) {
    step = run();
    benchmark::DoNotOptimize(step);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(list->candidates.vertex_face.size() +
                                                    list->candidates.edge_edge.size()) *
                          state.iterations());
  state.counters["step"] = step;
}

const bool registered = [] {
  for (const char* name : kSceneNames)
    for (const double separation : kSeparations)
      for (const Stages& stages : kStages)
        benchmark::RegisterBenchmark(("MeshCcdOnDenseList/" + std::string(name) + "/min_distance_" +
                                      std::to_string(separation).substr(0, 5) + stages.name)
                                         .c_str(),
                                     MeshCcdOnDenseList, std::string(name), separation, stages,
                                     Lists::faces_and_edges)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
  // The point kinds' lists, with the default stages.
  for (const char* name : kSceneNames)
    for (const double separation : kSeparations)
      for (const auto& [kind, which] : {std::pair{"edge_edge", Lists::edge_edge},
                                        std::pair{"vertex_edge", Lists::vertex_edge},
                                        std::pair{"vertex_vertex", Lists::vertex_vertex},
                                        std::pair{"vertex_edge/as_edge_edge", Lists::vertex_edge_as_ee},
                                        std::pair{"vertex_vertex/as_edge_edge", Lists::vertex_vertex_as_ee}})
        benchmark::RegisterBenchmark(("MeshCcdOnDenseList/" + std::string(name) + "/min_distance_" +
                                      std::to_string(separation).substr(0, 5) + "/" + kind)
                                         .c_str(),
                                     MeshCcdOnDenseList, std::string(name), separation, kStages[0], which)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
  for (const char* name : kSceneNames)
    for (const auto& [method, separation] : {std::pair{lab::kConservative, 0.0}, std::pair{lab::kExact, 0.0},
                                             std::pair{lab::kCubic, 0.0}, std::pair{lab::kConservative, 1e-3},
                                             std::pair{lab::kConservative, 1e-2}})
      benchmark::RegisterBenchmark(("MethodOnDenseList/" + std::string(name) + "/" + to_string(method) +
                                    (separation > 0 ? "/min_distance_" + std::to_string(separation).substr(0, 5) : ""))
                                       .c_str(),
                                   MethodOnDenseList, std::string(name), method, separation)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  for (const char* name : kSceneNames)
    for (const EarliestToiCall& call : kEarliestToiCalls)
      benchmark::RegisterBenchmark(("EarliestToi/" + std::string(name) + "/" + call.name).c_str(),
                                   EarliestToiOnDenseList, std::string(name), call)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  for (const char* name : kSceneNames)
    for (const double separation : {0.0, 1e-3})
      for (const int threads : {1, 2})
        for (const StepDriver driver :
             {StepDriver::batch, StepDriver::per_query_loop, StepDriver::tight_inclusion_loop})
          benchmark::RegisterBenchmark(("CollisionFreeStep/" + std::string(name) + "/min_distance_" +
                                        std::to_string(separation).substr(0, 5) + "/" + to_string(driver) +
                                        "/threads_" + std::to_string(threads))
                                           .c_str(),
                                       CollisionFreeStepOnDenseList, std::string(name), separation, driver, threads)
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime()
              ->Iterations(driver == StepDriver::batch ? 3 : 1);
  return true;
}();

}  // namespace
}  // namespace batchccd

BENCHMARK_MAIN();

// A frame loop allocates nothing: after the first call into a reused
// BatchResult, batch_ccd and mesh_ccd of every kind and option (point
// lists, per-candidate separations, min_distance 0 and > 0, 1 and 2
// threads, hit lists on and off) call no global operator new. An executable
// of its own: the replaced operators below count for the whole binary.
//
// What this cannot see: oneTBB's own allocations, which go through its
// cache-aligned allocator (malloc or tbbmalloc, never operator new): its
// task objects and the per-thread slots of its containers. The scheduler
// keeps its arenas alive between calls and uses no TBB container, so what
// remains of those is TBB's task pool, which reuses its memory. GMP's limbs
// (exact mode's last stage) use malloc too; these calls run conservative
// mode, whose survivors never reach it.
//
// The warm-up: the certified solver keeps its work lists per thread
// (inclusion_solver.cpp) and grows them to the deepest search that thread
// has run. With two threads, which of TBB's threads meets which survivor
// changes from call to call, so before counting each thread of TBB's pool
// runs the call once on one thread: every list has then seen every
// survivor, as it has after a frame loop's first steps.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <new>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "batchccd/batchccd.hpp"
#include "batchccd/ipc_stepsize.hpp"
#include "broad_phase.hpp"
#include "scenes.hpp"

namespace {

std::atomic<bool> counting{false};
std::atomic<long> allocations{0};

void* allocate(std::size_t size, std::size_t alignment) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
  if (size == 0) size = 1;
  void* p = alignment <= alignof(std::max_align_t)
                ? std::malloc(size)
                : std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  return p;
}
void* allocate_or_throw(std::size_t size, std::size_t alignment) {
  void* p = allocate(size, alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace

void* operator new(std::size_t size) { return allocate_or_throw(size, 0); }
void* operator new[](std::size_t size) { return allocate_or_throw(size, 0); }
void* operator new(std::size_t size, std::align_val_t a) { return allocate_or_throw(size, std::size_t(a)); }
void* operator new[](std::size_t size, std::align_val_t a) { return allocate_or_throw(size, std::size_t(a)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return allocate(size, 0); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return allocate(size, 0); }
void* operator new(std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate(size, std::size_t(a));
}
void* operator new[](std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate(size, std::size_t(a));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

namespace batchccd {
namespace {

// Operator-new calls made by `call`, on any thread.
template <class Call>
long allocations_of(const Call& call) {
  allocations = 0;
  counting = true;
  call();
  counting = false;
  return allocations.load();
}

// A cloth step with contacts, its broad-phase lists, and point lists made
// from the vertex-face one (the vertex against its face's edges and
// corners), each with a separation per candidate.
struct Frame {
  scenes::MovingMesh mesh = scenes::cloth_scene({.resolution = 16});
  Candidates lists;
  std::vector<double> separations[4];
  MeshView view() const { return mesh.view(); }

  Frame() {
    lists = scenes::swept_box_candidates(view(), scenes::mean_edge_length(view()));
    std::set<std::array<int, 3>> vertex_edge;
    std::set<std::array<int, 2>> vertex_vertex;
    for (const auto& [v, f] : lists.vertex_face)
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
        vertex_edge.insert({v, std::min(a, b), std::max(a, b)});
        vertex_vertex.insert({std::min(v, a), std::max(v, a)});
      }
    lists.vertex_edge.assign(vertex_edge.begin(), vertex_edge.end());
    lists.vertex_vertex.assign(vertex_vertex.begin(), vertex_vertex.end());
    const std::size_t sizes[4] = {lists.vertex_face.size(), lists.edge_edge.size(), lists.vertex_edge.size(),
                                  lists.vertex_vertex.size()};
    const double edge = scenes::mean_edge_length(view());
    for (int list = 0; list < 4; ++list)
      for (std::size_t i = 0; i < sizes[list]; ++i) separations[list].push_back(edge * 1e-3 * double(i % 3));
  }

  MinDistances min_distances() const {
    return {separations[0], separations[1], separations[2], separations[3]};
  }

  // The lists as raw queries of one kind.
  std::vector<Query> queries(Kind kind) const {
    const auto points = [&](std::initializer_list<int> ids) {
      std::vector<Vec3> t0, t1;
      for (int id : ids) {
        t0.push_back(mesh.positions_t0.row(id).transpose());
        t1.push_back(mesh.positions_t1.row(id).transpose());
      }
      return make_query(kind, t0, t1);
    };
    std::vector<Query> out;
    if (kind == Kind::vertex_face)
      for (const auto& c : lists.vertex_face) out.push_back(vertex_face_query(view(), c));
    if (kind == Kind::edge_edge)
      for (const auto& c : lists.edge_edge) out.push_back(edge_edge_query(view(), c));
    if (kind == Kind::vertex_edge)
      for (const auto& [v, a, b] : lists.vertex_edge) out.push_back(points({v, a, b}));
    if (kind == Kind::vertex_vertex)
      for (const auto& [p, q] : lists.vertex_vertex) out.push_back(points({p, q}));
    return out;
  }
};

const Frame& frame() {
  static const Frame instance;
  return instance;
}

// Each set of options a frame loop may call with.
std::vector<std::pair<std::string, Options>> option_sets() {
  std::vector<std::pair<std::string, Options>> sets;
  for (int threads : {1, 2})
    for (double min_distance : {0.0, 1e-3})
      for (bool hit_list : {false, true})
        for (bool per_candidate : {false, true}) {
          Options options;
          options.threads = threads;
          options.min_distance = min_distance * scenes::mean_edge_length(frame().view());
          options.hit_list = hit_list;
          options.per_candidate_results = per_candidate;
          sets.emplace_back("threads " + std::to_string(threads) + " min_distance " + std::to_string(min_distance) +
                                " hit_list " + std::to_string(hit_list) + " per_candidate " +
                                std::to_string(per_candidate),
                            options);
        }
  return sets;
}

// Runs `work` once on each thread of TBB's pool and on the caller: the
// threads a call's workers may be. Each waits for all to arrive, so that no
// thread runs it twice.
template <class Work>
void on_every_thread(const Work& work) {
  const int threads = tbb::info::default_concurrency();
  std::atomic<int> arrived{0};
  tbb::parallel_for(
      tbb::blocked_range<int>(0, threads, 1),
      [&](const tbb::blocked_range<int>&) {
        arrived.fetch_add(1);
        while (arrived.load() < threads) std::this_thread::yield();
        work();
      },
      tbb::simple_partitioner());
}

// Two calls to grow what they keep and the call on one thread on every
// thread (the warm-up above), then three calls that must allocate nothing.
// call(threads, out): the call with Options::threads = threads into out
// (if it writes a BatchResult).
template <class Call>
void expect_no_allocation_after_warm_up(const Call& call, int threads, const std::string& what) {
  BatchResult out;
  call(threads, out);
  call(threads, out);
  on_every_thread([&] {
    BatchResult own;
    call(1, own);
  });
  EXPECT_EQ(allocations_of([&] { call(threads, out), call(threads, out), call(threads, out); }), 0) << what;
}

TEST(NoAllocation, TheCounterSeesAllocations) {
  // The replaced operator new counts, here and on TBB's workers alike.
  EXPECT_GT(allocations_of([] { std::vector<int> grown(1000); }), 0);
  BatchResult fresh;
  Options options;
  options.threads = 2;
  options.hit_list = true;
  EXPECT_GT(allocations_of([&] { mesh_ccd(frame().view(), frame().lists, options, fresh); }), 0);
}

TEST(NoAllocation, MeshCallsOfEveryKindAndOption) {
  ASSERT_GT(frame().lists.vertex_edge.size(), 0u);
  ASSERT_GT(frame().lists.vertex_vertex.size(), 0u);
  for (const auto& set : option_sets())
    for (bool each : {false, true}) {
      const auto& [name, own_options] = set;
      const Options& options = own_options;  // a reference, not a binding: the lambda captures it
      const MinDistances separations = each ? frame().min_distances() : MinDistances{};
      expect_no_allocation_after_warm_up(
          [&](int threads, BatchResult& out) {
            Options own = options;
            own.threads = threads;
            mesh_ccd(frame().view(), frame().lists, separations, own, out);
          },
          options.threads, "mesh_ccd, " + name + (each ? ", a separation per candidate" : ""));
    }
}

// Raw calls of every kind and option on `queries_of(kind)` (3D or 2D queries).
template <class QueriesOf>
void expect_raw_calls_allocate_nothing(const QueriesOf& queries_of, const std::string& label) {
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex}) {
    const auto queries = queries_of(kind);
    const std::vector<double>& own = frame().separations[static_cast<int>(kind)];
    ASSERT_EQ(queries.size(), own.size());
    for (const auto& [name, own_options] : option_sets())
      for (bool each : {false, true}) {
        const Options& options = own_options;  // a reference, not a binding: the lambda captures it
        expect_no_allocation_after_warm_up(
            [&](int threads, BatchResult& out) {
              Options with = options;
              with.threads = threads;
              batch_ccd(kind, std::span(queries), each ? std::span<const double>(own) : std::span<const double>{},
                        with, out);
            },
            options.threads, label + " " + to_string(kind) + ", " + name + (each ? ", a separation per query" : ""));
      }
  }
}

TEST(NoAllocation, RawCallsOfEveryKindAndOption) {
  expect_raw_calls_allocate_nothing([](Kind kind) { return frame().queries(kind); }, "batch_ccd");
}

// 2D queries are lifted into storage the thread keeps: none after the first call.
TEST(NoAllocation, RawCallsIn2D) {
  expect_raw_calls_allocate_nothing(
      [](Kind kind) {
        std::vector<Query2D> queries;
        for (const Query& query : frame().queries(kind)) {
          Query2D flat;
          for (int k = 0; k < 8; ++k) flat.points[k] = query.points[k].head<2>();
          queries.push_back(flat);
        }
        return queries;
      },
      "batch_ccd 2D");
}

TEST(NoAllocation, CollisionFreeStepsize) {
  const double min_distance = 1e-3 * scenes::mean_edge_length(frame().view());
  for (int threads : {1, 2})
    expect_no_allocation_after_warm_up(
        [&](int workers, BatchResult&) {
          ipc::collision_free_stepsize(frame().view(), frame().lists, min_distance, ipc::DEFAULT_CCD_TOLERANCE,
                                       ipc::DEFAULT_CCD_MAX_ITERATIONS, ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING,
                                       workers);
        },
        threads, "collision_free_stepsize, threads " + std::to_string(threads));
}

}  // namespace
}  // namespace batchccd

// The shrinking window (docs/design.md §12): a survivor asked over
// [0, window] instead of [0, tmax] gets the same answer whenever its contact
// counts (toi below the window), so the earliest TOI of mesh_ccd's
// earliest-TOI-only calls and of ipc::collision_free_stepsize is the minimum
// of the per-candidate answers, whatever the order in which threads find
// contacts.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "broad_phase.hpp"
#include "ipc_rules.hpp"
#include "query_builders.hpp"
#include "falling_contacts.hpp"
#include "scenes.hpp"
#include "scheduler/shrinking_window.hpp"

namespace batchccd {
namespace {

using testing::candidate_queries;
using testing::KindQuery;

struct SceneCase {
  std::string name;
  scenes::MovingMesh mesh;
  Candidates candidates;
  double edge_length = 0;
};

SceneCase scene_case(scenes::MovingMesh mesh) {
  SceneCase scene{mesh.name, std::move(mesh), {}, 0};
  scene.edge_length = scenes::mean_edge_length(scene.mesh.view());
  scene.candidates = scenes::swept_box_candidates(scene.mesh.view(), scene.edge_length);
  return scene;
}

// Cloth frames with contacts, and rigid bodies: warped, and exactly flat
// (coplanar pairs, decided by the planar search).
std::vector<SceneCase> scene_cases() {
  std::vector<SceneCase> cases;
  for (const int frame : {73, 76, 90})
    cases.push_back(scene_case(scenes::cloth_scene({.resolution = 16, .frames = 100, .frame = frame})));
  cases.push_back(scene_case(scenes::rigid_scene({.resolution = 2})));
  cases.push_back(scene_case(scenes::rigid_scene({.resolution = 2, .warp = 0})));
  return cases;
}

// Windows above a TOI: from `from` (the window past it that counts) to the
// end of the step, and those below `from`, just above the TOI.
std::vector<double> windows_from(double from) {
  std::vector<double> windows;
  for (const double window : {from, std::nextafter(from, 2.0), 2 * from, 0.5 * (from + 1), 1.0})
    if (window >= from && window <= 1) windows.push_back(window);
  return windows;
}
std::vector<double> windows_within(double toi, double from) {
  std::vector<double> windows;
  for (const double window : {std::nextafter(toi, 2.0), toi + 1e-12, toi + 1e-9, std::nextafter(from, 0.0)})
    if (window > toi && window < from) windows.push_back(window);
  return windows;
}

// At most `count` of `items`, spread over all of them.
template <class T>
std::vector<T> spread(const std::vector<T>& items, std::size_t count) {
  if (items.size() <= count) return items;
  std::vector<T> some;
  for (std::size_t k = 0; k < count; ++k) some.push_back(items[k * items.size() / count]);
  return some;
}

// A hit's TOI, asked again with tmax from window_tmax above it, in both
// certified modes, touching and at a separation: the same hit, the same
// TOI. With tmax closer above the TOI, the contact may lie after tmax (a TOI
// is a lower bound): then a miss, or a TOI no earlier -- which never lowers
// a minimum already at or below that tmax.
TEST(ShrinkingWindow, AHitsToiDoesNotDependOnTmaxAboveIt) {
  int checked = 0, within = 0;
  for (const SceneCase& scene : scene_cases()) {
    const std::vector<KindQuery> queries = candidate_queries(scene.mesh.view(), scene.candidates);
    for (const Mode mode : {Mode::conservative, Mode::exact})
      for (const double separation : {0.0, 1e-3 * scene.edge_length, 1e-2 * scene.edge_length}) {
        Options options;
        options.mode = mode;
        options.min_distance = separation;
        std::vector<std::pair<KindQuery, double>> hits;
        for (const KindQuery& q : queries) {
          const QueryResult result = query_ccd(q.kind, q.query, options);
          if (result.hit) hits.push_back({q, result.toi});
        }
        for (const auto& hit : spread(hits, 150)) {
          const KindQuery& q = hit.first;  // named, not bound: lambdas below capture them
          const double toi = hit.second;
          const auto again = [&](double window) {
            Options in_window = options;
            in_window.tmax = window;
            return query_ccd(q.kind, q.query, in_window);
          };
          const auto where = [&](double window, const QueryResult& result) {
            return ::testing::Message() << scene.name << ' ' << to_string(mode) << " min_distance " << separation << ' '
                                        << to_string(q.kind) << ": toi " << toi << " over [0, 1], "
                                        << (result.hit ? result.toi : -1.0) << " over [0, " << window << "] ("
                                        << window - toi << " above)";
          };
          const double from = window_tmax(toi, options);
          for (const double window : windows_from(from)) {
            const QueryResult result = again(window);
            EXPECT_TRUE(result.hit && result.toi == toi) << where(window, result);
            ++checked;
          }
          for (const double window : windows_within(toi, from)) {
            const QueryResult result = again(window);
            EXPECT_TRUE(!result.hit || (result.toi >= toi && result.toi <= window)) << where(window, result);
            within += !result.hit || result.toi != toi;
          }
        }
      }
  }
  EXPECT_GT(checked, 5000);
  EXPECT_GT(within, 0) << "no window within a TOI's tolerance changed an answer: is the margin needed?";
}

// The same for ipc-toolkit's rules around a query (ipc.hpp), which
// collision_free_stepsize asks with tmax ipc_window_tmax of the earliest
// step found so far.
TEST(ShrinkingWindow, AnIpcStepDoesNotDependOnTmaxAboveIt) {
  int checked = 0;
  for (const SceneCase& scene : scene_cases()) {
    const std::vector<KindQuery> queries = candidate_queries(scene.mesh.view(), scene.candidates);
    for (const double separation : {0.0, 1e-3 * scene.edge_length}) {
      const auto decide = [&](const KindQuery& q, double tmax, double& toi) {
        return ipc::rules::decide(q.kind, q.query, toi, separation, tmax, ipc::DEFAULT_CCD_TOLERANCE,
                                  ipc::DEFAULT_CCD_MAX_ITERATIONS, ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING);
      };
      std::vector<std::pair<KindQuery, double>> steps;
      for (const KindQuery& q : queries)
        if (double toi = 1; decide(q, 1.0, toi)) steps.push_back({q, toi});
      for (const auto& [q, toi] : spread(steps, 150))
        for (const double window : windows_from(ipc_window_tmax(toi, ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING))) {
          double again = -1;
          EXPECT_TRUE(decide(q, window, again) && again == toi)
              << scene.name << " min_distance " << separation << ' ' << to_string(q.kind) << ": step " << toi
              << " over [0, 1], " << again << " over [0, " << window << "]";
          ++checked;
        }
    }
  }
  EXPECT_GT(checked, 1000);
}

// Two vertices falling onto one triangle, the later step listed first: the
// earlier one's step comes from the small-toi retry (its first toi is
// below 1e-6) and is rescaled below the later one's step, while its
// contact comes after it. Asked with the later step as tmax, the retry
// would miss its contact; one thread asks them in list order.
TEST(ShrinkingWindow, ARescaledStepBelowTheWindowIsNotLost) {
  Eigen::MatrixXd x0(5, 3);
  x0 << -1, -1, 0, 3, -1, 0, -1, 3, 0, 0, 0, 1.3e-6, 0.5, 0.5, 1.2e-6;
  Eigen::MatrixXd x1 = x0;
  x1.col(2).tail(2).array() -= 1;  // both fall at speed 1
  const Eigen::MatrixXi faces = (Eigen::MatrixXi(1, 3) << 0, 1, 2).finished();
  const std::vector<std::array<int, 2>> vertex_face{{3, 0}, {4, 0}};
  const MeshView mesh{x0, x1, faces};
  std::vector<double> steps;
  for (const KindQuery& q : candidate_queries(mesh, {.vertex_face = vertex_face})) {
    double toi = 1;
    ASSERT_TRUE(ipc::rules::decide(q.kind, q.query, toi, 0.0, 1.0, ipc::DEFAULT_CCD_TOLERANCE,
                                   ipc::DEFAULT_CCD_MAX_ITERATIONS, ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING));
    steps.push_back(toi);
  }
  ASSERT_LT(steps[1], steps[0]);
  ASSERT_LT(steps[0], 1.2e-6 - 1e-7);  // the second's contact lies beyond the first's step
  for (const int threads : {1, 2})
    EXPECT_EQ(ipc::collision_free_stepsize(mesh, {.vertex_face = vertex_face}, 0.0, ipc::DEFAULT_CCD_TOLERANCE,
                                           ipc::DEFAULT_CCD_MAX_ITERATIONS, ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING,
                                           threads),
              steps[1])
        << threads << " threads";
}

// mesh_ccd asked for the earliest TOI only (no per-candidate results, no
// hit list) shrinks its window as it finds contacts: its earliest TOI is
// the minimum of the per-candidate results, for any thread count.
TEST(ShrinkingWindow, MeshCcdsEarliestToiIsTheMinimumOfItsResults) {
  int with_contact = 0, shrunk = 0;
  for (const SceneCase& scene : scene_cases())
    for (const Mode mode : {Mode::conservative, Mode::exact})
      for (const double separation : {0.0, 1e-3 * scene.edge_length, 1e-2 * scene.edge_length})
        for (const double tmax : {1.0, 0.5}) {
          SCOPED_TRACE(::testing::Message() << scene.name << ' ' << to_string(mode) << " min_distance "
                                            << separation << " tmax " << tmax);
          Options options;
          options.mode = mode;
          options.min_distance = separation;
          options.tmax = tmax;
          options.threads = 1;
          const BatchResult full = mesh_ccd(scene.mesh.view(), scene.candidates, options);
          double minimum = std::numeric_limits<double>::infinity();
          for (const QueryResult& result : full.results)
            if (result.hit) minimum = std::min(minimum, result.toi);
          ASSERT_EQ(full.earliest_toi, minimum);
          with_contact += minimum < tmax;
          options.per_candidate_results = false;
          for (const int threads : {1, 2}) {
            options.threads = threads;
            const BatchResult earliest = mesh_ccd(scene.mesh.view(), scene.candidates, options);
            EXPECT_EQ(earliest.earliest_toi, minimum) << threads << " threads";
            EXPECT_EQ(earliest.counters.candidates, full.counters.candidates);
            EXPECT_LE(earliest.counters.hits, full.counters.hits);
            shrunk += threads == 1 && earliest.counters.hits < full.counters.hits;
          }
        }
  EXPECT_GE(with_contact, 20);
  EXPECT_GE(shrunk, with_contact / 2) << "the window should spare most calls with contacts some of their hits";
}

// Contacts at falling times (falling_contacts.hpp), each the earliest once:
// mesh_ccd asked for the earliest TOI only filters each batch over the part
// of the step the contacts before it left open, and must still find it, in
// every mode, with and without separations (one for all, one per candidate).
TEST(ShrinkingWindow, MeshCcdFiltersOverTheOpenPartOfTheStepMissNoEarlierContact) {
  const std::vector<std::vector<double>> times = testing::falling_contact_times();
  for (std::size_t last_list = 0; last_list < times.size(); ++last_list)
    for (std::size_t last = 0; last < times[last_list].size(); ++last) {
      const testing::FallingContacts scene = testing::falling_contacts(last_list, last);
      const CandidateLists& lists = scene.candidates;
      const auto each = [](std::size_t count, double s) { return std::vector<double>(count, s); };
      const std::vector<double> vf = each(lists.vertex_face.size(), 1e-3), ee = each(lists.edge_edge.size(), 2e-3),
                                ve = each(lists.vertex_edge.size(), 1e-3), vv = each(lists.vertex_vertex.size(), 0);
      for (const Mode mode : {Mode::conservative, Mode::exact})
        for (const bool per_candidate : {false, true}) {
          SCOPED_TRACE(::testing::Message() << "earliest at " << times[last_list][last] << ' ' << to_string(mode)
                                            << (per_candidate ? " per-candidate separations" : ""));
          const MinDistances separations =
              per_candidate ? MinDistances{vf, ee, ve, vv} : MinDistances{};
          Options options;
          options.mode = mode;
          BatchResult full;
          mesh_ccd(scene.view(), lists, separations, options, full);
          double minimum = std::numeric_limits<double>::infinity();
          for (const QueryResult& result : full.results)
            if (result.hit) minimum = std::min(minimum, result.toi);
          EXPECT_LT(minimum, times[last_list][last]);
          options.per_candidate_results = false;
          for (const int threads : {1, 2}) {
            options.threads = threads;
            BatchResult earliest;
            mesh_ccd(scene.view(), lists, separations, options, earliest);
            EXPECT_EQ(earliest.earliest_toi, minimum) << threads << " threads";
            EXPECT_EQ(earliest.counters.candidates, full.counters.candidates);
          }
        }
    }
}

}  // namespace
}  // namespace batchccd

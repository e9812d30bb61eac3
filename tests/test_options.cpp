// The knobs of options.hpp and batch.hpp each doing what its comment says:
// tolerance, toi_tolerance and its floor, max_iterations at a separation,
// threads <= 0, candidate lists switched off (and the result layout then),
// Counters::operator+=, per-candidate separations of a mesh call.
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <oneapi/tbb/task_arena.h>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "exact_distance.hpp"
#include "same_answers.hpp"

namespace batchccd {
namespace {

using testing::Rational;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The unit right triangle in z = 0, still, and a vertex falling through
// z = 0 from z = 1 at speed `3` over the point (x, y): at t = 1/3 (not
// dyadic: no time the solver bisects to lands on it).
Query vertex_falling_at(double x, double y) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return {{Vec3(x, y, 1), a, b, c, Vec3(x, y, -2), a, b, c}};
}

// The vertex goes from above the triangle's middle (t = 0) to below and
// past its hypotenuse x + y = 1 (t = 1), crossing z = 0 just outside it:
// its path and the hypotenuse are skew lines `gap` apart (2 delta / 3 for
// delta = 3 gap / 2), the closest approach. No plane separates the two
// throughout, so no filter settles it: a search must.
Query vertex_passing_the_hypotenuse(double gap) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const double end = 0.75 + 1.5 * gap;
  return {{Vec3(0.25, 0.25, 1), a, b, c, Vec3(end, end, -1), a, b, c}};
}

// The generic search alone (planar path and swept boxes off): what
// Options::tolerance governs.
const lab::Settings kSearchAlone{.swept_box_filter = false, .planar_path = false};

// 2^-45 past the hypotenuse: within any of these tolerances, reported as
// a contact (Options::tolerance) -- and then, the promise of conservative
// mode, with the primitives within tolerance of each other at the TOI.
TEST(Tolerance, ANearMissIsReportedOnlyWithinIt) {
  const Query near_miss = vertex_passing_the_hypotenuse(0x1p-45);
  for (const double tolerance : {1e-9, 1e-6, 1e-2, 0.1}) {
    Options options;
    options.tolerance = tolerance;
    options.exact_stage_iterations = options.max_iterations;  // no exact stage: the search's own answer
    const QueryResult result = query_ccd(Kind::vertex_face, near_miss, options);
    ASSERT_TRUE(result.hit) << "tolerance " << tolerance;
    // The widest extent of the query's points along an axis: no definition
    // of the query's size the promise uses is larger.
    const Rational reach = 4 * tolerance * testing::query_size(near_miss);
    EXPECT_LE(testing::squared_distance_at(Kind::vertex_face, near_miss, result.toi), reach * reach)
        << "tolerance " << tolerance << ", toi " << result.toi;
  }
}

TEST(Tolerance, ZeroNegativeOrNanSendsNearContactsToTheExactStage) {
  // The same near miss: with nothing within tolerance only exact
  // arithmetic decides it, and it is a miss.
  const Query near_miss = vertex_passing_the_hypotenuse(0x1p-45);
  for (const double tolerance : {0.0, -1.0, kNaN}) {
    Options options;
    options.tolerance = tolerance;
    options.exact_stage_iterations = 1 << 10;
    const BatchResult batch = lab::batch_ccd(Kind::vertex_face, std::vector{near_miss}, options, kSearchAlone);
    EXPECT_FALSE(batch.results[0].hit) << "tolerance " << tolerance;
    EXPECT_EQ(batch.counters.exact_escalations, 1) << "tolerance " << tolerance;
  }
}

// A clean crossing at t = 1/3: the TOI at most toi_tolerance before it,
// never after; values below 2^-45 (zero, negative and NaN too) act as 2^-45.
TEST(ToiTolerance, BoundsHowEarlyTheToiIsDownToItsFloor) {
  const Query crossing = vertex_falling_at(0.25, 0.25);
  const Rational root(1, 3);
  for (const double toi_tolerance : {1e-2, 1e-4, 1e-7, 1e-10, 0x1p-45, 0x1p-60, 0.0, -1.0, kNaN}) {
    Options options;
    options.toi_tolerance = toi_tolerance;
    const QueryResult result = query_ccd(Kind::vertex_face, crossing, options);
    ASSERT_TRUE(result.hit) << toi_tolerance;
    EXPECT_LE(Rational(result.toi), root) << toi_tolerance;
    EXPECT_LE(root - Rational(result.toi), Rational(std::max(0x1p-45, toi_tolerance))) << toi_tolerance;
  }
}

// With min_distance > 0 the search gives up after max_iterations boxes
// (zero or negative: at the first) and reports a hit, counted undecided:
// a miss is never claimed unproven.
TEST(MaxIterations, ExhaustedAtASeparationIsAnUndecidedHit) {
  // Edge a on the x axis, still, ending a little short of x = 1/2; edge b
  // turns about its middle, held 1.625 2^-7 above the axis at x = 1/2. b's
  // line comes within the separation of a's line, but beyond a's end: the
  // edges keep 1.07 times the separation apart, closest at a's end (so
  // neither the lines' distance nor a fixed direction proves it), a miss
  // only a long search proves.
  const double height = 0x1p-7 * 1.625, end = 0.5 - 0x1p-7 * 0.75;
  const std::vector<Query> queries{Query{{Vec3(0, 0, 0), Vec3(end, 0, 0), Vec3(0.5, -1, 1 + height),
                                          Vec3(0.5, 1, -1 + height), Vec3(0, 0, 0), Vec3(end, 0, 0),
                                          Vec3(0.5, -1, -1 + height), Vec3(0.5, 1, 1 + height)}}};
  for (const Mode mode : {Mode::conservative, Mode::exact}) {
    SCOPED_TRACE(to_string(mode));
    Options options;
    options.mode = mode;
    options.min_distance = 1e-2;
    const BatchResult decided = batch_ccd(Kind::edge_edge, queries, options);
    EXPECT_FALSE(decided.results[0].hit);
    EXPECT_EQ(decided.counters.undecided, 0);
    for (const std::int64_t budget : {std::int64_t{16}, std::int64_t{1}, std::int64_t{0}, std::int64_t{-3}}) {
      options.max_iterations = budget;
      const BatchResult exhausted = batch_ccd(Kind::edge_edge, queries, options);
      EXPECT_TRUE(exhausted.results[0].hit) << "budget " << budget;
      EXPECT_EQ(exhausted.counters.undecided, 1) << "budget " << budget;
      EXPECT_EQ(exhausted.counters.hits, 1) << "budget " << budget;
    }
  }
}

// A falling vertex over a square of two triangles, its edges, a static
// vertex: candidates of every kind, some hits and some misses.
struct SmallMesh {
  Eigen::MatrixXd x0{6, 3}, x1;
  Eigen::MatrixXi faces{2, 3};
  Candidates candidates;

  SmallMesh() {
    x0 << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1, 2, 2, 0;
    x1 = x0;
    x1.row(4) << 0.5, 0.5, -1;
    faces << 0, 1, 2, 0, 2, 3;
    candidates.vertex_face = {{4, 0}, {4, 1}, {5, 0}};
    candidates.edge_edge = {{0, 1, 2, 3}, {0, 2, 4, 5}};
    candidates.vertex_edge = {{4, 0, 2}, {5, 1, 2}};
    candidates.vertex_vertex = {{4, 2}, {5, 2}, {4, 0}};
  }
  MeshView view() const { return {x0, x1, faces}; }
};

// A threads value of 0 or below runs in the caller's arena: the same
// answers as one thread, inside a one-thread arena too.
TEST(Threads, ZeroOrNegativeRunInTheCallersArena) {
  const SmallMesh mesh;
  Options one;
  one.threads = 1;
  one.min_distance = 0.3;
  const BatchResult reference = mesh_ccd(mesh.view(), mesh.candidates, one);
  for (const int threads : {0, -1, -8, std::numeric_limits<int>::min()}) {
    Options options = one;
    options.threads = threads;
    BatchResult result;
    ASSERT_NO_THROW(result = mesh_ccd(mesh.view(), mesh.candidates, options)) << threads;
    testing::expect_same_answers(result, reference, "threads " + std::to_string(threads));
    tbb::task_arena single(1);
    single.execute([&] { result = mesh_ccd(mesh.view(), mesh.candidates, options); });
    testing::expect_same_answers(result, reference, "in a one-thread arena, threads " + std::to_string(threads));
  }
}

// A list switched off gets no results and no counts; the others keep their
// answers, in the order vertex-face, edge-edge, vertex-edge, vertex-vertex,
// and the hit list numbers them in that order.
TEST(CandidateListSwitches, ListsLeftOutGetNoResultsAndTheRestCloseUp) {
  const SmallMesh mesh;
  Options all;
  all.min_distance = 0.3;
  all.hit_list = true;
  const BatchResult full = mesh_ccd(mesh.view(), mesh.candidates, all);
  const std::array<std::size_t, 4> sizes = {mesh.candidates.vertex_face.size(), mesh.candidates.edge_edge.size(),
                                            mesh.candidates.vertex_edge.size(),
                                            mesh.candidates.vertex_vertex.size()};
  ASSERT_EQ(full.results.size(), sizes[0] + sizes[1] + sizes[2] + sizes[3]);
  std::size_t full_hits = 0;
  for (const QueryResult& r : full.results) full_hits += r.hit;
  ASSERT_GT(full_hits, 0u);
  ASSERT_LT(full_hits, full.results.size());
  for (int mask = 0; mask < 16; ++mask) {
    Options options = all;
    const std::array<bool, 4> on = {(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0};
    options.vertex_face = on[0];
    options.edge_edge = on[1];
    options.vertex_edge = on[2];
    options.vertex_vertex = on[3];
    BatchResult expected;
    std::size_t start = 0;
    for (int list = 0; list < 4; ++list) {
      if (on[list])
        expected.results.insert(expected.results.end(), full.results.begin() + static_cast<std::ptrdiff_t>(start),
                                full.results.begin() + static_cast<std::ptrdiff_t>(start + sizes[list]));
      start += sizes[list];
    }
    const BatchResult result = mesh_ccd(mesh.view(), mesh.candidates, options);
    const std::string what = "lists " + std::to_string(mask);
    testing::expect_same_answers(result, expected, what);
    EXPECT_EQ(result.counters.candidates, static_cast<std::int64_t>(expected.results.size())) << what;
    std::vector<std::size_t> hits;
    double earliest = kInfinity;
    for (std::size_t i = 0; i < expected.results.size(); ++i)
      if (expected.results[i].hit) {
        hits.push_back(i);
        earliest = std::min(earliest, expected.results[i].toi);
      }
    EXPECT_EQ(result.counters.hits, static_cast<std::int64_t>(hits.size())) << what;
    EXPECT_EQ(result.earliest_toi, earliest) << what;
    ASSERT_EQ(result.hits.size(), hits.size()) << what;
    for (std::size_t h = 0; h < hits.size(); ++h) {
      EXPECT_EQ(result.hits[h].candidate, hits[h]) << what;
      EXPECT_EQ(result.hits[h].toi, expected.results[hits[h]].toi) << what;
    }
  }
}

// Every field summed, but the slowest query's time, which is the larger.
TEST(CountersSum, AddingSumsEveryCountAndKeepsTheSlowestQuery) {
  Counters a{.candidates = 1, .culled = 2, .culled_by_sign = 3, .culled_by_separation = 4, .culled_by_pieces = 5,
             .culled_by_swept_box = 6, .solved = 7, .hits = 8, .undecided = 9, .invalid = 10,
             .exact_escalations = 11, .max_query_seconds = 0.5, .solved_seconds = 13, .escalated_seconds = 14};
  const Counters b{.candidates = 100, .culled = 200, .culled_by_sign = 300, .culled_by_separation = 400,
                   .culled_by_pieces = 500, .culled_by_swept_box = 600, .solved = 700, .hits = 800,
                   .undecided = 900, .invalid = 1000, .exact_escalations = 1100, .max_query_seconds = 0.25,
                   .solved_seconds = 1300, .escalated_seconds = 1400};
  Counters& same = (a += b);
  EXPECT_EQ(&same, &a);
  EXPECT_EQ(a.candidates, 101);
  EXPECT_EQ(a.culled, 202);
  EXPECT_EQ(a.culled_by_sign, 303);
  EXPECT_EQ(a.culled_by_separation, 404);
  EXPECT_EQ(a.culled_by_pieces, 505);
  EXPECT_EQ(a.culled_by_swept_box, 606);
  EXPECT_EQ(a.solved, 707);
  EXPECT_EQ(a.hits, 808);
  EXPECT_EQ(a.undecided, 909);
  EXPECT_EQ(a.invalid, 1010);
  EXPECT_EQ(a.exact_escalations, 1111);
  EXPECT_EQ(a.max_query_seconds, 0.5);
  EXPECT_EQ(a.solved_seconds, 1313);
  EXPECT_EQ(a.escalated_seconds, 1414);
  Counters c{.max_query_seconds = 0.125};
  c += Counters{.max_query_seconds = 2};
  EXPECT_EQ(c.max_query_seconds, 2);
}

// A mesh call's per-candidate separations: a span of another length than
// its list, or a negative, NaN or infinite value, refuses the whole call
// naming the list (and the index and value), and leaves `out` as it was.
TEST(MeshMinDistances, WrongLengthOrBadValueRefusesTheCall) {
  const SmallMesh mesh;
  Options options;
  options.hit_list = true;
  BatchResult out;
  mesh_ccd(mesh.view(), mesh.candidates, MinDistances{}, options, out);
  const BatchResult before = out;
  const auto expect_refused = [&](const MinDistances& separations, const std::vector<std::string>& named) {
    try {
      mesh_ccd(mesh.view(), mesh.candidates, separations, options, out);
      ADD_FAILURE() << "accepted; expected a message with " << named.front();
    } catch (const std::invalid_argument& error) {
      for (const std::string& word : named)
        EXPECT_NE(std::string(error.what()).find(word), std::string::npos) << error.what();
    }
    testing::expect_same_answers(out, before, named.front());
    EXPECT_EQ(out.counters.candidates, before.counters.candidates);
    EXPECT_EQ(out.hits.size(), before.hits.size());
  };
  const std::vector<double> two = {0.1, 0.1}, four = {0.1, 0.1, 0.1, 0.1};
  expect_refused({.vertex_face = two}, {"vertex-face min_distances", "2 values for 3 candidates"});
  expect_refused({.edge_edge = four}, {"edge-edge min_distances", "4 values for 2 candidates"});
  expect_refused({.vertex_edge = four}, {"vertex-edge min_distances", "4 values for 2 candidates"});
  expect_refused({.vertex_vertex = two}, {"vertex-vertex min_distances", "2 values for 3 candidates"});
  const std::vector<double> negative = {0.1, -0.5}, nan = {kNaN, 0.1, 0.1}, infinite = {0.1, kInfinity};
  expect_refused({.edge_edge = negative}, {"edge-edge candidate 1", "got -0.5"});
  const std::vector<double> minus_one = {0.1, 0.1, -1};
  expect_refused({.vertex_face = minus_one}, {"vertex-face candidate 2: min_distance must be >= 0 and finite, got -1"});
  expect_refused({.vertex_vertex = nan}, {"vertex-vertex candidate 0", "nan"});
  expect_refused({.vertex_edge = infinite}, {"vertex-edge candidate 1", "inf"});
  // Even for a list the options switch off.
  options.vertex_face = false;
  expect_refused({.vertex_face = two}, {"vertex-face min_distances", "2 values for 3 candidates"});
}


// Per-candidate separations of 0 for every candidate mean separation 0: the
// same call as no list with Options::min_distance = 0 (a list replaces it),
// the same answers, filters and counters, for the modes and the fast
// baseline alike, raw queries and a mesh.
TEST(PerCandidateSeparations, AllZerosAreTheCallWithoutASeparation) {
  std::mt19937_64 rng(0x5e9a0);
  std::uniform_real_distribution<double> coordinate(-1, 1), displacement(-0.6, 0.6);
  std::vector<Query> queries(4096);
  for (Query& q : queries)
    for (int i = 0; i < 4; ++i) {
      q.points[i] = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
      q.points[i + 4] = q.points[i] + Vec3(displacement(rng), displacement(rng), displacement(rng));
    }
  const std::vector<double> zeros(queries.size(), 0.0);
  const auto expect_same_call = [](const BatchResult& listed, const BatchResult& plain, const std::string& what) {
    testing::expect_same_answers(listed, plain, what);
    testing::expect_same_counts(listed, plain, what);
  };
  for (const lab::Method& method : {lab::kConservative, lab::kExact, lab::kFast}) {
    const Options plain_options = method.applied_to({});
    Options listed_options = plain_options;
    listed_options.min_distance = 0.25;  // replaced by the list
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      const std::string what = std::string(lab::to_string(method)) + ", " + to_string(kind);
      BatchResult plain, listed;
      lab::batch_ccd(kind, queries, {}, plain_options, method.settings(), plain);
      lab::batch_ccd(kind, queries, zeros, listed_options, method.settings(), listed);
      // The mix holds culls by the sign filter, survivors and hits.
      EXPECT_GT(plain.counters.culled_by_sign, 0) << what;
      EXPECT_GT(plain.counters.solved, 0) << what;
      EXPECT_GT(plain.counters.hits, 0) << what;
      expect_same_call(listed, plain, what);
    }
    const SmallMesh mesh;
    const std::vector<double> vf(3, 0.0), ee(2, 0.0), ve(2, 0.0), vv(3, 0.0);
    BatchResult plain, listed;
    lab::mesh_ccd(mesh.view(), mesh.candidates, MinDistances{}, plain_options, method.settings(), plain);
    lab::mesh_ccd(mesh.view(), mesh.candidates,
                  MinDistances{.vertex_face = vf, .edge_edge = ee, .vertex_edge = ve, .vertex_vertex = vv},
                  listed_options, method.settings(), listed);
    expect_same_call(listed, plain, std::string(lab::to_string(method)) + ", mesh");
  }
}

}  // namespace
}  // namespace batchccd

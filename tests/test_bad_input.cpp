// The contract for bad input (batch.hpp and query.hpp say it; this file holds
// the library to it), one section per class of input:
//
// - non-finite coordinates: that query alone gets Status::invalid_input with
//   hit = true and toi = 0, in every mode and instruction set; the others of
//   the same call get the answers they get alone;
// - empty inputs: an empty result, never an error;
// - mismatched or malformed matrices and out-of-range indices: mesh_ccd
//   throws std::invalid_argument before evaluating anything;
// - degenerate geometry (repeated face vertices, a vertex of its own face,
//   edges sharing a vertex, zero-length edges): valid, evaluated as the
//   geometry it describes;
// - bad files: the readers throw InputError naming the file and the line.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "temporary_directory.hpp"

namespace {

namespace fs = std::filesystem;
using batchccd::BatchResult;
using batchccd::Candidates;
using batchccd::Isa;
using batchccd::Kind;
using batchccd::MeshView;
using batchccd::Mode;
using batchccd::Options;
using batchccd::Query;
using batchccd::QueryResult;
using batchccd::Status;
using batchccd::Vec3;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
namespace lab = batchccd::lab;
// The modes and the baselines: bad input is refused or flagged by all alike.
constexpr std::array<lab::Method, 4> kMethods{lab::kConservative, lab::kFast, lab::kCubic, lab::kExact};
// The modes, which promise every contact.
constexpr std::array<Mode, 2> kCertifiedModes{Mode::conservative, Mode::exact};
constexpr std::array<double, 3> kNonFinite{kNaN, kInfinity, -kInfinity};
// How much earlier than the true contact a conservative TOI may lie.
constexpr double kToiSlack = 1e-6;

Options with_mode(Mode mode) {
  Options options;
  options.mode = mode;
  return options;
}


void expect_invalid(const QueryResult& r) {
  EXPECT_EQ(r.status, Status::invalid_input);
  EXPECT_TRUE(r.hit) << "a query that could not be evaluated must never read as 'no collision'";
  EXPECT_EQ(r.toi, 0.0);
}

void expect_hit_at(const QueryResult& r, double time) {
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_TRUE(r.hit);
  if (r.hit) {
    EXPECT_LE(r.toi, time) << "toi after the contact";
    EXPECT_GE(r.toi, time - kToiSlack);
  }
}

void expect_miss(const QueryResult& r) {
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_FALSE(r.hit) << "toi = " << r.toi;
  EXPECT_EQ(r.toi, kInfinity);
}

void expect_same(const QueryResult& actual, const QueryResult& expected) {
  EXPECT_EQ(actual.status, expected.status);
  EXPECT_EQ(actual.hit, expected.hit);
  EXPECT_EQ(actual.toi, expected.toi);
}

// ---------------------------------------------------------------------------
// Raw queries.

// The vertex falls through the static triangle (0,0,0), (4,0,0), (0,4,0) at t = 1/2.
const Query kVertexFaceHit{{Vec3(1, 1, 4), Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0),
                            Vec3(1, 1, -4), Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)}};
// The vertex stays far from it.
const Query kVertexFaceMiss{{Vec3(9, 9, 9), Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0),
                             Vec3(9, 9, 9), Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)}};
// Edge a sweeps down through edge b, [0, 4] on the x axis, at t = 1/2.
const Query kEdgeEdgeHit{{Vec3(2, -4, 4), Vec3(2, 4, 4), Vec3(0, 0, 0), Vec3(4, 0, 0),
                          Vec3(2, -4, -4), Vec3(2, 4, -4), Vec3(0, 0, 0), Vec3(4, 0, 0)}};
// Edge a stays far above edge b.
const Query kEdgeEdgeMiss{{Vec3(2, -4, 9), Vec3(2, 4, 9), Vec3(0, 0, 0), Vec3(4, 0, 0),
                           Vec3(2, -4, 9), Vec3(2, 4, 9), Vec3(0, 0, 0), Vec3(4, 0, 0)}};

const Query& hit_query(Kind kind) { return kind == Kind::vertex_face ? kVertexFaceHit : kEdgeEdgeHit; }
const Query& miss_query(Kind kind) { return kind == Kind::vertex_face ? kVertexFaceMiss : kEdgeEdgeMiss; }

Query with_coordinate(Query query, int coordinate, double value) {
  query.points[static_cast<std::size_t>(coordinate / 3)][coordinate % 3] = value;
  return query;
}

QueryResult run_kind_entry(Kind kind, const Query& q, const Options& options) {
  const auto& x = q.points;
  if (kind == Kind::vertex_face)
    return batchccd::vertex_face_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], options);
  return batchccd::edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], options);
}

TEST(BadInputNonFinite, AnyNonFiniteCoordinateIsInvalidInEveryModeAndEntryPoint) {
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const lab::Method& method : kMethods)
      for (const double bad : kNonFinite)
        for (int coordinate = 0; coordinate < 24; ++coordinate) {
          SCOPED_TRACE(std::string(batchccd::to_string(kind)) + " " + lab::to_string(method) +
                       ", coordinate " + std::to_string(coordinate) + " = " + std::to_string(bad));
          // Both a query that would hit and one that would miss: the answer
          // must not depend on what the finite coordinates say.
          for (const Query* base : {&hit_query(kind), &miss_query(kind)}) {
            const Query q = with_coordinate(*base, coordinate, bad);
            expect_invalid(lab::query_ccd(kind, q, method.applied_to({}), method.settings()));
            if (method.baseline == lab::Baseline::none) expect_invalid(run_kind_entry(kind, q, with_mode(method.mode)));
          }
        }
}

TEST(BadInputNonFinite, OnlyDecisionAskedStillInvalid) {
  Options options;
  options.need_toi = false;
  expect_invalid(batchccd::query_ccd(Kind::vertex_face, with_coordinate(kVertexFaceMiss, 5, kNaN), options));
  expect_invalid(batchccd::query_ccd(Kind::edge_edge, with_coordinate(kEdgeEdgeMiss, 23, kInfinity), options));
}

// Huge but finite coordinates are valid input, not errors.
TEST(BadInputNonFinite, LargestFiniteCoordinatesAreEvaluated) {
  const double big = std::numeric_limits<double>::max();
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const lab::Method& method : kMethods) {
      const QueryResult r =
          lab::query_ccd(kind, with_coordinate(miss_query(kind), 0, big), method.applied_to({}), method.settings());
      EXPECT_EQ(r.status, Status::ok) << lab::to_string(method);
      EXPECT_FALSE(std::isnan(r.toi));
    }
}

// A batch mixing queries: every valid one gets exactly its answer alone.
std::vector<Query> mixed_batch(Kind kind) {
  return {hit_query(kind),
          with_coordinate(miss_query(kind), 0, kNaN),
          miss_query(kind),
          with_coordinate(hit_query(kind), 13, kInfinity),
          hit_query(kind),
          with_coordinate(miss_query(kind), 23, -kInfinity),
          miss_query(kind)};
}

TEST(BadInputNonFinite, BatchAnswersValidQueriesAsAloneAndFlagsTheRest) {
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const lab::Method& method : kMethods)
      for (const Isa isa : batchccd::available_isas()) {
        SCOPED_TRACE(std::string(batchccd::to_string(kind)) + " " + lab::to_string(method) + " " +
                     batchccd::to_string(isa));
        const std::vector<Query> queries = mixed_batch(kind);
        Options options = method.applied_to({});
        options.isa = isa;
        const BatchResult batch = lab::batch_ccd(kind, queries, options, method.settings());
        ASSERT_EQ(batch.results.size(), queries.size());
        std::int64_t invalid = 0, hits = 0;
        for (std::size_t i = 0; i < queries.size(); ++i) {
          const QueryResult alone = lab::query_ccd(kind, queries[i], method.applied_to({}), method.settings());
          if (alone.status == Status::invalid_input) {
            expect_invalid(batch.results[i]);
            ++invalid;
          } else if (isa == Isa::scalar) {
            expect_same(batch.results[i], alone);
          } else {  // lane kernels agree decision for decision
            EXPECT_EQ(batch.results[i].status, alone.status) << "query " << i;
            EXPECT_EQ(batch.results[i].hit, alone.hit) << "query " << i;
          }
          hits += batch.results[i].hit ? 1 : 0;
        }
        EXPECT_EQ(invalid, 3);
        EXPECT_EQ(batch.counters.candidates, 7);
        EXPECT_EQ(batch.counters.invalid, 3);
        EXPECT_EQ(batch.counters.hits, hits);
        // An unevaluated query counts as a contact at t = 0.
        EXPECT_EQ(batch.earliest_toi, 0.0);
      }
}

TEST(BadInputNonFinite, CountersAndEarliestToiWithoutPerCandidateResults) {
  Options options;
  options.per_candidate_results = false;
  const BatchResult batch = batchccd::batch_ccd(Kind::edge_edge, mixed_batch(Kind::edge_edge), options);
  EXPECT_TRUE(batch.results.empty());
  EXPECT_EQ(batch.counters.candidates, 7);
  EXPECT_EQ(batch.counters.invalid, 3);
  EXPECT_EQ(batch.earliest_toi, 0.0);
}

// The point kinds: a non-finite coordinate of any point they read makes the
// query invalid, through the single calls and in a batch, whose valid query
// keeps its answer alone.
TEST(BadInputNonFinite, PointKindsFlagEveryNonFiniteCoordinate) {
  // The point falls through the segment [0, 4] of the x axis, or onto the
  // still point (2, 0, 0), at t = 1/2.
  for (const Kind kind : {Kind::vertex_edge, Kind::vertex_vertex}) {
    const bool edge = kind == Kind::vertex_edge;
    const std::vector<Vec3> start = edge ? std::vector{Vec3(2, 0, 4), Vec3(0, 0, 0), Vec3(4, 0, 0)}
                                         : std::vector{Vec3(2, 0, 4), Vec3(2, 0, 0)};
    std::vector<Vec3> end = start;
    end[0].z() = -4;
    const std::size_t count = start.size();
    const Query valid = batchccd::make_query(kind, start, end);
    expect_hit_at(batchccd::query_ccd(kind, valid), 0.5);
    for (const double bad : kNonFinite)
      for (std::size_t point = 0; point < 2 * count; ++point)
        for (int axis = 0; axis < 3; ++axis) {
          SCOPED_TRACE(std::string(batchccd::to_string(kind)) + " point " + std::to_string(point) + " axis " +
                       std::to_string(axis) + " = " + std::to_string(bad));
          std::vector<Vec3> t0 = start, t1 = end;
          (point < count ? t0[point] : t1[point - count])[axis] = bad;
          const Query spoiled = batchccd::make_query(kind, t0, t1);
          if (edge)
            expect_invalid(batchccd::vertex_edge_ccd(t0[0], t0[1], t0[2], t1[0], t1[1], t1[2]));
          else
            expect_invalid(batchccd::vertex_vertex_ccd(t0[0], t0[1], t1[0], t1[1]));
          for (const Mode mode : kCertifiedModes) {
            const BatchResult batch = batchccd::batch_ccd(kind, std::vector{spoiled, valid}, with_mode(mode));
            expect_invalid(batch.results[0]);
            expect_hit_at(batch.results[1], 0.5);
            EXPECT_EQ(batch.counters.invalid, 1);
          }
        }
  }
}

// The hit list names an invalid query as a hit at 0 with its status.
TEST(BadInputNonFinite, HitListFlagsTheInvalidQuery) {
  Options options;
  options.hit_list = true;
  const std::vector<Query> queries = {kVertexFaceMiss, with_coordinate(kVertexFaceMiss, 13, kNaN), kVertexFaceHit};
  const BatchResult batch = batchccd::batch_ccd(Kind::vertex_face, queries, options);
  ASSERT_EQ(batch.hits.size(), 2u);
  EXPECT_EQ(batch.hits[0].candidate, 1u);
  EXPECT_EQ(batch.hits[0].status, Status::invalid_input);
  EXPECT_EQ(batch.hits[0].toi, 0.0);
  EXPECT_EQ(batch.hits[1].candidate, 2u);
  EXPECT_EQ(batch.hits[1].status, Status::ok);
  EXPECT_EQ(batch.hits[1].toi, batch.results[2].toi);
}

// An instruction set this processor or build lacks is refused by every
// batch call, naming it; one it has runs.
TEST(BadInputOptions, AnUnavailableInstructionSetIsRefusedByName) {
  const std::vector<Isa> available = batchccd::available_isas();
  ASSERT_FALSE(available.empty());
  EXPECT_EQ(available.front(), Isa::scalar);
  const Eigen::MatrixXd positions = Eigen::MatrixXd::Zero(3, 3);
  const Eigen::MatrixXi faces = Eigen::MatrixXi::Zero(0, 3);
  int refused = 0;
  for (const auto& [name, isa] : batchccd::isa_names()) {
    if (isa == Isa::automatic) continue;
    Options options;
    options.isa = isa;
    const std::vector<Query> queries{kVertexFaceHit};
    if (std::find(available.begin(), available.end(), isa) != available.end()) {
      EXPECT_EQ(batchccd::resolve_isa(isa), isa);
      expect_hit_at(batchccd::batch_ccd(Kind::vertex_face, queries, options).results[0], 0.5);
      continue;
    }
    ++refused;
    for (const auto& call : std::vector<std::function<void()>>{
             [&] { batchccd::resolve_isa(options.isa); },
             [&] { batchccd::batch_ccd(Kind::vertex_face, queries, options); },
             [&] { batchccd::mesh_ccd({positions, positions, faces}, batchccd::CandidateLists{}, options); }}) {
      try {
        call();
        ADD_FAILURE() << batchccd::to_string(isa) << " accepted";
      } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find(batchccd::to_string(isa)), std::string::npos) << error.what();
      }
    }
  }
  std::printf("[ record   ] %d of %zu vector instruction sets unavailable here\n", refused,
              batchccd::isa_names().size() - 2);
}

// ---------------------------------------------------------------------------
// Empty inputs.

void expect_empty(const BatchResult& batch) {
  EXPECT_TRUE(batch.results.empty());
  EXPECT_EQ(batch.earliest_toi, kInfinity);
  EXPECT_EQ(batch.counters.candidates, 0);
  EXPECT_EQ(batch.counters.culled, 0);
  EXPECT_EQ(batch.counters.solved, 0);
  EXPECT_EQ(batch.counters.hits, 0);
  EXPECT_EQ(batch.counters.undecided, 0);
  EXPECT_EQ(batch.counters.invalid, 0);
}

TEST(BadInputEmpty, EmptyQueryListGivesEmptyResult) {
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const lab::Method& method : kMethods)
      for (const Isa isa : batchccd::available_isas()) {
        Options options = method.applied_to({});
        options.isa = isa;
        expect_empty(lab::batch_ccd(kind, {}, options, method.settings()));
        options.per_candidate_results = false;
        expect_empty(lab::batch_ccd(kind, std::vector<Query>{}, options, method.settings()));
      }
}

TEST(BadInputEmpty, EmptyMeshWithoutCandidatesGivesEmptyResult) {
  const Eigen::MatrixXd none_3(0, 3);
  const Eigen::MatrixXi no_faces_3(0, 3);
  expect_empty(batchccd::mesh_ccd({none_3, none_3, no_faces_3}, batchccd::CandidateLists{}));
  // Default-constructed (0 x 0) matrices and views describe the same empty mesh.
  const Eigen::MatrixXd none;
  const Eigen::MatrixXi no_faces;
  expect_empty(batchccd::mesh_ccd({none, none, no_faces}, batchccd::CandidateLists{}));
  expect_empty(batchccd::mesh_ccd(batchccd::MeshView{}, batchccd::CandidateLists{}));
  expect_empty(batchccd::mesh_ccd(batchccd::MeshView{}, batchccd::EdgeIdCandidates{}));
}

// ---------------------------------------------------------------------------
// A small mesh with every degenerate case a simulator's mesh can hold.

struct TestMesh {
  Eigen::MatrixXd t0;
  Eigen::MatrixXd t1;
  Eigen::MatrixXi faces;
  Candidates candidates;
  MeshView view() const { return {t0, t1, faces}; }
};

// Vertices (t0 -> t1):
//   0 (0,0,0), 1 (4,0,0), 2 (0,4,0)     still
//   3 (1,1,4) -> (1,1,-4)              falls through triangle 0-1-2 at t = 1/2
//   4 (10,10,10)                        still, far away
//   5 (2,-4,4) -> (2,-4,-4), 6 (2,4,4) -> (2,4,-4)
//                                       edge 5-6 sweeps through edge 0-1 at t = 1/2
//   7 (2,0,4) -> (2,0,-4)              falls through the segment 0-1 at t = 1/2
//   8 (2,1,4) -> (2,1,-4)              falls beside the segment 0-1 (y = 1)
//   9 (0,4,4) -> (0,4,-4)              falls through vertex 2 at t = 1/2
// Faces: 0 = (0,1,2); 1 = (0,0,1), the segment 0-1; 2 = (2,2,2), the point 2.
TestMesh degenerate_mesh() {
  TestMesh mesh;
  mesh.t0.resize(10, 3);
  mesh.t1.resize(10, 3);
  mesh.t0 << 0, 0, 0, 4, 0, 0, 0, 4, 0, 1, 1, 4, 10, 10, 10, 2, -4, 4, 2, 4, 4, 2, 0, 4, 2, 1, 4, 0, 4, 4;
  mesh.t1 = mesh.t0;
  for (const int moving : {3, 5, 6, 7, 8, 9}) mesh.t1(moving, 2) = -4;
  mesh.faces.resize(3, 3);
  mesh.faces << 0, 1, 2, 0, 0, 1, 2, 2, 2;
  mesh.candidates.vertex_face = {{3, 0}, {4, 0}, {0, 0}, {7, 1}, {8, 1}, {9, 2}, {3, 2}};
  mesh.candidates.edge_edge = {{5, 6, 0, 1}, {5, 6, 2, 4}, {0, 1, 0, 2}, {0, 1, 1, 0}, {7, 7, 0, 1}, {8, 8, 0, 1}};
  return mesh;
}

// The exact answers, in the order of degenerate_mesh's candidates (vertex-face
// first); the contact times are all 1/2 or 0.
struct Expected {
  const char* what;
  bool hit;
  double time;
};
const std::vector<Expected> kExpected = {
    {"vertex 3 through triangle 0", true, 0.5},
    {"vertex 4 far from triangle 0", false, 0},
    {"vertex 0, a corner of its own face", true, 0.0},
    {"vertex 7 through the segment face (0,0,1)", true, 0.5},
    {"vertex 8 beside the segment face (0,0,1)", false, 0},
    {"vertex 9 through the point face (2,2,2)", true, 0.5},
    {"vertex 3 past the point face (2,2,2)", false, 0},
    {"edge 5-6 through edge 0-1", true, 0.5},
    {"edge 5-6 far from edge 2-4", false, 0},
    {"edges 0-1 and 0-2 sharing vertex 0", true, 0.0},
    {"edge 0-1 against itself reversed", true, 0.0},
    {"zero-length edge 7-7 through edge 0-1", true, 0.5},
    {"zero-length edge 8-8 beside edge 0-1", false, 0},
};

TEST(BadInputDegenerateMesh, DegenerateCandidatesAreEvaluatedAsTheirGeometry) {
  const TestMesh mesh = degenerate_mesh();
  for (const Mode mode : kCertifiedModes) {
    SCOPED_TRACE(batchccd::to_string(mode));
    const BatchResult batch = batchccd::mesh_ccd(mesh.view(), mesh.candidates, with_mode(mode));
    ASSERT_EQ(batch.results.size(), kExpected.size());
    for (std::size_t i = 0; i < kExpected.size(); ++i) {
      SCOPED_TRACE(kExpected[i].what);
      if (kExpected[i].hit) {
        expect_hit_at(batch.results[i], kExpected[i].time);
      } else {
        expect_miss(batch.results[i]);
      }
    }
    EXPECT_EQ(batch.counters.invalid, 0);
    EXPECT_EQ(batch.earliest_toi, 0.0);  // the neighbour pairs touch from the start
  }
}

TEST(BadInputDegenerateMesh, EveryModeAndInstructionSetGivesWellFormedAnswers) {
  const TestMesh mesh = degenerate_mesh();
  for (const lab::Method& method : kMethods)
    for (const Isa isa : batchccd::available_isas()) {
      SCOPED_TRACE(std::string(lab::to_string(method)) + " " + batchccd::to_string(isa));
      Options options = method.applied_to({});
      options.isa = isa;
      const BatchResult batch = lab::mesh_ccd(mesh.view(), mesh.candidates, options, method.settings());
      ASSERT_EQ(batch.results.size(), kExpected.size());
      for (const QueryResult& r : batch.results) {
        EXPECT_EQ(r.status, Status::ok);
        if (r.hit) {
          EXPECT_GE(r.toi, 0.0);
          EXPECT_LE(r.toi, 1.0);
        } else {
          EXPECT_EQ(r.toi, kInfinity);
        }
      }
    }
}

// A NaN position spoils exactly the candidates that use that vertex.
void check_poisoned_vertex(int vertex, bool at_t1) {
  const TestMesh clean = degenerate_mesh();
  TestMesh poisoned = clean;
  (at_t1 ? poisoned.t1 : poisoned.t0)(vertex, 1) = kNaN;
  const BatchResult expected = batchccd::mesh_ccd(clean.view(), clean.candidates);
  const BatchResult actual = batchccd::mesh_ccd(poisoned.view(), poisoned.candidates);
  ASSERT_EQ(actual.results.size(), expected.results.size());
  std::vector<std::vector<int>> used;  // the vertices each candidate reads
  for (const auto& [v, f] : clean.candidates.vertex_face)
    used.push_back({v, clean.faces(f, 0), clean.faces(f, 1), clean.faces(f, 2)});
  for (const auto& ids : clean.candidates.edge_edge) used.emplace_back(ids.begin(), ids.end());
  std::int64_t invalid = 0;
  for (std::size_t i = 0; i < used.size(); ++i) {
    SCOPED_TRACE(kExpected[i].what);
    if (std::find(used[i].begin(), used[i].end(), vertex) != used[i].end()) {
      expect_invalid(actual.results[i]);
      ++invalid;
    } else {
      expect_same(actual.results[i], expected.results[i]);
    }
  }
  EXPECT_EQ(actual.counters.invalid, invalid);
}

TEST(BadInputNonFinite, NaNVertexSpoilsOnlyTheCandidatesThatUseIt) {
  for (const int vertex : {2, 4, 7})
    for (const bool at_t1 : {false, true}) {
      SCOPED_TRACE("vertex " + std::to_string(vertex) + (at_t1 ? " at t1" : " at t0"));
      check_poisoned_vertex(vertex, at_t1);
    }
}

TEST(BadInputNonFinite, NaNVertexNoCandidateUsesChangesNothing) {
  TestMesh mesh = degenerate_mesh();
  const BatchResult expected = batchccd::mesh_ccd(mesh.view(), mesh.candidates);
  mesh.t0.conservativeResize(11, 3);
  mesh.t1.conservativeResize(11, 3);
  mesh.t0.row(10) << kNaN, kNaN, kNaN;
  mesh.t1.row(10) << kInfinity, 0, 0;
  const BatchResult actual = batchccd::mesh_ccd(mesh.view(), mesh.candidates);
  ASSERT_EQ(actual.results.size(), expected.results.size());
  for (std::size_t i = 0; i < actual.results.size(); ++i) expect_same(actual.results[i], expected.results[i]);
  EXPECT_EQ(actual.counters.invalid, 0);
}

// ---------------------------------------------------------------------------
// Malformed meshes and out-of-range indices: the whole call is refused.

// Expects mesh_ccd to throw std::invalid_argument whose message holds `words`.
void expect_refused(const TestMesh& mesh, const std::string& words, const Options& options = {}) {
  try {
    batchccd::mesh_ccd(mesh.view(), mesh.candidates, options);
    ADD_FAILURE() << "mesh_ccd accepted a mesh that should be refused with '" << words << "'";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
  }
}

TEST(BadInputMesh, MismatchedPositionRowCountsAreRefused) {
  TestMesh mesh = degenerate_mesh();
  mesh.t1.conservativeResize(9, 3);
  expect_refused(mesh, "positions_t0 has 10 rows but positions_t1 has 9");
  mesh = degenerate_mesh();
  mesh.t1.resize(0, 3);
  expect_refused(mesh, "positions_t1 has 0");
}

TEST(BadInputMesh, MatricesWithoutThreeColumnsAreRefused) {
  TestMesh mesh = degenerate_mesh();
  mesh.t0.conservativeResize(10, 2);  // a 2D mesh at t0 only
  expect_refused(mesh, "positions_t0 has 2 columns but positions_t1 has 3: a mesh is 2D or 3D at both times");
  mesh = degenerate_mesh();
  mesh.t1.conservativeResize(10, 4);
  expect_refused(mesh, "positions_t1 must have 3 columns (2 for a 2D mesh), it has 4");
  mesh = degenerate_mesh();
  mesh.t0.conservativeResize(10, 1);
  mesh.t1.conservativeResize(10, 1);
  expect_refused(mesh, "positions_t0 must have 3 columns (2 for a 2D mesh), it has 1");
  mesh = degenerate_mesh();
  mesh.faces.conservativeResize(3, 2);
  expect_refused(mesh, "faces must have 3 columns");
}

// Regression: faces with rows but no columns hold no elements, and used to
// pass the shape check; a vertex-face candidate then read faces(f, 0) out of
// bounds.
TEST(BadInputMesh, FacesWithRowsButNoColumnsAreRefused) {
  TestMesh mesh = degenerate_mesh();
  mesh.faces.resize(3, 0);
  mesh.candidates.vertex_face = {{3, 0}};
  expect_refused(mesh, "faces must have 3 columns");
}

TEST(BadInputMesh, OutOfRangeIndicesAreRefusedNamingTheCandidate) {
  struct Case {
    const char* what;
    void (*spoil)(TestMesh&);
    const char* words;
  };
  const Case cases[] = {
      {"negative vertex id", [](TestMesh& m) { m.candidates.vertex_face[2][0] = -1; },
       "vertex-face candidate 2: vertex -1 out of range [0, 10)"},
      {"vertex id = n", [](TestMesh& m) { m.candidates.vertex_face[0][0] = 10; },
       "vertex-face candidate 0: vertex 10 out of range"},
      {"negative face id", [](TestMesh& m) { m.candidates.vertex_face[1][1] = -3; },
       "vertex-face candidate 1: face -3 out of range [0, 3)"},
      {"face id = m", [](TestMesh& m) { m.candidates.vertex_face[6][1] = 3; },
       "vertex-face candidate 6: face 3 out of range"},
      {"edge id = n", [](TestMesh& m) { m.candidates.edge_edge[4][3] = 10; },
       "edge-edge candidate 4: vertex 10 out of range"},
      {"negative edge id", [](TestMesh& m) { m.candidates.edge_edge[0][0] = -2147483647 - 1; },
       "edge-edge candidate 0: vertex -2147483648 out of range"},
      {"face corner out of range", [](TestMesh& m) { m.faces(2, 1) = 12; },
       "face 2: vertex 12 out of range"},
      {"negative face corner", [](TestMesh& m) { m.faces(0, 0) = -1; }, "face 0: vertex -1 out of range"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    TestMesh mesh = degenerate_mesh();
    c.spoil(mesh);
    expect_refused(mesh, c.words);
  }
}

// The lane filters check the candidates' ids on the way instead of a pass of
// their own (a vector test per full group of lanes, id by id in a batch's
// last group): a bad id anywhere in a long list, in every instruction set
// and mode, is refused naming the first one, and a BatchResult passed in
// keeps what an earlier call wrote there.
TEST(BadInputMesh, BadIdsAnywhereInLongListsAreRefusedAndLeaveTheResultAsItWas) {
  TestMesh good = degenerate_mesh();
  const Candidates few = good.candidates;
  good.candidates = {};
  for (int copy = 0; copy < 400; ++copy) {  // 2800 and 2400 candidates: full groups and a partial batch
    good.candidates.vertex_face.insert(good.candidates.vertex_face.end(), few.vertex_face.begin(), few.vertex_face.end());
    good.candidates.edge_edge.insert(good.candidates.edge_edge.end(), few.edge_edge.begin(), few.edge_edge.end());
  }
  const std::size_t last_vf = good.candidates.vertex_face.size() - 1, last_ee = good.candidates.edge_edge.size() - 1;
  struct Case {
    bool edge_edge;
    std::size_t candidate;
    int slot, id;
    std::string words;
  };
  const Case cases[] = {
      {false, 0, 0, 10, "vertex-face candidate 0: vertex 10 out of range"},
      {false, 2053, 1, 3, "vertex-face candidate 2053: face 3 out of range"},
      {false, 1000, 1, -1, "vertex-face candidate 1000: face -1 out of range"},
      {false, last_vf, 0, -7, "vertex-face candidate " + std::to_string(last_vf) + ": vertex -7"},
      {true, 9, 2, 10, "edge-edge candidate 9: vertex 10 out of range"},
      {true, 2047, 3, -1, "edge-edge candidate 2047: vertex -1 out of range"},
      {true, 2301, 1, 1 << 30, "edge-edge candidate 2301: vertex 1073741824 out of range"},
      {true, last_ee, 0, 11, "edge-edge candidate " + std::to_string(last_ee) + ": vertex 11"},
  };
  for (const lab::Method& method : {lab::kExact, lab::kConservative, lab::kFast, lab::kCubic})
    for (const Isa isa : batchccd::available_isas()) {
      Options options = method.applied_to({});
      options.isa = isa;
      BatchResult out = lab::mesh_ccd(good.view(), good.candidates, options, method.settings());
      const BatchResult before = out;
      for (const Case& c : cases) {
        SCOPED_TRACE(std::string(lab::to_string(method)) + " " + batchccd::to_string(isa) + ": " + c.words);
        TestMesh bad = good;
        if (c.edge_edge) {
          bad.candidates.edge_edge[c.candidate][static_cast<std::size_t>(c.slot)] = c.id;
        } else {
          bad.candidates.vertex_face[c.candidate][static_cast<std::size_t>(c.slot)] = c.id;
        }
        try {
          lab::mesh_ccd(bad.view(), bad.candidates, {}, options, method.settings(), out);
          ADD_FAILURE() << "accepted";
        } catch (const std::invalid_argument& error) {
          EXPECT_NE(std::string(error.what()).find(c.words), std::string::npos) << error.what();
        }
        ASSERT_EQ(out.results.size(), before.results.size());
        for (std::size_t i = 0; i < out.results.size(); ++i) {
          ASSERT_EQ(out.results[i].hit, before.results[i].hit) << i;
          ASSERT_EQ(out.results[i].toi, before.results[i].toi) << i;
        }
        EXPECT_EQ(out.counters.candidates, before.counters.candidates);
        EXPECT_EQ(out.counters.hits, before.counters.hits);
      }
    }
}

TEST(BadInputMesh, CandidatesOutsideTheMeshAreRefusedEvenWhenTheirListIsOff) {
  TestMesh mesh = degenerate_mesh();
  mesh.candidates.edge_edge.push_back({0, 1, 2, 99});
  Options options;
  options.edge_edge = false;
  expect_refused(mesh, "edge-edge candidate 6: vertex 99 out of range", options);
}

TEST(BadInputMesh, CandidatesOnAnEmptyMeshAreRefused) {
  const Eigen::MatrixXd none;
  const Eigen::MatrixXi no_faces;
  Candidates vertex_face;
  vertex_face.vertex_face = {{0, 0}};
  EXPECT_THROW(batchccd::mesh_ccd({none, none, no_faces}, vertex_face), std::invalid_argument);
  Candidates edge_edge;
  edge_edge.edge_edge = {{0, 0, 0, 0}};
  EXPECT_THROW(batchccd::mesh_ccd({none, none, no_faces}, edge_edge), std::invalid_argument);
}

// A vertex-only mesh (no faces) is valid for edge-edge candidates.
TEST(BadInputMesh, MeshWithoutFacesServesEdgeEdgeCandidates) {
  TestMesh mesh = degenerate_mesh();
  mesh.faces.resize(0, 3);
  mesh.candidates.vertex_face.clear();
  const BatchResult batch = batchccd::mesh_ccd(mesh.view(), mesh.candidates);
  ASSERT_EQ(batch.results.size(), mesh.candidates.edge_edge.size());
  expect_hit_at(batch.results[0], 0.5);
  expect_miss(batch.results[1]);
}

// ---------------------------------------------------------------------------
// Bad files: the readers refuse them naming file and line, before anything runs.

using test_support::write_file;

// A query file of the given queries, coordinates as integers over 1.
std::string query_csv(const std::vector<Query>& queries) {
  std::ostringstream text;
  for (const Query& query : queries)
    for (const Vec3& point : query.points) text << point.x() << ",1," << point.y() << ",1," << point.z() << ",1\n";
  return text.str();
}

class BadInputFiles : public test_support::TemporaryDirectoryTest {
 protected:
  // The InputError `read` throws; fails the test when it throws none.
  template <class Read>
  static std::optional<batchccd::InputError> error_of(Read read) {
    try {
      read();
    } catch (const batchccd::InputError& error) {
      return error;
    }
    ADD_FAILURE() << "no InputError";
    return std::nullopt;
  }
};

TEST_F(BadInputFiles, SceneWithAnOutOfRangeCandidateNamesItsLine) {
  test_support::write_scene_with_an_out_of_range_candidate(path("scene"));
  const auto error = error_of([&] { batchccd::read_scene(path("scene")); });
  ASSERT_TRUE(error);
  EXPECT_EQ(fs::path(error->file()).filename(), "ee.csv");
  EXPECT_EQ(error->line(), 2);
  EXPECT_NE(std::string(error->what()).find("out of range"), std::string::npos) << error->what();
}

TEST_F(BadInputFiles, QueryFilesThatAreNotEightRowsOfDoublesAreRefused) {
  write_file(path("short.csv"), "1,1,2,1,3,1\n");  // 1 of 8 rows
  write_file(path("not-double.csv"), query_csv({kVertexFaceMiss}).replace(0, 5, "1,3,0"));
  write_file(path("good.csv"), query_csv({kVertexFaceHit, kVertexFaceMiss}));
  for (const char* name : {"short.csv", "not-double.csv"}) {
    const auto error = error_of([&] { batchccd::read_query_csv(path(name), Kind::vertex_face); });
    ASSERT_TRUE(error) << name;
    EXPECT_EQ(fs::path(error->file()).filename(), name);
  }
  const auto missing = error_of([&] { batchccd::read_query_csv(path("missing.csv"), Kind::vertex_face); });
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->line(), 0);
  EXPECT_EQ(batchccd::read_query_csv(path("good.csv"), Kind::vertex_face).queries.size(), 2u);
}

}  // namespace

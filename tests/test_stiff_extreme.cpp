// The stiff and extreme suite (bench/extreme_suite.hpp): on every category,
// exact mode against the constructed truth, conservative mode never missing
// what exact mode finds, no mode returning a NaN or out-of-range TOI, and
// consistent counters; then a few hand-made queries per category whose
// answers are worked out next to them (every coordinate exact in binary).
// A hang is caught by ctest's timeout.

#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"
#include "extreme_suite.hpp"

namespace batchccd {
namespace {

using scenes::ExtremeCategory;
using scenes::ExtremeRow;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kExactToiWidth = 0x1p-40;  // exact mode's TOI: at most this before the contact

// ------------------------------------------------------------------ the suite

const std::vector<ExtremeCategory>& suite() {
  static const std::vector<ExtremeCategory> categories = scenes::extreme_categories();
  return categories;
}

std::string describe(const ExtremeRow& row) {
  return row.category + " " + to_string(row.kind) + ", " + lab::to_string(row.method);
}

// A query's points at full precision, to reproduce a failure.
std::string describe(const Query& query) {
  std::ostringstream out;
  out.precision(17);
  for (const Vec3& point : query.points) out << "\n  " << point.transpose();
  return out.str();
}

void expect_mixed_answers(const ExtremeRow& exact) {
  EXPECT_GT(exact.truth_known, 0) << "no query with a constructed truth";
  EXPECT_GT(exact.batch.counters.hits, 0);
  if (exact.category.rfind("contact", 0) != 0) {  // those are all contacts
    EXPECT_LT(exact.batch.counters.hits, exact.queries);
  }
}

void expect_exact_matches_construction(const ExtremeCategory& category, const ExtremeRow& exact) {
  EXPECT_EQ(exact.truth_disagreements, 0);
  EXPECT_EQ(exact.late_tois, 0);
  for (std::size_t q = 0; q < category.queries.size(); ++q) {
    if (category.constructed_truth[q] != 1 || !exact.batch.results[q].hit) continue;
    const double contact = category.constructed_first_contact[q];
    EXPECT_GE(exact.batch.results[q].toi, contact - kExactToiWidth)
        << "query " << q << ", first contact " << contact << describe(category.queries[q]);
  }
}

void expect_conservative_misses_nothing(const ExtremeRow& conservative) {
  EXPECT_EQ(conservative.false_negatives, 0);
  EXPECT_EQ(conservative.late_tois, 0) << "a TOI after the constructed first contact";
}

// No NaN, a hit's TOI in [0, 1], a miss's +inf; the row's counts agree.
void expect_well_formed_tois(const ExtremeCategory& category, const ExtremeRow& row) {
  EXPECT_EQ(row.nan_tois, 0);
  EXPECT_EQ(row.malformed_tois, 0);
  for (std::size_t q = 0; q < category.queries.size(); ++q) {
    const QueryResult& result = row.batch.results[q];
    EXPECT_EQ(result.status, Status::ok);
    const bool well_formed = result.hit ? result.toi >= 0 && result.toi <= 1 : result.toi == kInfinity;
    EXPECT_TRUE(well_formed) << "query " << q << ": hit " << result.hit << ", toi " << result.toi
                             << describe(category.queries[q]);
  }
}

void expect_consistent_counters(const ExtremeRow& row) {
  const Counters& counters = row.batch.counters;
  std::int64_t hits = 0;
  for (const QueryResult& result : row.batch.results) hits += result.hit;
  EXPECT_EQ(counters.candidates, row.queries);
  EXPECT_EQ(counters.hits, hits);
  EXPECT_EQ(counters.invalid, 0);
  EXPECT_EQ(counters.culled + counters.solved, counters.candidates);
  // Each cull counted once, by the stage that made it.
  EXPECT_EQ(counters.culled, counters.culled_by_sign + counters.culled_by_separation + counters.culled_by_pieces +
                                 counters.culled_by_swept_box);
  EXPECT_LE(counters.undecided, counters.hits);
  if (row.method == lab::kCubic) {
    EXPECT_EQ(counters.culled, 0) << "the cubic baseline runs no filter";
  }
  if (row.method.baseline != lab::Baseline::none) {
    EXPECT_EQ(counters.exact_escalations, 0) << "only the certified modes have an exact stage";
  } else {
    // What the floating-point search cannot settle goes to the exact stage:
    // never a guessed contact (nearly parallel edges once ran out here).
    EXPECT_EQ(counters.undecided, 0);
  }
}

TEST(StiffExtreme, SuiteIsDeterministic) {
  const std::vector<ExtremeCategory> again = scenes::extreme_categories();
  ASSERT_EQ(again.size(), suite().size());
  for (std::size_t c = 0; c < suite().size(); ++c) {
    const ExtremeCategory& category = suite()[c];
    SCOPED_TRACE(category.name + " " + to_string(category.kind));
    ASSERT_EQ(category.queries.size(), 64u);
    ASSERT_EQ(category.constructed_truth.size(), category.queries.size());
    ASSERT_EQ(category.constructed_first_contact.size(), category.queries.size());
    for (std::size_t q = 0; q < category.queries.size(); ++q)
      EXPECT_EQ(again[c].queries[q].points, category.queries[q].points) << "query " << q;
  }
}

// One evaluation (ctest runs each test in its own process), on one thread:
// the test's time is what one core spends. Prints the report's table.
TEST(StiffExtreme, EveryModeOnEveryCategory) {
  Options options;
  options.threads = 1;
  const std::vector<ExtremeRow> rows = scenes::evaluate_extreme(suite(), options);
  scenes::write_extreme_table(std::cout, rows);
  ASSERT_EQ(rows.size(), 4 * suite().size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const ExtremeRow& row = rows[r];
    const ExtremeCategory& category = suite()[r / 4];  // four modes a category, exact first
    SCOPED_TRACE(describe(row));
    ASSERT_EQ(row.category, category.name);
    ASSERT_EQ(row.kind, category.kind);
    expect_well_formed_tois(category, row);
    expect_consistent_counters(row);
    if (row.method == lab::kExact) {
      expect_mixed_answers(row);
      expect_exact_matches_construction(category, row);
    }
    if (row.method == lab::kConservative) expect_conservative_misses_nothing(row);
  }
}

// ------------------------------------------------------------------ by hand

Vec3 V(double x, double y, double z) { return Vec3(x, y, z); }

// The vertex against the still unit triangle (0,0,0), (1,0,0), (0,1,0) in z = 0.
Query vertex_over_unit_triangle(const Vec3& p_t0, const Vec3& p_t1) {
  const Vec3 a = V(0, 0, 0), b = V(1, 0, 0), c = V(0, 1, 0);
  return Query{{p_t0, a, b, c, p_t1, a, b, c}};
}

// Edge b against the still unit edge a from (0,0,0) to (1,0,0).
Query edge_over_unit_edge(const Vec3& b0_t0, const Vec3& b1_t0, const Vec3& b0_t1, const Vec3& b1_t1) {
  const Vec3 a0 = V(0, 0, 0), a1 = V(1, 0, 0);
  return Query{{a0, a1, b0_t0, b1_t0, a0, a1, b0_t1, b1_t1}};
}

// Every coordinate x becomes x * scale + shift (exact for the values used).
Query transformed(Query query, double scale, double shift) {
  for (Vec3& point : query.points) point = point * scale + Vec3::Constant(shift);
  return query;
}

struct HandCase {
  std::string name;
  Kind kind;
  Query query;
  std::optional<double> first_contact;  // nullopt: they never touch
};

// Exact and conservative mode decide right, with TOIs never after the first
// contact (exact: within 2^-40 of it); the fast and cubic baselines answer
// in range.
void expect_answers(const std::vector<HandCase>& cases) {
  for (const HandCase& hand : cases) {
    SCOPED_TRACE(hand.name);
    for (const lab::Method& method : {lab::kExact, lab::kConservative, lab::kFast, lab::kCubic}) {
      SCOPED_TRACE(lab::to_string(method));
      const QueryResult result = lab::query_ccd(hand.kind, hand.query, method.applied_to({}), method.settings());
      ASSERT_EQ(result.status, Status::ok);
      ASSERT_FALSE(std::isnan(result.toi));
      if (result.hit) {
        EXPECT_GE(result.toi, 0.0);
        EXPECT_LE(result.toi, 1.0);
      } else {
        EXPECT_EQ(result.toi, kInfinity);
      }
      if (method.baseline != lab::Baseline::none) continue;
      EXPECT_EQ(result.hit, hand.first_contact.has_value()) << "toi " << result.toi;
      if (!result.hit || !hand.first_contact) continue;
      EXPECT_LE(result.toi, *hand.first_contact);
      if (method == lab::kExact) {
        EXPECT_GE(result.toi, *hand.first_contact - kExactToiWidth);
      }
    }
  }
}

const std::optional<double> kMiss = std::nullopt;

// Coordinates near 1024 moving 2^-22 (2.4e-7, 2.3e-10 of the coordinates).
TEST(StiffExtremeByHand, Stiff) {
  constexpr double h = 0x1p-23;
  expect_answers({
      {"vertex crossing at t = 1/2", Kind::vertex_face,
       transformed(vertex_over_unit_triangle(V(0.25, 0.25, h), V(0.25, 0.25, -h)), 1, 1024), 0.5},
      {"vertex stopping 2^-23 short", Kind::vertex_face,
       transformed(vertex_over_unit_triangle(V(0.25, 0.25, 2 * h), V(0.25, 0.25, h)), 1, 1024), kMiss},
      {"vertex crossing 2^-30 outside", Kind::vertex_face,
       transformed(vertex_over_unit_triangle(V(-0x1p-30, 0.25, h), V(-0x1p-30, 0.25, -h)), 1, 1024), kMiss},
      {"edges crossing at t = 1/2", Kind::edge_edge,
       transformed(edge_over_unit_edge(V(0.5, -0.5, h), V(0.5, 0.5, h), V(0.5, -0.5, -h), V(0.5, 0.5, -h)), 1, 1024),
       0.5},
      {"edge passing 2^-30 beyond the end", Kind::edge_edge,
       transformed(edge_over_unit_edge(V(1 + 0x1p-30, -0.5, h), V(1 + 0x1p-30, 0.5, h),
                                       V(1 + 0x1p-30, -0.5, -h), V(1 + 0x1p-30, 0.5, -h)),
                   1, 1024),
       kMiss},
  });
}

// Motion of 2000 unit primitive sizes.
TEST(StiffExtremeByHand, Fast) {
  expect_answers({
      {"vertex straight through", Kind::vertex_face,
       vertex_over_unit_triangle(V(0.25, 0.25, 1000), V(0.25, 0.25, -1000)), 0.5},
      {"vertex through obliquely (x = 0.25 at t = 1/2)", Kind::vertex_face,
       vertex_over_unit_triangle(V(-999.75, 0.25, 1000), V(1000.25, 0.25, -1000)), 0.5},
      {"vertex obliquely beside it (x = -0.25 at t = 1/2)", Kind::vertex_face,
       vertex_over_unit_triangle(V(-1000.25, 0.25, 1000), V(999.75, 0.25, -1000)), kMiss},
      {"edge straight through", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, -0.5, 1000), V(0.5, 0.5, 1000), V(0.5, -0.5, -1000), V(0.5, 0.5, -1000)), 0.5},
      {"edge beyond the end", Kind::edge_edge,
       edge_over_unit_edge(V(1.5, -0.5, 1000), V(1.5, 0.5, 1000), V(1.5, -0.5, -1000), V(1.5, 0.5, -1000)), kMiss},
  });
}

// Unit crossings and misses scaled by a power of two (exact).
std::vector<HandCase> scaled_unit_cases(double scale) {
  return {
      {"vertex crossing", Kind::vertex_face,
       transformed(vertex_over_unit_triangle(V(0.25, 0.25, 1), V(0.25, 0.25, -1)), scale, 0), 0.5},
      {"vertex beside", Kind::vertex_face,
       transformed(vertex_over_unit_triangle(V(0.75, 0.5, 1), V(0.75, 0.5, -1)), scale, 0), kMiss},
      {"edges crossing", Kind::edge_edge,
       transformed(edge_over_unit_edge(V(0.5, -0.5, 1), V(0.5, 0.5, 1), V(0.5, -0.5, -1), V(0.5, 0.5, -1)), scale, 0),
       0.5},
      {"edge beyond the end", Kind::edge_edge,
       transformed(edge_over_unit_edge(V(1.5, -0.5, 1), V(1.5, 0.5, 1), V(1.5, -0.5, -1), V(1.5, 0.5, -1)), scale, 0),
       kMiss},
  };
}

TEST(StiffExtremeByHand, Tiny) { expect_answers(scaled_unit_cases(0x1p-1000)); }  // 9.3e-302
TEST(StiffExtremeByHand, Huge) { expect_answers(scaled_unit_cases(0x1p1000)); }   // 1.1e301

TEST(StiffExtremeByHand, NearCoplanar) {
  constexpr double h = 0x1p-40;
  expect_answers({
      {"vertex sliding over at height 2^-40", Kind::vertex_face,
       vertex_over_unit_triangle(V(-1, 0.25, h), V(1, 0.25, h)), kMiss},
      {"vertex sliding in the plane, entering at t = 1/2", Kind::vertex_face,
       vertex_over_unit_triangle(V(-1, 0.25, 0), V(1, 0.25, 0)), 0.5},
      {"vertex tilting through the side x = 0 at t = 1/2", Kind::vertex_face,
       vertex_over_unit_triangle(V(-1, 0.25, h), V(1, 0.25, -h)), 0.5},
      {"edge sliding over at height 2^-40", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, 1, h), V(0.5, 2, h), V(0.5, -3, h), V(0.5, -2, h)), kMiss},
      {"edge sliding in the plane, its end reaching the other at t = 1/4", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, 1, 0), V(0.5, 2, 0), V(0.5, -3, 0), V(0.5, -2, 0)), 0.25},
  });
}

TEST(StiffExtremeByHand, NearParallelEdges) {
  constexpr double tilt = 0x1p-30;
  expect_answers({
      {"2^-29 radians apart, crossing at x = 1/2, t = 1/2", Kind::edge_edge,
       edge_over_unit_edge(V(0, -tilt, 1), V(1, tilt, 1), V(0, -tilt, -1), V(1, tilt, -1)), 0.5},
      {"nearly parallel, 2^-40 aside at its nearest", Kind::edge_edge,
       edge_over_unit_edge(V(0, 0x1p-40, 1), V(1, tilt, 1), V(0, 0x1p-40, -1), V(1, tilt, -1)), kMiss},
      {"parallel, 2^-40 aside", Kind::edge_edge,
       edge_over_unit_edge(V(0, 0x1p-40, 1), V(1, 0x1p-40, 1), V(0, 0x1p-40, -1), V(1, 0x1p-40, -1)), kMiss},
      {"parallel and overlapping in the plane at t = 1/2", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, 0, 1), V(1.5, 0, 1), V(0.5, 0, -1), V(1.5, 0, -1)), 0.5},
  });
}

TEST(StiffExtremeByHand, ContactAtTimeZero) {
  expect_answers({
      {"vertex leaving the inside", Kind::vertex_face,
       vertex_over_unit_triangle(V(0.25, 0.25, 0), V(0.25, 0.25, 1)), 0.0},
      {"vertex leaving a corner", Kind::vertex_face,
       vertex_over_unit_triangle(V(1, 0, 0), V(2, 1, 1)), 0.0},
      {"edge leaving from an end", Kind::edge_edge,
       edge_over_unit_edge(V(1, 0, 0), V(1, 1, 0), V(1, 0, 1), V(1, 1, 1)), 0.0},
  });
}

TEST(StiffExtremeByHand, ContactAtTimeOne) {
  expect_answers({
      {"vertex arriving inside", Kind::vertex_face,
       vertex_over_unit_triangle(V(0.25, 0.25, 1), V(0.25, 0.25, 0)), 1.0},
      {"vertex arriving on the plane outside", Kind::vertex_face,
       vertex_over_unit_triangle(V(1.25, 0.25, 1), V(1.25, 0.25, 0)), kMiss},
      {"edge arriving across", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, -0.5, 1), V(0.5, 0.5, 1), V(0.5, -0.5, 0), V(0.5, 0.5, 0)), 1.0},
      {"edge arriving at an end", Kind::edge_edge,
       edge_over_unit_edge(V(0, -0.5, -1), V(0, 0.5, -1), V(0, -0.5, 0), V(0, 0.5, 0)), 1.0},
  });
}

TEST(StiffExtremeByHand, StaticVertices) {
  const Vec3 a = V(0, 0, 0), b = V(1, 0, 0), c = V(0, 1, 0);
  const Vec3 p = V(0.25, 0.25, 0);
  expect_answers({
      {"all still, apart", Kind::vertex_face, vertex_over_unit_triangle(V(0.25, 0.25, 1), V(0.25, 0.25, 1)), kMiss},
      {"all still, touching", Kind::vertex_face, vertex_over_unit_triangle(p, p), 0.0},
      {"triangle crossing the still vertex at t = 1/2", Kind::vertex_face,
       Query{{p, a - V(0, 0, 1), b - V(0, 0, 1), c - V(0, 0, 1), p, a + V(0, 0, 1), b + V(0, 0, 1), c + V(0, 0, 1)}},
       0.5},
      {"all still edges, apart", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, -0.5, 1), V(0.5, 0.5, 1), V(0.5, -0.5, 1), V(0.5, 0.5, 1)), kMiss},
      {"all still edges, crossing", Kind::edge_edge,
       edge_over_unit_edge(V(0.5, -0.5, 0), V(0.5, 0.5, 0), V(0.5, -0.5, 0), V(0.5, 0.5, 0)), 0.0},
      {"edge a crossing the still edge b at t = 1/2", Kind::edge_edge,
       Query{{V(0, 0, -1), V(1, 0, -1), V(0.5, -0.5, 0), V(0.5, 0.5, 0), V(0, 0, 1), V(1, 0, 1), V(0.5, -0.5, 0),
              V(0.5, 0.5, 0)}},
       0.5},
  });
}

}  // namespace
}  // namespace batchccd

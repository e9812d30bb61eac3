// Property tests over random queries (fixed seeds, so every run sees the same
// queries). What they hold the library to:
//
// - Units do not matter: scaling all 24 coordinates by 2^k changes neither
//   the decision nor the TOI, bit for bit (conservative and fast).
// - Conservative mode has no false negatives: a query built to collide
//   (exact dyadic coordinates, so the contact is exact) is reported as a hit
//   no later than the built contact, and so is every exactly equivalent
//   description of it (axes permuted or flipped, translated, time reversed,
//   triangle vertices or edge endpoints reordered). A query whose primitives
//   stay clearly apart keeps missing under the same transforms.
// - Near misses the filters leave to the search over (u, v) (certified
//   apart far above tolerance) are misses, with the default options, the
//   decision alone and coarse TOIs; at a separation, edges that only that
//   search tells apart are a decided miss, and within it a decided hit.
// - Nothing breaks on extreme finite input (1e-300 .. 1e300), in any mode.
// - NaN or infinite coordinates give Status::invalid_input with hit == true.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"
#include "exact_distance.hpp"
#include "query_builders.hpp"

namespace {

using batchccd::Kind;
using batchccd::Mode;
using batchccd::Options;
using batchccd::Query;
using batchccd::QueryResult;
using batchccd::Status;
using batchccd::Vec3;
using Rng = std::mt19937_64;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------
// Small helpers.

double uniform(Rng& rng, double low, double high) {
  return std::uniform_real_distribution<double>(low, high)(rng);
}
int uniform_int(Rng& rng, int low, int high) {
  return std::uniform_int_distribution<int>(low, high)(rng);
}
bool coin(Rng& rng, double probability = 0.5) {
  return std::bernoulli_distribution(probability)(rng);
}

namespace lab = batchccd::lab;
namespace batchccd_testing = batchccd::testing;  // exact_distance.hpp, query_builders.hpp

QueryResult run(Kind kind, const Query& query, const lab::Method& method = lab::kConservative) {
  return lab::query_ccd(kind, query, method.applied_to({}), method.settings());
}

std::string describe(Kind kind, const Query& query) {
  std::ostringstream out;
  out.precision(17);
  out << batchccd::to_string(kind) << " {";
  for (int i = 0; i < 8; ++i) {
    const Vec3& x = query.points[i];
    out << (i ? ", " : "") << "(" << x[0] << ", " << x[1] << ", " << x[2] << ")";
  }
  out << "}";
  return out.str();
}

// ---------------------------------------------------------------------------
// Random points. Grid points are dyadic with few significant bits, so every
// construction below (interpolation at dyadic times, dyadic barycentric
// weights, division by powers of two) and every integer translation stays
// exact in double.

enum class PointKind {
  integer_grid,  // integers in [-8, 8]
  fine_grid,     // multiples of 2^-16 in [-16, 16]
  real,          // uniform doubles in [-1, 1] (constructions then inexact)
};

struct PointMaker {
  PointKind kind = PointKind::integer_grid;
  bool planar = false;  // every point in z = 0: coplanar motion throughout

  double coordinate(Rng& rng) const {
    switch (kind) {
      case PointKind::integer_grid:
        return uniform_int(rng, -8, 8);
      case PointKind::fine_grid:
        return std::ldexp(uniform_int(rng, -(1 << 20), 1 << 20), -16);
      case PointKind::real:
        return uniform(rng, -1, 1);
    }
    return 0;
  }
  Vec3 operator()(Rng& rng) const {
    const double x = coordinate(rng), y = coordinate(rng);
    return {x, y, planar ? 0.0 : coordinate(rng)};
  }
};

PointMaker random_point_maker(Rng& rng, bool exact_only) {
  PointMaker maker;
  const int choice = uniform_int(rng, 0, exact_only ? 1 : 2);
  maker.kind = choice == 0 ? PointKind::integer_grid
               : choice == 1 ? PointKind::fine_grid
                             : PointKind::real;
  maker.planar = coin(rng, 0.15);
  return maker;
}

Vec3 lerp(const Vec3& at0, const Vec3& at1, double t) { return at0 + t * (at1 - at0); }

// Contact times at which a path through a given point can be solved for
// exactly: t or 1 - t is a power of two (or t is 0 or 1).
double random_contact_time(Rng& rng) {
  static const double times[] = {0, 0.125, 0.25, 0.5, 0.75, 0.875, 1};
  return times[uniform_int(rng, 0, 6)];
}

// A point moving linearly that is exactly at `target` at time t.
void place_through(Rng& rng, const PointMaker& point, const Vec3& target, double t, Vec3& at0,
                   Vec3& at1) {
  if (t == 0) {
    at0 = target;
    at1 = point(rng);
  } else if (t == 1) {
    at1 = target;
    at0 = point(rng);
  } else if (t <= 0.5) {  // t = 2^-s
    at0 = point(rng);
    at1 = at0 + (target - at0) / t;
  } else {  // 1 - t = 2^-s
    at1 = point(rng);
    at0 = at1 + (target - at1) / (1 - t);
  }
}

// Motion of the primitive that is not solved for: static, translating or free.
void random_motion(Rng& rng, const PointMaker& point, int count, Vec3* at0, Vec3* at1) {
  const int style = uniform_int(rng, 0, 2);
  const Vec3 shift = point(rng);
  for (int i = 0; i < count; ++i) {
    at0[i] = point(rng);
    at1[i] = style == 0 ? at0[i] : style == 1 ? Vec3(at0[i] + shift) : point(rng);
  }
}

struct Contact {
  Kind kind;
  Query query;
  double time;  // a time at which the primitives touch (exactly, for grid points)
};

// Vertex-face: the triangle moves at random, the vertex is placed on it at a
// random barycentric point (corners and edges included) at a random time.
Contact vertex_face_contact(Rng& rng, const PointMaker& point, double segment_share) {
  Vec3 at0[3], at1[3];  // a, b, c
  random_motion(rng, point, 3, at0, at1);
  // Degenerate triangles now and then: one point (1 in 20), or a segment (c = b
  // or three collinear corners, `segment_share` of the time: the solver can
  // spend its whole iteration budget on those, ~0.1 s each, see the
  // degenerate suite, so the slower tests ask for fewer).
  if (coin(rng, 0.05)) {  // all three corners one point
    at0[1] = at0[2] = at0[0];
    at1[1] = at1[2] = at1[0];
  } else if (coin(rng, segment_share)) {
    if (coin(rng)) {  // zero area: c = b
      at0[2] = at0[1];
      at1[2] = at1[1];
    } else {  // collinear: c = a + 2 (b - a)
      at0[2] = at0[0] + 2 * (at0[1] - at0[0]);
      at1[2] = at1[0] + 2 * (at1[1] - at1[0]);
    }
  }
  const double t = random_contact_time(rng);
  const Vec3 a = lerp(at0[0], at1[0], t), b = lerp(at0[1], at1[1], t), c = lerp(at0[2], at1[2], t);
  const int i = uniform_int(rng, 0, 16), j = uniform_int(rng, 0, 16 - i);
  const double u = i / 16.0, v = j / 16.0;
  const Vec3 target = a + u * (b - a) + v * (c - a);
  Vec3 p0, p1;
  place_through(rng, point, target, t, p0, p1);
  return {Kind::vertex_face, Query{{p0, at0[0], at0[1], at0[2], p1, at1[0], at1[1], at1[2]}}, t};
}

// Edge-edge: edge a moves at random; edge b is built through a random point
// of edge a at a random time, at a parameter v where v or 1 - v is a power of
// two.
Contact edge_edge_contact(Rng& rng, const PointMaker& point) {
  Vec3 a0[2], a1[2];  // edge a's endpoints at t0 and t1
  random_motion(rng, point, 2, a0, a1);
  if (coin(rng, 0.08)) {  // zero-length edge a
    a0[1] = a0[0];
    a1[1] = a1[0];
  }
  const double t = random_contact_time(rng);
  const double u = uniform_int(rng, 0, 16) / 16.0;
  const Vec3 ea0 = lerp(a0[0], a1[0], t), ea1 = lerp(a0[1], a1[1], t);
  const Vec3 target = ea0 + u * (ea1 - ea0);

  static const double parameters[] = {0, 0.125, 0.25, 0.5, 0.75, 0.875, 1};
  const double v = parameters[uniform_int(rng, 0, 6)];
  const bool zero_length_b = coin(rng, 0.08);
  Vec3 b0[2], b1[2];  // edge b's endpoints at t0 and t1
  if (zero_length_b) {
    place_through(rng, point, target, t, b0[0], b1[0]);
    b0[1] = b0[0];
    b1[1] = b1[0];
  } else if (v == 0) {
    place_through(rng, point, target, t, b0[0], b1[0]);
    b0[1] = point(rng);
    b1[1] = coin(rng) ? b0[1] : point(rng);
  } else if (v == 1 || v <= 0.5) {  // v = 2^-s: solve for endpoint 1
    b0[0] = point(rng);
    b1[0] = coin(rng) ? b0[0] : point(rng);
    const Vec3 start = lerp(b0[0], b1[0], t);
    place_through(rng, point, start + (target - start) / v, t, b0[1], b1[1]);
  } else {  // 1 - v = 2^-s: solve for endpoint 0
    b0[1] = point(rng);
    b1[1] = coin(rng) ? b0[1] : point(rng);
    const Vec3 end = lerp(b0[1], b1[1], t);
    place_through(rng, point, end + (target - end) / (1 - v), t, b0[0], b1[0]);
  }
  return {Kind::edge_edge, Query{{a0[0], a0[1], b0[0], b0[1], a1[0], a1[1], b1[0], b1[1]}}, t};
}

// segment_share: how often a VF triangle is a segment (zero area).
Contact random_contact(Rng& rng, Kind kind, const PointMaker& point,
                       double segment_share = 1.0 / 30) {
  return kind == Kind::vertex_face ? vertex_face_contact(rng, point, segment_share)
                                   : edge_edge_contact(rng, point);
}

// ---------------------------------------------------------------------------
// Clear misses, certified exactly.

// Whether the primitives stay more than `gap` apart over [0, 1], proven by
// the exact labels of exact_distance.hpp (rational distances, a certified
// Lipschitz bound). Those spend their GMP samples only on queries the
// double-precision distance already keeps twice `gap` apart (a bisection on
// the same Lipschitz cones), where a wide margin settles the proof in a few
// samples: a query nearer than that is another try, never a test case.
bool certainly_apart(Kind kind, const Query& q, double gap) {
  const double speed = batchccd_testing::lipschitz_bound(kind, q);
  std::vector<std::array<double, 2>> stack = {{0.0, 1.0}};
  for (int evaluations = 0; !stack.empty(); ++evaluations) {
    const auto [low, high] = stack.back();
    stack.pop_back();
    const double middle = 0.5 * (low + high);
    if (batchccd_testing::distance_in_double(kind, q, middle) - speed * 0.5 * (high - low) > 2 * gap) continue;
    if (evaluations > 20000 || high - low < 1e-7) return false;
    stack.push_back({low, middle});
    stack.push_back({middle, high});
  }
  return batchccd_testing::label(kind, q, gap).label == batchccd_testing::Label::miss;
}

// The points shifted to turn a contact into a miss: the vertex (VF), edge b (EE).
std::vector<int> moving_points(Kind kind) {
  return kind == Kind::vertex_face ? std::vector<int>{0, 4} : std::vector<int>{2, 3, 6, 7};
}

// A query whose primitives stay more than 1e-3 of its size apart: a
// contact with the vertex (VF) or edge b (EE) shifted off it, when that
// clears it; otherwise another try.
Query random_clear_miss(Rng& rng, Kind kind, const PointMaker& point) {
  for (;;) {
    Query q = random_contact(rng, kind, point).query;
    const double scale = std::ldexp(1.0, -uniform_int(rng, 0, 4));
    Vec3 shift(uniform_int(rng, -4, 4) * scale, uniform_int(rng, -4, 4) * scale,
               point.planar ? 0.0 : uniform_int(rng, -4, 4) * scale);
    if (point.kind == PointKind::real) shift *= 0.25;
    for (int index : moving_points(kind)) q.points[index] += shift;
    if (certainly_apart(kind, q, 1e-3 * batchccd_testing::query_size(q))) return q;
  }
}

// ---------------------------------------------------------------------------
// Exactly equivalent descriptions of a query.

struct Variant {
  std::string name;
  Query query;
  bool time_reversed = false;
};

std::vector<Variant> equivalent_variants(Rng& rng, Kind kind, const Query& q, bool exact) {
  std::vector<Variant> variants;
  std::array<int, 3> order = {0, 1, 2};
  while (std::next_permutation(order.begin(), order.end()))
    variants.push_back({"axes permuted " + std::to_string(order[0]) + std::to_string(order[1]) +
                            std::to_string(order[2]),
                        batchccd_testing::axes_permuted(q, order)});
  for (int mask = 1; mask < 8; ++mask)
    variants.push_back({"axes flipped, mask " + std::to_string(mask), batchccd_testing::axes_flipped(q, mask)});
  if (exact) {
    // Integer offsets keep grid coordinates exact (they carry few bits).
    for (int k = 0; k < 3; ++k) {
      const int range = k == 0 ? 4 : k == 1 ? 1000 : 1 << 20;
      const Vec3 offset(uniform_int(rng, -range, range), uniform_int(rng, -range, range),
                        uniform_int(rng, -range, range));
      variants.push_back({"translated by range " + std::to_string(range), batchccd_testing::translated(q, offset)});
    }
  }
  variants.push_back({"time reversed", batchccd_testing::time_reversed(q), true});
  if (kind == Kind::vertex_face) {
    std::array<int, 3> corners = {1, 2, 3};
    while (std::next_permutation(corners.begin(), corners.end()))
      variants.push_back({"triangle reordered " + std::to_string(corners[0]) +
                              std::to_string(corners[1]) + std::to_string(corners[2]),
                          batchccd_testing::reordered(q, {0, corners[0], corners[1], corners[2]})});
  } else {
    const std::array<std::array<int, 4>, 7> orders = {{{1, 0, 2, 3},
                                                       {0, 1, 3, 2},
                                                       {1, 0, 3, 2},
                                                       {2, 3, 0, 1},
                                                       {3, 2, 0, 1},
                                                       {2, 3, 1, 0},
                                                       {3, 2, 1, 0}}};
    for (const auto& o : orders)
      variants.push_back({"endpoints reordered " + std::to_string(o[0]) + std::to_string(o[1]) +
                              std::to_string(o[2]) + std::to_string(o[3]),
                          batchccd_testing::reordered(q, o)});
  }
  // A few compositions of everything at once.
  for (int k = 0; k < 2; ++k) {
    std::array<int, 3> axes = {0, 1, 2};
    std::shuffle(axes.begin(), axes.end(), rng);
    Query composed = batchccd_testing::axes_flipped(batchccd_testing::axes_permuted(q, axes), uniform_int(rng, 0, 7));
    if (exact)
      composed = batchccd_testing::translated(
          composed, Vec3(uniform_int(rng, -64, 64), uniform_int(rng, -64, 64), uniform_int(rng, -64, 64)));
    if (kind == Kind::vertex_face) {
      std::array<int, 4> corners = {0, 1, 2, 3};
      std::shuffle(corners.begin() + 1, corners.end(), rng);
      composed = batchccd_testing::reordered(composed, corners);
    } else {
      std::array<int, 4> ends = {0, 1, 2, 3};
      if (coin(rng)) std::swap(ends[0], ends[1]);
      if (coin(rng)) std::swap(ends[2], ends[3]);
      if (coin(rng)) ends = {ends[2], ends[3], ends[0], ends[1]};
      composed = batchccd_testing::reordered(composed, ends);
    }
    const bool reversed = coin(rng);
    if (reversed) composed = batchccd_testing::time_reversed(composed);
    variants.push_back({"composed " + std::to_string(k), composed, reversed});
  }
  return variants;
}

// ---------------------------------------------------------------------------
// Power-of-two scaling leaves decisions and TOI bit-identical.

// Zero-area triangles for the tests that run each query many times.
constexpr double kFewSegments = 0.01;

// Random queries for the scaling test: constructed crossings, near misses
// (a crossing shifted by 1e-1 .. 1e-12 of its size), near-coplanar queries
// (all points within 1e-6 .. 0 of the plane z = 0) and clear misses.
Query random_scaling_query(Rng& rng, Kind kind, int family) {
  const PointMaker point = random_point_maker(rng, false);
  switch (family) {
    case 0:
      return random_contact(rng, kind, point, kFewSegments).query;
    case 1: {
      Query q = random_contact(rng, kind, point, kFewSegments).query;
      const Vec3 direction(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
      const Vec3 shift = direction * std::pow(10.0, -uniform(rng, 1, 12)) * batchccd_testing::query_size(q);
      for (int index : moving_points(kind)) q.points[index] += shift;
      return q;
    }
    case 2: {
      static const double heights[] = {0, 1e-15, 1e-12, 1e-9, 1e-6};
      const double height = heights[uniform_int(rng, 0, 4)];
      PointMaker planar = point;
      planar.planar = true;
      Query q = coin(rng) ? random_contact(rng, kind, planar, kFewSegments).query
                          : random_clear_miss(rng, kind, planar);
      for (Vec3& x : q.points) x[2] = height * uniform(rng, -1, 1);
      return q;
    }
    default:
      return random_clear_miss(rng, kind, point);
  }
}

constexpr int kScalingQueries = 200;

void check_scaling(Kind kind, std::uint64_t seed) {
  Rng rng(seed);
  const int exponents[] = {-500, -200, -20, 7, 100, 500};
  int hits = 0;
  for (int n = 0; n < kScalingQueries; ++n) {
    const Query q = random_scaling_query(rng, kind, n % 4);
    for (const lab::Method& method : {lab::kConservative, lab::kFast}) {
      const QueryResult base = run(kind, q, method);
      hits += base.hit;
      for (int exponent : exponents) {
        const QueryResult result = run(kind, batchccd_testing::scaled(q, exponent), method);
        EXPECT_EQ(result.hit, base.hit)
            << lab::to_string(method) << ", scaled by 2^" << exponent << ": "
            << describe(kind, q);
        EXPECT_EQ(result.toi, base.toi)
            << lab::to_string(method) << ", scaled by 2^" << exponent << ": "
            << describe(kind, q);
        EXPECT_EQ(result.status, base.status);
      }
    }
  }
  // The mix must contain both answers, or the test proves little.
  EXPECT_GT(hits, kScalingQueries / 2);
  EXPECT_LT(hits, 2 * kScalingQueries - kScalingQueries / 2);
}

TEST(PropertiesScaling, PowerOfTwoScalingIsBitIdenticalVertexFace) {
  check_scaling(Kind::vertex_face, 0x5ca1e0001);
}

TEST(PropertiesScaling, PowerOfTwoScalingIsBitIdenticalEdgeEdge) {
  check_scaling(Kind::edge_edge, 0x5ca1e0002);
}

// ---------------------------------------------------------------------------
// Constructed contacts are found, no later than the built contact.

void check_constructed_contacts(Kind kind, std::uint64_t seed) {
  Rng rng(seed);
  for (int n = 0; n < 1200; ++n) {
    const PointMaker point = random_point_maker(rng, true);
    const Contact contact = random_contact(rng, kind, point);
    // Any power of two keeps the contact exact (at worst subnormal with few
    // bits); within double range.
    const int exponent = n % 3 == 0 ? uniform_int(rng, -1000, 1000) : 0;
    const Query q = batchccd_testing::scaled(contact.query, exponent);
    const QueryResult r = run(kind, q);
    EXPECT_EQ(r.status, Status::ok);
    EXPECT_TRUE(r.hit) << "missed a contact at t = " << contact.time << ": " << describe(kind, q);
    if (r.hit) {
      EXPECT_GE(r.toi, 0.0);
      EXPECT_LE(r.toi, contact.time + 1e-12)
          << "toi after a contact at t = " << contact.time << ": " << describe(kind, q);
    }
  }
}

TEST(PropertiesNoFalseNegative, ConstructedVertexFaceContactsAreFound) {
  check_constructed_contacts(Kind::vertex_face, 0xc0ac7001);
}

TEST(PropertiesNoFalseNegative, ConstructedEdgeEdgeContactsAreFound) {
  check_constructed_contacts(Kind::edge_edge, 0xc0ac7002);
}

// ---------------------------------------------------------------------------
// Equivalent descriptions: a hit stays a hit, a clear miss stays a miss.

void check_equivalent_hits(Kind kind, std::uint64_t seed) {
  Rng rng(seed);
  for (int n = 0; n < 100; ++n) {
    const PointMaker point = random_point_maker(rng, true);
    const Contact contact = random_contact(rng, kind, point, kFewSegments);
    const QueryResult original = run(kind, contact.query);
    ASSERT_TRUE(original.hit) << describe(kind, contact.query);
    for (const Variant& variant : equivalent_variants(rng, kind, contact.query, true)) {
      const QueryResult r = run(kind, variant.query);
      EXPECT_EQ(r.status, Status::ok);
      EXPECT_TRUE(r.hit) << variant.name << " turned a collision into a miss: "
                         << describe(kind, variant.query) << "\n  original: "
                         << describe(kind, contact.query);
      // Time reversal maps the built contact at t to 1 - t; the first contact
      // of the reversed motion is no later than that (not compared with the
      // forward TOI: reversal maps the first contact to the last).
      const double contact_time = variant.time_reversed ? 1 - contact.time : contact.time;
      if (r.hit) {
        EXPECT_LE(r.toi, contact_time + 1e-12)
            << variant.name << ": toi after a contact at t = " << contact_time << ": "
            << describe(kind, variant.query);
      }
    }
  }
}

void check_equivalent_misses(Kind kind, std::uint64_t seed) {
  Rng rng(seed);
  for (int n = 0; n < 150; ++n) {
    const PointMaker point = random_point_maker(rng, true);
    const Query q = random_clear_miss(rng, kind, point);
    const QueryResult original = run(kind, q);
    EXPECT_FALSE(original.hit) << "false positive on a clear miss: " << describe(kind, q);
    for (const Variant& variant : equivalent_variants(rng, kind, q, true)) {
      const QueryResult r = run(kind, variant.query);
      EXPECT_EQ(r.status, Status::ok);
      EXPECT_FALSE(r.hit) << variant.name << " turned a clear miss into a hit (toi " << r.toi
                          << "): " << describe(kind, variant.query);
      EXPECT_EQ(r.toi, kInfinity);
    }
  }
}

TEST(PropertiesEquivalence, VertexFaceHitsStayHits) {
  check_equivalent_hits(Kind::vertex_face, 0xe9a1001);
}

TEST(PropertiesEquivalence, EdgeEdgeHitsStayHits) {
  check_equivalent_hits(Kind::edge_edge, 0xe9a1002);
}

TEST(PropertiesEquivalence, VertexFaceClearMissesStayMisses) {
  check_equivalent_misses(Kind::vertex_face, 0xe9a1003);
}

TEST(PropertiesEquivalence, EdgeEdgeClearMissesStayMisses) {
  check_equivalent_misses(Kind::edge_edge, 0xe9a1004);
}

// ---------------------------------------------------------------------------
// Near misses that reach the search over (u, v). The clear misses above are
// decided before it (the lane filters, the cubic's signs, the inside and
// outside tests over a time interval); these keep the cubic's signs
// uncertain or the inside tests undecided down to narrow time intervals, so
// that the boxes' exclusion, their error bound and the width called within
// tolerance decide them. Their gaps lie far above `tolerance`: conservative
// mode must report every one a miss.

// A random point of the plane z = 0 (of the kind `point` makes).
Vec3 planar_point(Rng& rng, const PointMaker& point) {
  PointMaker planar = point;
  planar.planar = true;
  return planar(rng);
}

// One of the 48 exact rotations and reflections of the axes, at random.
Query axes_shuffled(Rng& rng, const Query& q) {
  std::array<int, 3> axes = {0, 1, 2};
  std::shuffle(axes.begin(), axes.end(), rng);
  return batchccd_testing::axes_flipped(batchccd_testing::axes_permuted(q, axes), uniform_int(rng, 0, 7));
}

// The middle of one of the four pieces the lane filters cut the step into:
// a closest approach there keeps the cubic's Bernstein signs mixed over
// its piece.
double random_piece_middle(Rng& rng) { return (2 * uniform_int(rng, 0, 3) + 1) / 8.0; }

// A vertex touching a tilting triangle's edge at t0 (random_piece_middle),
// to be raised by a gap (raised below): a and b still in z = 0, c falling
// through it (its height 2 k (t0 - t)), the vertex in z = 0 moving across
// edge ab towards c. Once raised by `gap` it stays above the triangle's
// plane (its height there is gap + 2 k mu (t - t0)^2, mu > 0 the rate at
// which its barycentric coordinate of c grows) and is outside the
// triangle before t0: the cubic has no root, but its signs stay mixed over
// intervals around t0 wider than about sqrt(gap).
Query vertex_grazing_an_edge(Rng& rng, const PointMaker& point) {
  for (;;) {
    const Vec3 a = planar_point(rng, point), b = planar_point(rng, point), c = planar_point(rng, point);
    if ((b - a).cross(c - a).z() == 0) continue;  // a triangle, not a segment
    const double t0 = random_piece_middle(rng);
    const Vec3 fall(0, 0, std::ldexp(2.0, -uniform_int(rng, 0, 2)));
    const Vec3 e = a + uniform_int(rng, 1, 15) / 16.0 * (b - a);  // on edge ab
    const Vec3 velocity = std::ldexp(1.0, -uniform_int(rng, 0, 2)) * (c - e) + uniform_int(rng, -2, 2) / 8.0 * (b - a);
    return {{e - t0 * velocity, a, b, c + t0 * fall, e + (1 - t0) * velocity, a, b, c - (1 - t0) * fall}};
  }
}

// A point of the plane x + y + z = 0 (no axis plane: the swept boxes of
// two such parallel planes overlap).
Vec3 tilted_point(Rng& rng, const PointMaker& point) {
  const Vec3 p = planar_point(rng, point);
  return {p.x(), p.y(), -p.x() - p.y()};
}

// Edge b turning through parallel to edge a at t0 (random_piece_middle)
// while they overlap, both in the plane x + y + z = 0 and carried by one
// translation, to be raised by a gap (raised below). Once raised, b lies
// in a parallel plane gap / sqrt(3) from a's throughout; the cubic's root
// at t0 is where neither inside test can decide.
Query edge_passing_parallel(Rng& rng, const PointMaker& point) {
  for (;;) {
    const Vec3 a0 = tilted_point(rng, point), a1 = tilted_point(rng, point);
    const Vec3 turn = std::ldexp(1.0, -uniform_int(rng, 0, 2)) * tilted_point(rng, point);
    if (a0 == a1 || (a1 - a0).cross(turn) == Vec3::Zero()) continue;  // b must turn through parallel
    const double t0 = random_piece_middle(rng);
    const Vec3 shift = uniform_int(rng, -4, 4) / 8.0 * (a1 - a0);
    const Vec3 b0 = a0 + shift, b1 = a1 + shift;  // at t0
    const Vec3 carried = coin(rng) ? point(rng) : Vec3::Zero();
    return {{a0, a1, b0 - t0 * turn, b1 + t0 * turn, a0 + carried, a1 + carried,
             b0 + (1 - t0) * turn + carried, b1 - (1 - t0) * turn + carried}};
  }
}

// Whether the lane filters leave `q` to the solver.
bool reaches_the_solver(Kind kind, const Query& q, const Options& options = {}) {
  return lab::batch_ccd(kind, std::vector{q}, options, {}).counters.solved == 1;
}

// A time that is no halving point of [0, 1]: a root there leaves the
// cubic's signs to narrow it (at a halving point one of them is zero).
double crossing_time(Rng& rng) { return uniform(rng, 0.1, 0.9); }

// The velocity, relative to primitives carried by one translation, of a
// primitive that is at `target` at the crossing time, beside their plane
// of normal `normal`: it comes from the side of `towards` and off the
// plane (so that in projection it passes over the other primitive, and no
// projection proves the miss) and goes on through the plane.
Vec3 crossing_velocity(Rng& rng, const Vec3& target, const Vec3& towards, const Vec3& normal) {
  const Vec3 inward = towards - target;
  return -uniform(rng, 0.5, 2) * inward - uniform(rng, 0.2, 1) * inward.norm() * normal.normalized();
}

// A vertex crossing a translating triangle's plane at a random time just
// outside it, at barycentric (u, v) with v = -2^-k, or u = -2^-k, or
// u + v = 1 + 2^-k, having come from over the triangle. The cubic has a
// certain root there; only the outside tests and the search tell the miss.
Query vertex_just_outside(Rng& rng, const PointMaker& point, int k) {
  for (;;) {
    const Vec3 a0 = point(rng), b0 = point(rng), c0 = point(rng);
    const Vec3 carried = coin(rng) ? point(rng) : Vec3::Zero();
    const double t = crossing_time(rng);
    const Vec3 a = a0 + t * carried, b = b0 + t * carried, c = c0 + t * carried;
    const Vec3 normal = (b - a).cross(c - a);
    if (normal == Vec3::Zero()) continue;
    const double along = uniform_int(rng, 1, 15) / 16.0, out = std::ldexp(1.0, -k);
    double u = along, v = -out;
    if (const int side = uniform_int(rng, 0, 2); side == 1) {
      u = -out;
      v = along;
    } else if (side == 2) {
      v = 1 + out - along;
    }
    const Vec3 target = a + u * (b - a) + v * (c - a);
    const Vec3 velocity = carried + crossing_velocity(rng, target, (a + b + c) / 3, normal);
    return {{target - t * velocity, a0, b0, c0, target + (1 - t) * velocity, a0 + carried, b0 + carried,
             c0 + carried}};
  }
}

// Edge b, translating, crossing edge a's line at a random time about 2^-k
// of a's length beyond one of its ends, having come from over a.
Query edge_just_outside(Rng& rng, const PointMaker& point, int k) {
  for (;;) {
    const Vec3 a0 = point(rng), a1 = point(rng), direction = point(rng);
    const Vec3 carried = coin(rng) ? point(rng) : Vec3::Zero();
    const double t = crossing_time(rng);
    const Vec3 ea0 = a0 + t * carried, ea1 = a1 + t * carried;
    const Vec3 normal = (ea1 - ea0).cross(direction);
    if (normal == Vec3::Zero()) continue;
    const double out = std::ldexp(1.0, -k), u = coin(rng) ? -out : 1 + out;
    const Vec3 target = ea0 + u * (ea1 - ea0);  // b's first end at t
    const Vec3 velocity = carried + crossing_velocity(rng, target, 0.5 * (ea0 + ea1), normal);
    const Vec3 b0 = target - t * velocity, b1 = target + (1 - t) * velocity;
    return {{a0, a1, b0, b0 + direction, a0 + carried, a1 + carried, b1, b1 + direction}};
  }
}

// `count` queries from `make(k)` (k in [low, high]), each in a random
// orientation, that reach the solver and are certified to stay more than
// 2^-(k+3) of their size apart, far above tolerance.
template <class Make>
std::vector<Query> certified_near_misses(Rng& rng, Kind kind, int count, int low, int high, Make make) {
  std::vector<Query> found;
  while (static_cast<int>(found.size()) < count) {
    const int k = uniform_int(rng, low, high);
    const Query q = axes_shuffled(rng, make(k));
    const double apart = std::ldexp(batchccd_testing::query_size(q), -k - 3);
    if (reaches_the_solver(kind, q) && batchccd_testing::label(kind, q, apart).label == batchccd_testing::Label::miss)
      found.push_back(q);
  }
  return found;
}

// The query with `points` (at both ends) moved up by 2^-k of its size: an
// exact sum for grid points and k <= 20.
Query raised(const Query& q, std::initializer_list<int> points, int k) {
  Query out = q;
  const double gap = std::ldexp(1.0, std::ilogb(batchccd_testing::query_size(q)) - k);
  for (int index : points) out.points[index].z() += gap;
  return out;
}

// Every one of `queries` must be a miss in conservative mode with `options`.
void expect_misses(Kind kind, const std::vector<Query>& queries, const Options& options, const std::string& what) {
  const batchccd::BatchResult batch = lab::batch_ccd(kind, queries, options, {});
  EXPECT_EQ(batch.counters.undecided, 0) << what;
  for (std::size_t i = 0; i < queries.size(); ++i)
    EXPECT_FALSE(batch.results[i].hit) << what << ": a near miss reported a contact at toi "
                                       << batch.results[i].toi << ": " << describe(kind, queries[i]);
}

// Options a user sets for a near miss: the defaults, the decision alone
// (need_toi = false: any interval the search calls within tolerance
// settles the query), a coarse TOI.
std::vector<std::pair<std::string, Options>> near_miss_options() {
  Options decision_only;
  decision_only.need_toi = false;
  std::vector<std::pair<std::string, Options>> all = {{"defaults", Options{}}, {"need_toi = false", decision_only}};
  for (const int k : {6, 8, 10}) {
    Options coarse_toi;
    coarse_toi.toi_tolerance = std::ldexp(1.0, -k);
    all.push_back({"toi_tolerance = 2^-" + std::to_string(k), coarse_toi});
  }
  return all;
}

TEST(PropertiesNearMiss, VertexGrazingAnEdgeIsAMiss) {
  Rng rng(0x9a2e0001);
  const std::vector<Query> queries = certified_near_misses(rng, Kind::vertex_face, 40, 6, 16, [&](int k) {
    return raised(vertex_grazing_an_edge(rng, random_point_maker(rng, true)), {0, 4}, k);
  });
  for (const auto& [name, options] : near_miss_options()) expect_misses(Kind::vertex_face, queries, options, name);
}

TEST(PropertiesNearMiss, EdgePassingParallelIsAMiss) {
  Rng rng(0x9a2e0002);
  std::vector<Query> queries;
  while (queries.size() < 60) {
    const Query built = edge_passing_parallel(rng, random_point_maker(rng, true));
    const Query q = axes_shuffled(rng, raised(built, {2, 3, 6, 7}, uniform_int(rng, 6, 20)));
    if (reaches_the_solver(Kind::edge_edge, q)) queries.push_back(q);
  }
  for (const auto& [name, options] : near_miss_options()) expect_misses(Kind::edge_edge, queries, options, name);
}

TEST(PropertiesNearMiss, VertexJustOutsideIsAMiss) {
  Rng rng(0x9a2e0003);
  const std::vector<Query> queries = certified_near_misses(rng, Kind::vertex_face, 60, 8, 16, [&](int k) {
    return vertex_just_outside(rng, random_point_maker(rng, true), k);
  });
  for (const auto& [name, options] : near_miss_options()) expect_misses(Kind::vertex_face, queries, options, name);
}

TEST(PropertiesNearMiss, EdgeJustOutsideIsAMiss) {
  Rng rng(0x9a2e0004);
  const std::vector<Query> queries = certified_near_misses(rng, Kind::edge_edge, 60, 8, 16, [&](int k) {
    return edge_just_outside(rng, random_point_maker(rng, true), k);
  });
  for (const auto& [name, options] : near_miss_options()) expect_misses(Kind::edge_edge, queries, options, name);
}

// Edge b turning about its middle in the plane x = 1/2, `height` above
// edge a's line, while a (on the x axis, still) ends `short_of` before that
// plane: b's line comes within `height` of a's, but beyond a's end, and
// the edges stay sqrt(short_of^2 + height^2 / (1 + slope^2)) apart, closest
// at a's end. No fixed direction separates them throughout, neither does
// the lines' distance: at a separation above `height` only the search over
// (u, v) proves a miss, or witnesses a contact.
Query edge_turning_past_an_end(double short_of, double height, double slope, double half_length) {
  const double x = 0.5, end = x - short_of, rise = half_length * slope;
  return {{Vec3(0, 0, 0), Vec3(end, 0, 0), Vec3(x, -half_length, height + rise), Vec3(x, half_length, height - rise),
           Vec3(0, 0, 0), Vec3(end, 0, 0), Vec3(x, -half_length, height - rise),
           Vec3(x, half_length, height + rise)}};
}

struct AtASeparation {
  Query query;
  double separation;
};

// edge_turning_past_an_end at a random separation, scale and orientation,
// its height in [low, high] times the separation and its closest approach
// `apart` times it.
AtASeparation random_edges_turning(Rng& rng, double low, double high, double apart) {
  const double separation = std::ldexp(1.0, -uniform_int(rng, 5, 8));
  const double height = uniform(rng, low, high), slope = uniform(rng, 0.5, 2);
  const double short_of = std::sqrt(apart * apart - height * height / (1 + slope * slope));
  const int exponent = uniform_int(rng, -20, 20);
  const Query built = edge_turning_past_an_end(short_of * separation, height * separation, slope, uniform(rng, 0.5, 1));
  return {axes_shuffled(rng, batchccd_testing::scaled(built, exponent)), std::ldexp(separation, exponent)};
}

// At a separation the search over (u, v) has no exact stage behind it.
// Edges whose lines come within the separation while they stay 1.05 times
// it apart (certified beyond 1.02 times) are a miss, decided (not an
// undecided hit), in both certified modes, with need_toi or without.
TEST(PropertiesNearMiss, EdgesTurningPastAnEndAtASeparationAreADecidedMiss) {
  Rng rng(0x9a2e0005);
  for (int checked = 0; checked < 16;) {
    const auto [q, separation] = random_edges_turning(rng, 0.5, 0.9, std::sqrt(1.1));
    Options options;
    options.min_distance = separation;
    if (!reaches_the_solver(Kind::edge_edge, q, options) ||
        batchccd_testing::label(Kind::edge_edge, q, 1.02 * separation).label != batchccd_testing::Label::miss)
      continue;
    ++checked;
    for (const Mode mode : {Mode::conservative, Mode::exact})
      for (const bool need_toi : {true, false}) {
        options.mode = mode;
        options.need_toi = need_toi;
        const std::string what = std::string(batchccd::to_string(mode)) + (need_toi ? "" : ", need_toi = false") +
                                 ", min_distance " + std::to_string(separation) + ": " + describe(Kind::edge_edge, q);
        const batchccd::BatchResult batch = lab::batch_ccd(Kind::edge_edge, std::vector{q}, options, {});
        EXPECT_FALSE(batch.results[0].hit) << what;
        EXPECT_EQ(batch.counters.undecided, 0) << what;
      }
  }
}

// The same edges at half the separation: a hit, decided by a certified
// witness (not an undecided one), no later than the exact labels' witness.
TEST(PropertiesNearMiss, EdgesTurningPastAnEndWithinTheSeparationAreADecidedHit) {
  Rng rng(0x9a2e0006);
  for (int checked = 0; checked < 24;) {
    const auto [q, separation] = random_edges_turning(rng, 0.2, 0.45, 0.5);
    const batchccd_testing::Labelled truth = batchccd_testing::label(Kind::edge_edge, q, separation);
    if (truth.label != batchccd_testing::Label::hit) continue;
    ++checked;
    for (const Mode mode : {Mode::conservative, Mode::exact}) {
      Options options;
      options.mode = mode;
      options.min_distance = separation;
      const std::string what = std::string(batchccd::to_string(mode)) + ", min_distance " +
                               std::to_string(separation) + ": " + describe(Kind::edge_edge, q);
      const batchccd::BatchResult batch = lab::batch_ccd(Kind::edge_edge, std::vector{q}, options, {});
      EXPECT_TRUE(batch.results[0].hit) << what;
      EXPECT_LE(batch.results[0].toi, truth.witness) << what;
      EXPECT_EQ(batch.counters.undecided, 0) << what;
    }
  }
}

// ---------------------------------------------------------------------------
// Extreme magnitudes: every mode returns a well-formed answer.

// sign * [1, 2) * 2^e with e in [-997, 997]: about 1e-300 .. 1e300.
double wild_coordinate(Rng& rng) {
  const double magnitude = std::ldexp(uniform(rng, 1, 2), uniform_int(rng, -997, 997));
  return coin(rng) ? magnitude : -magnitude;
}

Query random_wild_query(Rng& rng, Kind kind, int family) {
  Query q;
  switch (family) {
    case 0:  // every coordinate its own magnitude
      for (Vec3& x : q.points) x = Vec3(wild_coordinate(rng), wild_coordinate(rng), wild_coordinate(rng));
      break;
    case 1: {  // one magnitude for the query, coordinates spread around it
      const int base = uniform_int(rng, -950, 950);
      for (Vec3& x : q.points)
        for (int axis = 0; axis < 3; ++axis)
          x[axis] = std::ldexp(uniform(rng, -1, 1), base + uniform_int(rng, -40, 40));
      break;
    }
    case 2: {  // a contact scaled to an extreme, with a few coordinates made wild
      const PointMaker point = random_point_maker(rng, false);
      q = batchccd_testing::scaled(random_contact(rng, kind, point).query, uniform_int(rng, -1000, 1000));
      for (int k = uniform_int(rng, 0, 3); k > 0; --k)
        q.points[uniform_int(rng, 0, 7)][uniform_int(rng, 0, 2)] = wild_coordinate(rng);
      break;
    }
    default:  // wild coordinates mixed with exact zeros and shared points
      for (Vec3& x : q.points)
        for (int axis = 0; axis < 3; ++axis) x[axis] = coin(rng, 0.3) ? 0.0 : wild_coordinate(rng);
      for (int k = uniform_int(rng, 0, 3); k > 0; --k)
        q.points[uniform_int(rng, 0, 7)] = q.points[uniform_int(rng, 0, 7)];
      break;
  }
  return q;
}

void check_extreme_magnitudes(Kind kind, std::uint64_t seed) {
  Rng rng(seed);
  for (int n = 0; n < 800; ++n) {
    const Query q = random_wild_query(rng, kind, n % 4);
    for (const lab::Method& method : {lab::kConservative, lab::kFast, lab::kCubic}) {
      const QueryResult r = run(kind, q, method);
      const std::string where = std::string(lab::to_string(method)) + ": " + describe(kind, q);
      EXPECT_EQ(r.status, Status::ok) << where;
      EXPECT_FALSE(std::isnan(r.toi)) << where;
      if (r.hit) {
        EXPECT_GE(r.toi, 0.0) << where;
        EXPECT_LE(r.toi, 1.0) << where;
      } else {
        EXPECT_EQ(r.toi, kInfinity) << where;
      }
    }
  }
}

TEST(PropertiesExtremeMagnitudes, VertexFaceWellFormedInEveryMode) {
  check_extreme_magnitudes(Kind::vertex_face, 0xe7e0001);
}

TEST(PropertiesExtremeMagnitudes, EdgeEdgeWellFormedInEveryMode) {
  check_extreme_magnitudes(Kind::edge_edge, 0xe7e0002);
}

// ---------------------------------------------------------------------------
// Non-finite input.

TEST(PropertiesNonFinite, NanOrInfiniteCoordinateIsInvalidInputAndHit) {
  const double bad_values[] = {std::numeric_limits<double>::quiet_NaN(), kInfinity, -kInfinity};
  Rng rng(0xbad0001);
  for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
    for (int point = 0; point < 8; ++point)
      for (int axis = 0; axis < 3; ++axis)
        for (double bad : bad_values) {
          // Both a clear miss and a hit as the otherwise finite query.
          const PointMaker maker;
          const Query misses = random_clear_miss(rng, kind, maker);
          const Query hits = random_contact(rng, kind, maker).query;
          for (Query q : {misses, hits}) {
            q.points[point][axis] = bad;
            for (const lab::Method& method : {lab::kConservative, lab::kFast, lab::kCubic}) {
              const QueryResult r = run(kind, q, method);
              EXPECT_EQ(r.status, Status::invalid_input)
                  << lab::to_string(method) << ": " << describe(kind, q);
              EXPECT_TRUE(r.hit) << lab::to_string(method) << ": " << describe(kind, q);
            }
          }
        }
  }
}

TEST(PropertiesNonFinite, EveryCoordinateNonFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Query q;
  for (Vec3& x : q.points) x = Vec3(nan, kInfinity, -kInfinity);
  for (Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const lab::Method& method : {lab::kConservative, lab::kFast, lab::kCubic}) {
      const QueryResult r = run(kind, q, method);
      EXPECT_EQ(r.status, Status::invalid_input);
      EXPECT_TRUE(r.hit);
    }
}

}  // namespace

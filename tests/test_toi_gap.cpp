// A TOI a simulator can step to: conservative mode's TOI
// against the first contact (exact mode's TOI, less than 2^-40 before it) on
// adversarial queries and the stiff and extreme suite. Each case prints
// both. What is asserted is the promise of Mode::conservative (options.hpp):
// never after the first contact; at most toi_tolerance before it unless the
// primitives come within `tolerance` of each other earlier -- and then they
// are within it at the reported TOI.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include <gtest/gtest.h>

#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "batchccd/options.hpp"
#include "exact_distance.hpp"
#include "extreme_suite.hpp"

namespace batchccd {
namespace {

constexpr double kExactToiWidth = 0x1p-40;

Query vertex_face(const Vec3& p0, const Vec3& a0, const Vec3& b0, const Vec3& c0, const Vec3& p1,
                  const Vec3& a1, const Vec3& b1, const Vec3& c1) {
  return Query{{p0, a0, b0, c0, p1, a1, b1, c1}};
}

// Exact mode's promise against a known first contact `root`: never after
// it, less than 2^-40 before it (compared in rationals).
void expect_exact_first_contact(const QueryResult& exact, const testing::Rational& root) {
  ASSERT_TRUE(exact.hit) << "first contact at " << root.get_d();
  EXPECT_LE(testing::Rational(exact.toi), root) << "toi " << exact.toi << " after the first contact";
  EXPECT_LT(root - testing::Rational(exact.toi), testing::Rational(kExactToiWidth)) << "toi " << exact.toi;
}

struct Tois {
  QueryResult exact, conservative;
  std::int64_t exact_stage = 0;  // the conservative call's
};

Tois measure(const std::string& name, Kind kind, const Query& query) {
  Options exact;
  exact.mode = Mode::exact;
  const BatchResult batch = batch_ccd(kind, std::span<const Query>(&query, 1), Options{});
  const Tois tois{query_ccd(kind, query, exact), query_ccd(kind, query, Options{}),
                  batch.counters.exact_escalations};
  std::printf("[toi gap] %-44s exact %d %.17g  conservative %d %.17g (exact stage %lld)  gap %.3e\n",
              name.c_str(), tois.exact.hit, tois.exact.toi, tois.conservative.hit, tois.conservative.toi,
              static_cast<long long>(tois.exact_stage),
              tois.exact.hit && tois.conservative.hit ? tois.exact.toi - tois.conservative.toi : NAN);
  return tois;
}

// The promise on one hit: never after the first contact; at most
// toi_tolerance before it, or the primitives within (about) tolerance of
// each other at the reported TOI.
void expect_promised_toi(Kind kind, const Query& query, const Tois& tois) {
  ASSERT_TRUE(tois.exact.hit);
  ASSERT_TRUE(tois.conservative.hit);
  EXPECT_LE(tois.conservative.toi, tois.exact.toi + kExactToiWidth);
  if (tois.exact.toi - tois.conservative.toi > Options{}.toi_tolerance) {
    const double distance = std::sqrt(squared_distance(kind, query, tois.conservative.toi));
    EXPECT_LE(distance, 4 * Options{}.tolerance * testing::query_size(query))
        << "a TOI " << tois.exact.toi - tois.conservative.toi
        << " before the contact without the primitives within tolerance there";
  }
}

// det[b - a, c - a, p - a] = s^3 with s = 3t - 1: a at the origin,
// b - a = (1, s, 0), c - a = (0, 1, s), p - a = (s, 0, 0) + (b - a)/4 + (c - a)/4
// (adding multiples of the other rows leaves the determinant alone). At
// t = 1/3 the triangle is (0,0,0), (1,0,0), (0,1,0) and p = (1/4, 1/4, 0),
// inside it: the only root of the cubic, a triple one, is the first contact.
// `shear` adds shear times x to y (the determinant stays s^3): the triangle
// becomes a sliver shear long, and p comes within s^2 / shear of it.
Query triple_root(double shear = 0) {
  auto at = [&](double s) {
    auto sheared = [&](const Vec3& x) { return Vec3(x.x(), shear * x.x() + x.y(), x.z()); };
    return std::array<Vec3, 4>{sheared(Vec3(s + 0.25, 0.25 * s + 0.25, 0.25 * s)), Vec3(0, 0, 0),
                               sheared(Vec3(1, s, 0)), sheared(Vec3(0, 1, s))};
  };
  const auto t0 = at(-1), t1 = at(2);
  return vertex_face(t0[0], t0[1], t0[2], t0[3], t1[0], t1[1], t1[2], t1[3]);
}

// Edge a (0,0,0)-(1,0,0) still; edge b, one unit along y at x = 1/2, its
// far end 2^-33 out of the plane z = 0, slides `travel` along y: nearly
// coplanar throughout. Only its near end lies in z = 0; it reaches edge a
// when its y, about (0.609 - t) travel, reaches 0: exactly at
// near_coplanar_contact (the ends' y as doubles hold them).
Query near_coplanar_edges(double travel) {
  const double e = 0x1p-33;
  return Query{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.609 * travel, 0), Vec3(0.5 + e, 0.609 * travel + 1, e),
                Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, (0.609 - 1) * travel, 0),
                Vec3(0.5 - e, (0.609 - 1) * travel + 1, e)}};
}

testing::Rational near_coplanar_contact(const Query& edges) {
  const testing::Rational start(edges.points[2].y()), end(edges.points[6].y());
  return start / (start - end);
}

// A unit triangle in z = 0 whose corner c moves out to (0, 2^200, 0); the
// vertex crosses the plane at t = 0.4 at (1/8, 1/8, 0), inside it throughout.
Query huge_corner_motion() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c0(0, 1, 0), c1(0, 0x1p200, 0);
  return vertex_face(Vec3(0.125, 0.125, 1), a, b, c0, Vec3(0.125, 0.125, -1.5), a, b, c1);
}

// A unit triangle in z = 0, still, and a vertex sweeping `sweep` along x
// while it falls through the plane at t = 7/16 at (1/8, 1/8, 0).
Query huge_vertex_sweep(double sweep) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return vertex_face(Vec3(0.125 - sweep * 0.4375, 0.125, 0.4375), a, b, c,
                     Vec3(0.125 + sweep * 0.5625, 0.125, -0.5625), a, b, c);
}

// A unit triangle in z = 0, still, and a vertex moving 2^200 along (1, 0, 1)
// on the line x - z = -1e48: it crosses the triangle's plane at t = 1/2,
// 1e48 outside the triangle, and is never nearer to it than 1e48 / sqrt(2).
Query huge_motion_far_vertex() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return vertex_face(Vec3(-0x1p199, 0, -0x1p199 + 1e48), a, b, c, Vec3(0x1p199, 0, 0x1p199 + 1e48), a, b, c);
}

TEST(ToiGap, TripleRootAtOneThird) {
  const Query query = triple_root();
  const Tois tois = measure("triple root at 1/3", Kind::vertex_face, query);
  expect_exact_first_contact(tois.exact, testing::Rational(1, 3));
  expect_promised_toi(Kind::vertex_face, query, tois);
  EXPECT_LE(tois.exact.toi - tois.conservative.toi, Options{}.toi_tolerance);
}

// Sheared, the sliver triangle and the vertex come within s^2 / shear of
// each other long before t = 1/3 (2e-12 at t = 0.3326 for shear 1e6, with
// tolerance 1e-9 times about 1e6): the promise allows the earlier TOI, and
// the primitives are within tolerance there.
TEST(ToiGap, ShearedTripleRootIsWithinToleranceEarlier) {
  for (const double shear : {1e2, 1e4, 1e6, 1e8}) {
    const Query query = triple_root(shear);
    const Tois tois = measure("triple root at 1/3, shear " + std::to_string(shear), Kind::vertex_face, query);
    expect_exact_first_contact(tois.exact, testing::Rational(1, 3));
    expect_promised_toi(Kind::vertex_face, query, tois);
  }
}

TEST(ToiGap, NearCoplanarEdges) {
  for (const double travel : {1.0, 1e3, 1e6}) {
    const Query query = near_coplanar_edges(travel);
    const Tois tois =
        measure("near-coplanar edges at 0.609, travel " + std::to_string(travel), Kind::edge_edge, query);
    expect_exact_first_contact(tois.exact, near_coplanar_contact(query));
    expect_promised_toi(Kind::edge_edge, query, tois);
    EXPECT_LE(tois.exact.toi - tois.conservative.toi, Options{}.toi_tolerance);
  }
}

TEST(ToiGap, HugeMotion) {
  {
    const Query query = huge_corner_motion();
    const Tois tois = measure("contact at 0.4, a corner moving 2^200", Kind::vertex_face, query);
    expect_exact_first_contact(tois.exact, testing::Rational(2, 5));  // z = 1 - 5t/2
    expect_promised_toi(Kind::vertex_face, query, tois);
    EXPECT_LE(tois.exact.toi - tois.conservative.toi, Options{}.toi_tolerance);
  }
  for (const double sweep : {0x1p20, 0x1p100, 0x1p200}) {
    const Query query = huge_vertex_sweep(sweep);
    const Tois tois =
        measure("contact at 7/16, vertex sweeping 2^" + std::to_string(std::ilogb(sweep)), Kind::vertex_face, query);
    expect_exact_first_contact(tois.exact, testing::Rational(7, 16));
    expect_promised_toi(Kind::vertex_face, query, tois);
    EXPECT_LE(tois.exact.toi - tois.conservative.toi, Options{}.toi_tolerance);
  }
}

// Within tolerance of the whole motion (1e-9 of 2^200 is 1.6e51) but 1e48
// from the triangle whenever the vertex is near it: measured against the
// query's size over each time interval, no contact.
TEST(ToiGap, HugeMotionFarVertexIsNoContact) {
  const Tois tois = measure("vertex 1e48 from a unit triangle", Kind::vertex_face, huge_motion_far_vertex());
  EXPECT_FALSE(tois.exact.hit);
  EXPECT_FALSE(tois.conservative.hit);
}

// The stiff and extreme suite: every hit both modes report keeps the promise.
TEST(ToiGap, StiffAndExtremeSuite) {
  Options exact;
  exact.mode = Mode::exact;
  for (const scenes::ExtremeCategory& category : scenes::extreme_categories()) {
    const BatchResult reference = batch_ccd(category.kind, category.queries, exact);
    const BatchResult conservative = batch_ccd(category.kind, category.queries, Options{});
    double largest = 0;
    for (std::size_t i = 0; i < category.queries.size(); ++i) {
      const Tois tois{reference.results[i], conservative.results[i], 0};
      if (!tois.exact.hit || !tois.conservative.hit) continue;
      largest = std::max(largest, tois.exact.toi - tois.conservative.toi);
      SCOPED_TRACE(category.name + " #" + std::to_string(i));
      expect_promised_toi(category.kind, category.queries[i], tois);
    }
    std::printf("[toi gap] %-20s %s largest gap %.3e\n", category.name.c_str(), to_string(category.kind), largest);
  }
}

}  // namespace
}  // namespace batchccd

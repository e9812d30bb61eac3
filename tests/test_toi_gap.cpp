// Issue #19 item 7, "a TOI a simulator can step to": conservative mode's TOI
// against the first contact (exact mode's TOI, less than 2^-40 before it) on
// adversarial queries. Each case prints both; what is asserted is what the
// promise of Mode::conservative (options.hpp) says of it.

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "batchccd/options.hpp"

namespace batchccd {
namespace {

constexpr double kExactToiWidth = 0x1p-40;

Query vertex_face(const Vec3& p0, const Vec3& a0, const Vec3& b0, const Vec3& c0, const Vec3& p1,
                  const Vec3& a1, const Vec3& b1, const Vec3& c1) {
  return Query{{p0, a0, b0, c0, p1, a1, b1, c1}};
}

struct Tois {
  QueryResult exact, conservative;
};

Tois measure(const std::string& name, Kind kind, const Query& query) {
  Options exact;
  exact.mode = Mode::exact;
  const Tois tois{query_ccd(kind, query, exact), query_ccd(kind, query, Options{})};
  const BatchResult batch = batch_ccd(kind, std::span<const Query>(&query, 1), Options{});
  std::printf("[toi gap] %-40s exact %d %.17g  conservative %d %.17g (exact stage %lld)  gap %.3e\n", name.c_str(),
              tois.exact.hit, tois.exact.toi, tois.conservative.hit, tois.conservative.toi,
              static_cast<long long>(batch.counters.exact_escalations),
              tois.exact.hit && tois.conservative.hit ? tois.exact.toi - tois.conservative.toi : NAN);
  return tois;
}

// det[b - a, c - a, p - a] = s^3 with s = 3t - 1: a at the origin,
// b - a = (1, s, 0), c - a = (0, 1, s), p - a = (s, 0, 0) + (b - a)/4 + (c - a)/4
// (adding multiples of the other rows leaves the determinant alone). At
// t = 1/3 the triangle is (0,0,0), (1,0,0), (0,1,0) and p = (1/4, 1/4, 0),
// inside it: the only root of the cubic, a triple one, is the first contact.
Query triple_root() {
  auto at = [](double s) {
    return std::array<Vec3, 4>{Vec3(s + 0.25, 0.25 * s + 0.25, 0.25 * s), Vec3(0, 0, 0), Vec3(1, s, 0),
                               Vec3(0, 1, s)};
  };
  const auto t0 = at(-1), t1 = at(2);
  return vertex_face(t0[0], t0[1], t0[2], t0[3], t1[0], t1[1], t1[2], t1[3]);
}

// Edge a (0,0,0)-(1,0,0) still; edge b runs along y at x = 1/2 and slides
// down in the plane z = 0, its far end raised 2^-33 out of it: nearly
// coplanar throughout. Its near end reaches edge a when y = 0.609 - t
// reaches 0 (in doubles: the t1 end is 0.609 - 1 rounded).
Query near_coplanar_edges() {
  return Query{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.609, 0), Vec3(0.5, 1.609, 0x1p-33), Vec3(0, 0, 0),
                Vec3(1, 0, 0), Vec3(0.5, 0.609 - 1, 0), Vec3(0.5, 1.609 - 1, 0x1p-33)}};
}

// A unit triangle in z = 0 whose corner c moves out to (0, 2^200, 0); the
// vertex crosses the plane at t = 0.4 at (1/8, 1/8, 0), inside it throughout.
Query huge_motion_contact() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c0(0, 1, 0), c1(0, 0x1p200, 0);
  return vertex_face(Vec3(0.125, 0.125, 1), a, b, c0, Vec3(0.125, 0.125, -1.5), a, b, c1);
}

// A unit triangle in z = 0, still, and a vertex moving 2^200 along (1, 0, 1)
// on the line x - z = -1e48: it crosses the triangle's plane at t = 1/2,
// 1e48 outside the triangle, and is never nearer to it than 1e48 / sqrt(2).
Query huge_motion_far_vertex() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  return vertex_face(Vec3(-0x1p199, 0, -0x1p199 + 1e48), a, b, c, Vec3(0x1p199, 0, 0x1p199 + 1e48), a, b, c);
}

TEST(ToiGap, TripleRootAtOneThird) {
  const Tois tois = measure("triple root at 1/3", Kind::vertex_face, triple_root());
  ASSERT_TRUE(tois.exact.hit);
  EXPECT_NEAR(tois.exact.toi, 1.0 / 3, kExactToiWidth);
  ASSERT_TRUE(tois.conservative.hit);
  EXPECT_LE(tois.conservative.toi, tois.exact.toi + kExactToiWidth);
}

TEST(ToiGap, NearCoplanarEdges) {
  const Tois tois = measure("near-coplanar edges, contact ~0.609", Kind::edge_edge, near_coplanar_edges());
  ASSERT_TRUE(tois.exact.hit);
  EXPECT_NEAR(tois.exact.toi, 0.609, 1e-12);
  ASSERT_TRUE(tois.conservative.hit);
  EXPECT_LE(tois.conservative.toi, tois.exact.toi + kExactToiWidth);
}

TEST(ToiGap, HugeMotionContact) {
  const Tois tois = measure("contact at 0.4, a corner moving 2^200", Kind::vertex_face, huge_motion_contact());
  ASSERT_TRUE(tois.exact.hit);
  EXPECT_NEAR(tois.exact.toi, 0.4, 1e-12);
  ASSERT_TRUE(tois.conservative.hit);
  EXPECT_LE(tois.conservative.toi, tois.exact.toi + kExactToiWidth);
}

TEST(ToiGap, HugeMotionFarVertex) {
  const Tois tois = measure("vertex 1e48 from a unit triangle", Kind::vertex_face, huge_motion_far_vertex());
  EXPECT_FALSE(tois.exact.hit);
}

}  // namespace
}  // namespace batchccd

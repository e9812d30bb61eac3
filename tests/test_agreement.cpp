// Every path against every other on seeded near-miss and colliding queries
// of every kind and scale, with and without a separation: the batch lanes
// of every instruction set and the scalar path give the same answers bit
// for bit, and conservative mode never misses what exact mode finds, nor
// reports its TOI after exact mode's (docs/design.md §7).
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "same_answers.hpp"

namespace batchccd {
namespace {

// Positions at a time t* where the primitives touch (or pass `gap` apart),
// moved linearly from there to t = 0 and t = 1 with random velocities.
class NearMisses {
 public:
  explicit NearMisses(std::uint64_t seed) : random_(seed) {}

  struct Case {
    Query query;
    double gap = 0;  // 0: they touch at t* (up to rounding)
  };

  // The first primitive (the vertex, edge a, point p) moves relative to
  // the other across the gap's direction, so the gap is their closest
  // approach: just beyond a triangle's edge, an edge's end, a point.
  Case next(Kind kind) {
    Case c;
    c.gap = pick(3) == 0 ? 0.0 : std::ldexp(1.0, -static_cast<int>(4 + pick(40)));
    std::vector<Vec3> at;  // the points at t*, in make_query's order for the kind
    Vec3 across = Vec3::Zero();  // the first primitive's motion relative to the other
    const Vec3 base = point();
    switch (kind) {
      case Kind::vertex_face: {
        const Vec3 a = base, b = base + point(), c3 = base + point();
        const Vec3 n = (b - a).cross(c3 - a).normalized();
        const Vec3 outward = n.cross(b - a).normalized();  // in the plane, away from c across edge ab
        const Vec3 beside = a + uniform(0, 1) * (b - a) + (outward.dot(c3 - a) > 0 ? -c.gap : c.gap) * outward;
        at = {beside, a, b, c3};
        across = n;
        break;
      }
      case Kind::edge_edge: {
        const Vec3 a0 = base, a1 = base + point(), d = point();
        const Vec3 short_end = a1 - c.gap * (a1 - a0).normalized();
        const double s = uniform(0, 1);
        at = {short_end - (a1 - a0), short_end, a1 - s * d, a1 + (1 - s) * d};  // edge a ends the gap short of b
        across = (a1 - a0).cross(d).normalized();
        break;
      }
      case Kind::vertex_edge: {
        const Vec3 e0 = base, e1 = base + point();
        at = {e1 + c.gap * (e1 - e0).normalized(), e0, e1};
        across = (e1 - e0).cross(unit()).normalized();
        break;
      }
      case Kind::vertex_vertex: {
        const Vec3 n = unit();
        at = {base + c.gap * n, base};
        across = n.cross(unit()).normalized();
        break;
      }
    }
    const double contact_time = uniform(0, 1), scale = std::ldexp(1.0, static_cast<int>(pick(601)) - 300);
    const Vec3 common = point(), relative = uniform(0.1, 1) * across;
    std::vector<Vec3> t0, t1;
    for (std::size_t k = 0; k < at.size(); ++k) {
      const bool first = kind == Kind::edge_edge ? k < 2 : k == 0;
      const Vec3 velocity = first ? common + relative : common;
      t0.push_back(scale * (at[k] - contact_time * velocity));
      t1.push_back(scale * (at[k] + (1 - contact_time) * velocity));
    }
    c.query = make_query(kind, t0, t1);
    c.gap *= scale;
    return c;
  }

 private:
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(random_); }
  double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(random_); }
  Vec3 point() { return {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)}; }
  Vec3 unit() { return point().normalized(); }

  std::mt19937_64 random_;
};

constexpr Kind kKinds[] = {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex};

TEST(PathsAgree, LanesScalarAndExactOnNearMisses) {
  NearMisses generator(20261124);
  for (const Kind kind : kKinds) {
    std::vector<Query> queries;
    std::vector<double> separations;
    for (int n = 0; n < 160; ++n) {
      const NearMisses::Case c = generator.next(kind);
      queries.push_back(c.query);
      // Half without a separation; the others just above or below the gap.
      separations.push_back(n % 2 == 0 ? 0.0 : c.gap * (n % 4 == 1 ? 0.5 : 2.0));
    }
    Options conservative, exact;
    exact.mode = Mode::exact;
    BatchResult reference;
    conservative.isa = Isa::scalar;
    batch_ccd(kind, queries, separations, conservative, reference);
    for (const Isa isa : available_isas()) {
      conservative.isa = isa;
      BatchResult lanes;
      batch_ccd(kind, queries, separations, conservative, lanes);
      testing::expect_same_answers(lanes, reference, std::string(to_string(kind)) + " " + to_string(isa));
    }
    BatchResult decided;
    batch_ccd(kind, queries, separations, exact, decided);
    int hits = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      Options single = conservative;
      single.min_distance = separations[i];
      const QueryResult alone = query_ccd(kind, queries[i], single);
      EXPECT_EQ(alone.hit, reference.results[i].hit) << to_string(kind) << " " << i;
      EXPECT_EQ(alone.toi, reference.results[i].toi) << to_string(kind) << " " << i;
      if (!decided.results[i].hit) continue;
      ++hits;
      // Both TOIs lie at or before the first contact, exact mode's within 2^-40 of it.
      EXPECT_TRUE(reference.results[i].hit) << "conservative missed " << to_string(kind) << " " << i;
      EXPECT_LE(reference.results[i].toi, decided.results[i].toi + 0x1p-40) << to_string(kind) << " " << i;
    }
    // The generator makes both contacts and misses of every kind.
    EXPECT_GT(hits, 10) << to_string(kind);
    EXPECT_LT(hits, 120) << to_string(kind);
  }
}

}  // namespace
}  // namespace batchccd

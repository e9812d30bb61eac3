// The calls shaped like ipc-toolkit's (ipc.hpp): 2D points read as z = 0 and
// never past their end, 3D-only calls that refuse 2D points, the rules
// ipc-toolkit applies around its solver (no motion, the effective
// separation, the retry of a small toi), and NarrowPhase, also behind the
// adapter to ipc::NarrowPhaseCCD that ipc.hpp shows.
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "expect_refused.hpp"

namespace {

using batchccd::Vec3;
using Eigen::Vector2d;
using Eigen::VectorXd;
namespace ipc = batchccd::ipc;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Which points each call takes, asked at compile time.
template <class P, class Q = P>
concept PointPointTakes = requires(const P& p, const Q& q, double& toi) { ipc::point_point_ccd(p, q, p, q, toi); };
template <class P, class Q = P>
concept PointEdgeTakes =
    requires(const P& p, const Q& q, double& toi) { ipc::point_edge_ccd(p, q, q, p, q, q, toi); };
template <class P, class Q = P>
concept EdgeEdgeTakes =
    requires(const P& p, const Q& q, double& toi) { ipc::edge_edge_ccd(p, q, q, q, p, q, q, q, toi); };
template <class P, class Q = P>
concept PointTriangleTakes =
    requires(const P& p, const Q& q, double& toi) { ipc::point_triangle_ccd(p, q, q, q, p, q, q, q, toi); };

using MapXd = Eigen::Map<const VectorXd>;
using RefXd = Eigen::Ref<const VectorXd>;

// 2D or 3D, fixed or dynamic, for the point calls.
static_assert(PointPointTakes<Vector2d> && PointPointTakes<Vec3> && PointPointTakes<VectorXd> &&
              PointPointTakes<MapXd> && PointPointTakes<RefXd> && PointPointTakes<Eigen::RowVector2d>);
static_assert(PointEdgeTakes<Vector2d> && PointEdgeTakes<Vec3> && PointEdgeTakes<VectorXd> &&
              PointEdgeTakes<MapXd> && PointEdgeTakes<RefXd> && PointEdgeTakes<Vector2d, VectorXd>);
// Fixed lengths that do not fit: refused at compile time.
static_assert(!PointPointTakes<Vector2d, Vec3> && !PointPointTakes<Eigen::Vector4d> &&
              !PointPointTakes<Eigen::Matrix<double, 1, 1>> && !PointPointTakes<Eigen::Vector2f>);
static_assert(!PointEdgeTakes<Vector2d, Vec3> && !PointEdgeTakes<Vec3, Vector2d> && !PointEdgeTakes<Eigen::Vector4d>);
// 3D only.
static_assert(PointTriangleTakes<Vec3> && PointTriangleTakes<VectorXd> && EdgeEdgeTakes<Vec3> &&
              EdgeEdgeTakes<MapXd>);
static_assert(!PointTriangleTakes<Vector2d> && !PointTriangleTakes<Vec3, Vector2d> &&
              !PointTriangleTakes<Eigen::Vector4d>);
static_assert(!EdgeEdgeTakes<Vector2d> && !EdgeEdgeTakes<Vec3, Vector2d> && !EdgeEdgeTakes<Eigen::Vector4d>);

Vec3 spatial(const Vector2d& point) { return {point.x(), point.y(), 0}; }

Vector2d lerp(const Vector2d& a, const Vector2d& b, double t) { return a + t * (b - a); }

// A 2D point kept in a buffer with a NaN right after it: a call that reads
// past the 2-vector's end sees the NaN and reports toi = 0.
struct FencedPoint {
  explicit FencedPoint(const Vector2d& point) : storage{point.x(), point.y(), kNaN} {}
  MapXd view() const { return MapXd(storage.data(), 2); }
  std::array<double, 3> storage;
};

// Point p against edge (e0, e1) in the plane, six points t0 then t1.
struct PlanarPointEdge {
  std::array<Vector2d, 6> x;  // p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1
  double contact_time = 0;    // when they certainly meet (the first contact is no later)
};

// The point reaches the edge's interior at contact_time.
PlanarPointEdge planar_point_edge_impact(std::mt19937_64& random) {
  std::uniform_real_distribution<double> coordinate(-1, 1), time(0.05, 0.95), along(0.1, 0.9);
  PlanarPointEdge c;
  for (Vector2d& point : c.x) point = {coordinate(random), coordinate(random)};
  c.contact_time = time(random);
  const Vector2d met = lerp(lerp(c.x[1], c.x[4], c.contact_time), lerp(c.x[2], c.x[5], c.contact_time),
                            along(random));
  c.x[3] = c.x[0] + (met - c.x[0]) / c.contact_time;
  return c;
}

// The edge stays in x <= 0 and the point in x >= 0.5: at least 0.5 apart.
PlanarPointEdge planar_point_edge_miss(std::mt19937_64& random) {
  std::uniform_real_distribution<double> coordinate(-1, 1), left(-1, 0), right(0.5, 1.5);
  PlanarPointEdge c;
  for (Vector2d& point : c.x) point = {left(random), coordinate(random)};
  c.x[0].x() = right(random);
  c.x[3].x() = right(random);
  c.contact_time = std::numeric_limits<double>::infinity();
  return c;
}

struct Answer {
  bool hit;
  double toi;
};

template <class Point>
Answer point_edge(const std::array<Point, 6>& x, double min_distance) {
  double toi = -1;
  const bool hit = ipc::point_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], toi, min_distance);
  return {hit, toi};
}

// The same question with 2-vectors (fixed, and dynamic in fenced buffers)
// and with 3-vectors at z = 0: the same answer.
Answer planar_point_edge(const PlanarPointEdge& c, double min_distance) {
  std::array<Vec3, 6> in_space;
  std::array<FencedPoint, 6> fenced = {FencedPoint(c.x[0]), FencedPoint(c.x[1]), FencedPoint(c.x[2]),
                                       FencedPoint(c.x[3]), FencedPoint(c.x[4]), FencedPoint(c.x[5])};
  std::array<MapXd, 6> dynamic = {fenced[0].view(), fenced[1].view(), fenced[2].view(),
                                  fenced[3].view(), fenced[4].view(), fenced[5].view()};
  for (int k = 0; k < 6; ++k) in_space[k] = spatial(c.x[k]);
  const Answer planar = point_edge(c.x, min_distance);
  const Answer through_maps = point_edge(dynamic, min_distance);
  const Answer spatial_answer = point_edge(in_space, min_distance);
  EXPECT_EQ(planar.hit, spatial_answer.hit);
  EXPECT_EQ(planar.toi, spatial_answer.toi);
  EXPECT_EQ(through_maps.hit, spatial_answer.hit);
  EXPECT_EQ(through_maps.toi, spatial_answer.toi);
  return planar;
}

TEST(IpcPlanar, PointEdgeImpactsAndMisses) {
  std::mt19937_64 random(28);
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const PlanarPointEdge c = planar_point_edge_impact(random);
    for (const double min_distance : {0.0, 0.01}) {
      const Answer answer = planar_point_edge(c, min_distance);
      EXPECT_TRUE(answer.hit) << "impact " << i << " at " << c.contact_time;
      EXPECT_GE(answer.toi, 0.0);
      EXPECT_LE(answer.toi, c.contact_time) << "impact " << i;
      hits += answer.hit;
    }
  }
  EXPECT_EQ(hits, 800);
  for (int i = 0; i < 400; ++i) {
    const PlanarPointEdge c = planar_point_edge_miss(random);
    for (const double min_distance : {0.0, 0.25}) {
      const Answer answer = planar_point_edge(c, min_distance);
      EXPECT_FALSE(answer.hit) << "miss " << i;
      EXPECT_EQ(answer.toi, -1);  // untouched
    }
  }
}

TEST(IpcPlanar, PointPointImpactsAndMisses) {
  std::mt19937_64 random(280);
  std::uniform_real_distribution<double> coordinate(-1, 1), time(0.05, 0.95), right(0.5, 1.5);
  const double min_distance = 0.01;
  for (int i = 0; i < 400; ++i) {
    // p reaches q at contact_time.
    std::array<Vector2d, 4> x;  // p_t0, q_t0, p_t1, q_t1
    for (Vector2d& point : x) point = {coordinate(random), coordinate(random)};
    const double contact_time = time(random);
    x[2] = x[0] + (lerp(x[1], x[3], contact_time) - x[0]) / contact_time;
    const std::array<FencedPoint, 4> fenced = {FencedPoint(x[0]), FencedPoint(x[1]), FencedPoint(x[2]),
                                               FencedPoint(x[3])};
    double toi = -1, toi_fenced = -1, toi_spatial = -1;
    ASSERT_TRUE(ipc::point_point_ccd(x[0], x[1], x[2], x[3], toi, min_distance)) << "impact " << i;
    EXPECT_GE(toi, 0.0);
    EXPECT_LE(toi, contact_time);
    EXPECT_TRUE(ipc::point_point_ccd(fenced[0].view(), fenced[1].view(), fenced[2].view(), fenced[3].view(),
                                     toi_fenced, min_distance));
    EXPECT_TRUE(ipc::point_point_ccd(spatial(x[0]), spatial(x[1]), spatial(x[2]), spatial(x[3]), toi_spatial,
                                     min_distance));
    EXPECT_EQ(toi_fenced, toi_spatial);
    EXPECT_EQ(toi, toi_spatial);
  }
  for (int i = 0; i < 400; ++i) {
    // p stays in x >= 0.5, q in x <= 0.
    std::array<Vector2d, 4> x;
    for (Vector2d& point : x) point = {-right(random) + 0.5, coordinate(random)};
    x[0].x() = right(random);
    x[2].x() = right(random);
    const std::array<FencedPoint, 4> fenced = {FencedPoint(x[0]), FencedPoint(x[1]), FencedPoint(x[2]),
                                               FencedPoint(x[3])};
    double toi = -1;
    EXPECT_FALSE(ipc::point_point_ccd(x[0], x[1], x[2], x[3], toi, min_distance)) << "miss " << i;
    EXPECT_FALSE(ipc::point_point_ccd(fenced[0].view(), fenced[1].view(), fenced[2].view(), fenced[3].view(), toi,
                                      min_distance))
        << "miss " << i;
    EXPECT_EQ(toi, -1);
  }
}

// A point crossing an edge in the plane, through every kind of 2-vector.
TEST(IpcPlanar, EveryKindOfVector) {
  const Vector2d p_t0(0.5, 1), p_t1(0.5, -1), e0(0, 0), e1(1, 0);
  double toi = -1;
  ASSERT_TRUE(ipc::point_edge_ccd(p_t0, e0, e1, p_t1, e0, e1, toi));
  const double expected = toi;
  EXPECT_LE(expected, 0.5);
  EXPECT_GE(expected, 0.5 - 1e-4);

  const VectorXd dynamic_p_t0 = p_t0, dynamic_p_t1 = p_t1, dynamic_e0 = e0, dynamic_e1 = e1;
  toi = -1;
  EXPECT_TRUE(ipc::point_edge_ccd(dynamic_p_t0, dynamic_e0, dynamic_e1, dynamic_p_t1, dynamic_e0, dynamic_e1, toi));
  EXPECT_EQ(toi, expected);

  const RefXd ref_p_t0(dynamic_p_t0), ref_p_t1(dynamic_p_t1), ref_e0(dynamic_e0), ref_e1(dynamic_e1);
  toi = -1;
  EXPECT_TRUE(ipc::point_edge_ccd(ref_p_t0, ref_e0, ref_e1, ref_p_t1, ref_e0, ref_e1, toi));
  EXPECT_EQ(toi, expected);

  // Rows of a matrix of points, and an expression.
  Eigen::Matrix<double, 4, 2> rows;
  rows << p_t0.transpose(), p_t1.transpose(), e0.transpose(), e1.transpose();
  toi = -1;
  EXPECT_TRUE(ipc::point_edge_ccd(rows.row(0), rows.row(2), rows.row(3), rows.row(1), rows.row(2), rows.row(3), toi));
  EXPECT_EQ(toi, expected);
  toi = -1;
  EXPECT_TRUE(ipc::point_edge_ccd(p_t0, e0, e1, p_t0 + (p_t1 - p_t0), e0, e1, toi));
  EXPECT_EQ(toi, expected);

  // Fixed and dynamic lengths mixed: checked at run time, and they agree.
  toi = -1;
  EXPECT_TRUE(ipc::point_edge_ccd(p_t0, dynamic_e0, e1, dynamic_p_t1, e0, ref_e1, toi));
  EXPECT_EQ(toi, expected);
}

TEST(IpcPlanar, LengthsThatDoNotFitAreRefusedAtRunTime) {
  const VectorXd planar = Vector2d(0.5, 1), spatial_point = Vec3(0.5, 1, 0), four = Eigen::Vector4d(0.5, 1, 0, 0);
  const VectorXd one = VectorXd::Constant(1, 0.5), empty;
  double toi = -1;
  const std::string point_edge_name = "batchccd::ipc::point_edge_ccd";
  const std::string point_point_name = "batchccd::ipc::point_point_ccd";
  expect_refused([&] { ipc::point_edge_ccd(four, four, four, four, four, four, toi); }, point_edge_name, "p_t0");
  expect_refused([&] { ipc::point_edge_ccd(one, one, one, one, one, one, toi); }, point_edge_name, "p_t0");
  expect_refused([&] { ipc::point_edge_ccd(empty, empty, empty, empty, empty, empty, toi); }, point_edge_name,
                 "p_t0");
  expect_refused([&] { ipc::point_edge_ccd(planar, planar, planar, planar, planar, four, toi); }, point_edge_name,
                 "e1_t1");
  expect_refused([&] { ipc::point_edge_ccd(planar, planar, spatial_point, planar, planar, planar, toi); },
                 point_edge_name, "e1_t0");
  expect_refused([&] { ipc::point_edge_ccd(spatial_point, planar, spatial_point, spatial_point, spatial_point,
                                           spatial_point, toi); },
                 point_edge_name, "e0_t0");
  // A fixed 2-vector among dynamic 3-vectors.
  expect_refused([&] { ipc::point_point_ccd(spatial_point, spatial_point, Vector2d(0, 0), spatial_point, toi); },
                 point_point_name, "p0_t1");
  expect_refused([&] { ipc::point_point_ccd(four, four, four, four, toi); }, point_point_name, "p0_t0");
  // 3D only: a dynamic 2-vector is refused too.
  expect_refused([&] { ipc::point_triangle_ccd(planar, planar, planar, planar, planar, planar, planar, planar, toi); },
                 "batchccd::ipc::point_triangle_ccd", "p_t0");
  const Vec3 a(0, 0, 0);
  expect_refused([&] { ipc::edge_edge_ccd(a, a, a, a, a, a, a, planar, toi); }, "batchccd::ipc::edge_edge_ccd",
                 "eb1_t1");
  EXPECT_EQ(toi, -1);
}

// ipc-toolkit's rules around its solver.

const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);  // the unit triangle in z = 0

// Point (1/4, 1/4, height) moving by `motion` past the static unit triangle.
bool point_over_triangle(double height, const Vec3& motion, double& toi, double min_distance,
                         double tolerance = ipc::DEFAULT_CCD_TOLERANCE, long max_iterations = -1,
                         double conservative_rescaling = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING) {
  const Vec3 p(0.25, 0.25, height);
  return ipc::point_triangle_ccd(p, kA, kB, kC, p + motion, kA, kB, kC, toi, min_distance, 1.0, tolerance,
                                 max_iterations, conservative_rescaling);
}

// Nothing moves: only the initial distance counts, as there.
TEST(IpcRules, NoMotionIsTheInitialDistanceCheck) {
  double toi = -1;
  EXPECT_TRUE(point_over_triangle(0, Vec3::Zero(), toi, 0));  // lying on the triangle
  EXPECT_EQ(toi, 0.0);
  toi = -1;
  EXPECT_TRUE(point_over_triangle(0.25, Vec3::Zero(), toi, 0.25));
  EXPECT_EQ(toi, 0.0);
  toi = -1;
  EXPECT_FALSE(point_over_triangle(0.25, Vec3::Zero(), toi, 0.125));
  EXPECT_EQ(toi, -1);
  // A point on a static edge in the plane, and a point on a point.
  const Vector2d p(0.5, 0), e0(0, 0), e1(1, 0);
  EXPECT_TRUE(ipc::point_edge_ccd(p, e0, e1, p, e0, e1, toi));
  EXPECT_EQ(toi, 0.0);
  toi = -1;
  EXPECT_TRUE(ipc::point_point_ccd(p, p, p, p, toi));
  EXPECT_EQ(toi, 0.0);
  toi = -1;
  EXPECT_FALSE(ipc::point_point_ccd(p, e0, p, e0, toi, 0.25));
  EXPECT_EQ(toi, -1);
}

// The first ask keeps (1 - s)(d0 - min_distance), at most 1e-4, of the gap
// above min_distance free. Falling straight at the triangle at speed 2^-10,
// the distance is d0 - 2^-10 t, so it reaches a separation m at
// (d0 - m) 2^10. With d0 = 2^-11, min_distance = 3 2^-13 and s = 3/4 (all
// exact in binary) the separation is min_distance + 2^-15 (d0 alone in
// place of the gap would give min_distance + 1e-4: toi 0.0225).
TEST(IpcRules, EffectiveSeparationIsAFractionOfTheGap) {
  const double initial_distance = 0x1p-11, min_distance = 3 * 0x1p-13, speed = 0x1p-10, rescaling = 0.75;
  const double separation = min_distance + std::min((1 - rescaling) * (initial_distance - min_distance), 1e-4);
  ASSERT_EQ(separation, min_distance + 0x1p-15);
  const double exact_toi = (initial_distance - separation) / speed;  // 0.09375, above the retry's 1e-6
  const double tolerance = 0x1p-40;  // the distance tolerance, 2^-30 of the step at this speed
  double toi = -1;
  ASSERT_TRUE(point_over_triangle(initial_distance, Vec3(0, 0, -speed), toi, min_distance, tolerance,
                                  ipc::DEFAULT_CCD_MAX_ITERATIONS, rescaling));
  EXPECT_LE(toi, exact_toi);
  EXPECT_GE(toi, exact_toi - 1e-7 - tolerance / speed);
}

// A first toi below 1e-6 is asked again with min_distance itself, and
// scaled by s. The first contact here comes 2^-25 into the step (the point
// moving mostly along the triangle), inside the solver's first time
// interval 1e-7 wide: its lower bound would be 0, a step a line search
// cannot take. Resolved finely, the toi is positive and at least s times
// the time the distance halves (d0 / 2 is the distance tolerance here), 36
// times what the speed alone gives (the last resort).
TEST(IpcRules, SmallToiIsResolvedNotZero) {
  const double contact_time = 0x1p-25, normal_speed = 0x1p-7;
  const Vec3 motion(0.25, 0.125, -normal_speed);
  double toi = -1;
  ASSERT_TRUE(point_over_triangle(normal_speed * contact_time, motion, toi, 0));
  EXPECT_GT(toi, 0.0);
  EXPECT_LE(toi, 0.8 * contact_time);
  EXPECT_GE(toi, 0.8 * (0.5 * contact_time - 0x1p-45));
}

// Even 2^-45 of the step cannot tell a contact 2^-50 in from t = 0: the toi
// is then s (d0 - min_distance) / (2 v), v the largest displacement (here 1).
TEST(IpcRules, SmallToiBelowTheFinestResolutionIsBoundedBySpeed) {
  for (const double min_distance : {0.0, 0.5}) {
    const double gap = 0x1p-50;
    double toi = -1;
    ASSERT_TRUE(point_over_triangle(min_distance + gap, Vec3(0, 0, -1), toi, min_distance));
    EXPECT_GT(toi, 0.0);
    EXPECT_EQ(toi, 0.8 * gap / 2);
  }
}

// The retry has no iteration limit, as there. Edge a, still, ends short of
// x = 1/2; edge b turns about its middle above x = 1/2, closest to a's end
// at t = 0 and 1 (sqrt(3/4^2 + 1.625^2 / 2) 2^-7 apart), with a separation
// 1e-7 of that below it: a miss only a long search proves, neither the
// lines' distance nor a fixed direction. With max_iterations 0 the first
// ask gives up at once (below the small toi) and would report a contact
// there; the retry, unlimited, proves the miss. Passing max_iterations to
// the retry turns this into a contact.
TEST(IpcRules, SmallToiRetryHasNoIterationLimit) {
  const double height = 0x1p-7 * 1.625, gap = 0x1p-7 * 0.75, end = 0.5 - gap;
  const Vec3 a0(0, 0, 0), a1(end, 0, 0);
  const double closest = std::sqrt(gap * gap + height * height / 2), min_distance = closest * (1 - 1e-7);
  double toi = -1;
  EXPECT_FALSE(ipc::edge_edge_ccd(a0, a1, Vec3(0.5, -1, 1 + height), Vec3(0.5, 1, -1 + height), a0, a1,
                                  Vec3(0.5, -1, -1 + height), Vec3(0.5, 1, 1 + height), toi, min_distance, 1.0,
                                  ipc::DEFAULT_CCD_TOLERANCE, /*max_iterations=*/0));
  EXPECT_EQ(toi, -1);
}

// NarrowPhase: TightInclusionCCD's settings, forwarded to the calls.

// It takes the points each free function takes.
template <class P, class Q = P>
concept NarrowPhasePointEdgeTakes = requires(const ipc::NarrowPhase& narrow_phase, const P& p, const Q& q,
                                             double& toi) { narrow_phase.point_edge_ccd(p, q, q, p, q, q, toi); };
template <class P, class Q = P>
concept NarrowPhasePointTriangleTakes =
    requires(const ipc::NarrowPhase& narrow_phase, const P& p, const Q& q, double& toi) {
      narrow_phase.point_triangle_ccd(p, q, q, q, p, q, q, q, toi);
    };
static_assert(NarrowPhasePointEdgeTakes<Vector2d> && NarrowPhasePointEdgeTakes<Vec3> &&
              NarrowPhasePointEdgeTakes<RefXd> && !NarrowPhasePointEdgeTakes<Vector2d, Vec3>);
static_assert(NarrowPhasePointTriangleTakes<Vec3> && NarrowPhasePointTriangleTakes<MapXd> &&
              !NarrowPhasePointTriangleTakes<Vector2d>);
// A value to copy into an adapter, with no virtual calls of its own.
static_assert(!std::is_polymorphic_v<ipc::NarrowPhase> && std::is_trivially_copyable_v<ipc::NarrowPhase>);

TEST(IpcNarrowPhase, DefaultsAreIpcToolkits) {
  const ipc::NarrowPhase narrow_phase;
  EXPECT_EQ(narrow_phase.tolerance, 1e-6);
  EXPECT_EQ(narrow_phase.max_iterations, 10'000'000L);
  EXPECT_EQ(narrow_phase.conservative_rescaling, 0.8);
  const ipc::NarrowPhase custom(1e-3, 100, 0.5);
  EXPECT_EQ(custom.tolerance, 1e-3);
  EXPECT_EQ(custom.max_iterations, 100);
  EXPECT_EQ(custom.conservative_rescaling, 0.5);
}

// Each call of `narrow_phase` refuses its `member`: the call forwards it.
void expect_each_call_refuses(const ipc::NarrowPhase& narrow_phase, const std::string& member) {
  const Vector2d p(0.5, 1), e0(0, 0), e1(1, 0);
  double toi = -1;
  expect_refused([&] { narrow_phase.point_point_ccd(p, e0, p, e0, toi); }, "batchccd::ipc::point_point_ccd", member);
  expect_refused([&] { narrow_phase.point_edge_ccd(p, e0, e1, p, e0, e1, toi); }, "batchccd::ipc::point_edge_ccd",
                 member);
  expect_refused([&] { narrow_phase.edge_edge_ccd(kA, kB, kA, kC, kA, kB, kA, kC, toi); },
                 "batchccd::ipc::edge_edge_ccd", member);
  expect_refused([&] { narrow_phase.point_triangle_ccd(kA, kA, kB, kC, kA, kA, kB, kC, toi); },
                 "batchccd::ipc::point_triangle_ccd", member);
  EXPECT_EQ(toi, -1);
}

// The constructor refuses what the calls would, naming the member; a member
// changed afterwards is refused by each call.
TEST(IpcNarrowPhase, RefusesWhatTheCallsRefuse) {
  const std::string constructor = "batchccd::ipc::NarrowPhase";
  const double infinity = std::numeric_limits<double>::infinity();
  for (const double tolerance : {0.0, -1e-6, kNaN, infinity})
    expect_refused([&] { ipc::NarrowPhase{tolerance}; }, constructor, "tolerance");
  for (const double rescaling : {0.0, -0.5, 1.5, kNaN})
    expect_refused([&] { ipc::NarrowPhase(ipc::DEFAULT_CCD_TOLERANCE, ipc::DEFAULT_CCD_MAX_ITERATIONS, rescaling); },
                   constructor, "conservative_rescaling");
  try {
    ipc::NarrowPhase(1e-3, 100, 2.5);
    ADD_FAILURE() << "accepted conservative_rescaling 2.5";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "batchccd::ipc::NarrowPhase: conservative_rescaling must be in (0, 1], got 2.5");
  }
  EXPECT_NO_THROW(ipc::NarrowPhase(1e-3, -1, 1.0));  // no iteration limit, no rescaling

  ipc::NarrowPhase narrow_phase;
  narrow_phase.conservative_rescaling = 0;
  expect_each_call_refuses(narrow_phase, "conservative_rescaling");
  narrow_phase.conservative_rescaling = 0.8;
  narrow_phase.tolerance = -1;
  expect_each_call_refuses(narrow_phase, "tolerance");
}

// ipc-toolkit's base class, declared here from its documented interface
// (batchccd does not depend on ipc-toolkit): four const virtual calls, toi
// out, min_distance and tmax defaulted. `Planar` is how the point-point and
// point-edge calls take a point (2D or 3D), `Spatial` how the 3D calls do.
namespace ipc_stand_in {

using VectorMax3d = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 3, 1>;

template <class Planar, class Spatial>
class NarrowPhaseCCD {
 public:
  using PlanarPoint = Planar;
  using SpatialPoint = Spatial;

  virtual ~NarrowPhaseCCD() = default;

  virtual bool point_point_ccd(Planar p0_t0, Planar p1_t0, Planar p0_t1, Planar p1_t1, double& toi,
                               const double min_distance = 0.0, const double tmax = 1.0) const = 0;
  virtual bool point_edge_ccd(Planar p_t0, Planar e0_t0, Planar e1_t0, Planar p_t1, Planar e0_t1, Planar e1_t1,
                              double& toi, const double min_distance = 0.0, const double tmax = 1.0) const = 0;
  virtual bool edge_edge_ccd(Spatial ea0_t0, Spatial ea1_t0, Spatial eb0_t0, Spatial eb1_t0, Spatial ea0_t1,
                             Spatial ea1_t1, Spatial eb0_t1, Spatial eb1_t1, double& toi,
                             const double min_distance = 0.0, const double tmax = 1.0) const = 0;
  virtual bool point_triangle_ccd(Spatial p_t0, Spatial t0_t0, Spatial t1_t0, Spatial t2_t0, Spatial p_t1,
                                  Spatial t0_t1, Spatial t1_t1, Spatial t2_t1, double& toi,
                                  const double min_distance = 0.0, const double tmax = 1.0) const = 0;
};

// 1.3 takes const references to the vectors; 1.4 on, const Eigen::Refs.
using Version13 = NarrowPhaseCCD<const VectorMax3d&, const Eigen::Vector3d&>;
using Version14 = NarrowPhaseCCD<const Eigen::Ref<const VectorMax3d>&, const Eigen::Ref<const Eigen::Vector3d>&>;

}  // namespace ipc_stand_in

using ipc_stand_in::VectorMax3d;

// The adapter ipc.hpp shows, with the base's parameter types.
template <class Base>
class BatchccdCCD : public Base {
  using Planar = typename Base::PlanarPoint;
  using Spatial = typename Base::SpatialPoint;

 public:
  explicit BatchccdCCD(const ipc::NarrowPhase& settings = ipc::NarrowPhase()) : narrow_phase(settings) {}

  bool point_point_ccd(Planar p0_t0, Planar p1_t0, Planar p0_t1, Planar p1_t1, double& toi,
                       const double min_distance = 0.0, const double tmax = 1.0) const override {
    return narrow_phase.point_point_ccd(p0_t0, p1_t0, p0_t1, p1_t1, toi, min_distance, tmax);
  }
  bool point_edge_ccd(Planar p_t0, Planar e0_t0, Planar e1_t0, Planar p_t1, Planar e0_t1, Planar e1_t1, double& toi,
                      const double min_distance = 0.0, const double tmax = 1.0) const override {
    return narrow_phase.point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, toi, min_distance, tmax);
  }
  bool edge_edge_ccd(Spatial ea0_t0, Spatial ea1_t0, Spatial eb0_t0, Spatial eb1_t0, Spatial ea0_t1, Spatial ea1_t1,
                     Spatial eb0_t1, Spatial eb1_t1, double& toi, const double min_distance = 0.0,
                     const double tmax = 1.0) const override {
    return narrow_phase.edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1, toi,
                                      min_distance, tmax);
  }
  bool point_triangle_ccd(Spatial p_t0, Spatial t0_t0, Spatial t1_t0, Spatial t2_t0, Spatial p_t1, Spatial t0_t1,
                          Spatial t1_t1, Spatial t2_t1, double& toi, const double min_distance = 0.0,
                          const double tmax = 1.0) const override {
    return narrow_phase.point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, toi, min_distance,
                                           tmax);
  }

  ipc::NarrowPhase narrow_phase;
};

// One question, the points as ipc-toolkit hands them over.
struct NarrowPhaseCase {
  const char* name;
  batchccd::Kind kind;
  std::vector<VectorMax3d> points;  // t0 then t1, in the call's order
  double min_distance = 0;
  double tmax = 1;
  bool hit = true;              // what every setting answers (misses: given iterations)
  double contact_time = 1;      // a hit's toi is no later
  const char* shows = nullptr;  // the member whose change changes the answer
};

VectorMax3d at(double x, double y) { return Vector2d(x, y); }
VectorMax3d at(double x, double y, double z) { return Vec3(x, y, z); }

// For each kind: hits, misses, 2D points for the point calls, min_distance,
// tmax, and a case where each member of NarrowPhase changes the answer (the
// "close" ones start 2^-14 apart, where the rescaling sets the separation;
// the others were found on a grid of quarters). No case of point_point_ccd
// depends on the tolerance (none found); RefusesWhatTheCallsRefuse shows
// that one forwarded.
std::vector<NarrowPhaseCase> narrow_phase_cases() {
  using batchccd::Kind;
  const VectorMax3d o = at(0, 0, 0), b = at(1, 0, 0), c = at(0, 1, 0), o2 = at(0, 0), b2 = at(1, 0);
  const double close = 0x1p-14;
  return {
      {.name = "point-point 3D", .kind = Kind::vertex_vertex, .points = {at(0, 0, 1), o, at(0, 0, -1), o},
       .contact_time = 0.5},
      {.name = "point-point 2D", .kind = Kind::vertex_vertex, .points = {at(0, 1), o2, at(0, -1), o2},
       .contact_time = 0.5},
      {.name = "point-point 2D miss", .kind = Kind::vertex_vertex, .points = {at(1, 1), o2, at(1, -1), o2},
       .min_distance = 0.5, .hit = false},
      {.name = "point-point close", .kind = Kind::vertex_vertex, .points = {at(0, 0, close), o, at(0, 0, -close), o},
       .contact_time = 0.5, .shows = "conservative_rescaling"},
      // Point kinds are decided by their vertex-segment search, bounded on
      // its own: max_iterations (the box budget) shows on the other kinds.
      {.name = "point-point near", .kind = Kind::vertex_vertex,
       .points = {at(-0.25, 0, 0), at(-0.75, -0.25, -0.25), at(-0.75, -0.25, -0.5), at(-0.75, -0.25, -0.25)},
       .min_distance = 0.25},
      {.name = "point-edge 2D", .kind = Kind::vertex_edge, .points = {at(0.5, 1), o2, b2, at(0.5, -1), o2, b2},
       .contact_time = 0.5},
      {.name = "point-edge 2D with min_distance", .kind = Kind::vertex_edge,
       .points = {at(0.5, 1), o2, b2, at(0.5, -1), o2, b2}, .min_distance = 0.25, .contact_time = 0.375},
      {.name = "point-edge 2D miss", .kind = Kind::vertex_edge, .points = {at(2, 1), o2, b2, at(2, -1), o2, b2},
       .min_distance = 0.5, .hit = false},
      {.name = "point-edge 2D close", .kind = Kind::vertex_edge,
       .points = {at(0.5, close), o2, b2, at(0.5, -close), o2, b2}, .contact_time = 0.5,
       .shows = "conservative_rescaling"},
      {.name = "point-edge 2D crossing", .kind = Kind::vertex_edge,
       .points = {at(0, 0), at(-0.5, 1), at(-0.75, 0.25), at(-0.75, 1), at(-0.5, 1), at(-0.75, 0.25)}},
      {.name = "point-edge 2D tolerance", .kind = Kind::vertex_edge,
       .points = {at(0.25, -0.5), at(0.75, 0.75), at(0.5, 0), at(0.25, 0.5), at(0.75, 0.75), at(0.5, 0)},
       .min_distance = 0.25},
      {.name = "point-edge 3D", .kind = Kind::vertex_edge, .points = {at(0.5, 0, 1), o, b, at(0.5, 0, -1), o, b},
       .contact_time = 0.5},
      {.name = "point-edge 3D tolerance", .kind = Kind::vertex_edge,
       .points = {at(0, 0, -0.25), at(0.25, 1, -0.75), at(-0.5, 0.5, -0.5), at(-0.75, 0.75, -0.25),
                  at(0.25, 1, -0.75), at(-0.5, 0.5, -0.5)},
       .min_distance = 0.25},
      {.name = "edge-edge", .kind = Kind::edge_edge,
       .points = {at(0, -1, 1), at(0, 1, 1), at(-1, 0, 0), b, at(0, -1, -1), at(0, 1, -1), at(-1, 0, 0), b},
       .contact_time = 0.5},
      {.name = "edge-edge with min_distance", .kind = Kind::edge_edge,
       .points = {at(0, -1, 1), at(0, 1, 1), at(-1, 0, 0), b, at(0, -1, -1), at(0, 1, -1), at(-1, 0, 0), b},
       .min_distance = 0.25, .contact_time = 0.375},
      {.name = "edge-edge miss", .kind = Kind::edge_edge,
       .points = {at(3, -1, 1), at(3, 1, 1), at(-1, 0, 0), b, at(3, -1, -1), at(3, 1, -1), at(-1, 0, 0), b},
       .hit = false},
      {.name = "edge-edge close", .kind = Kind::edge_edge,
       .points = {at(0, -1, close), at(0, 1, close), at(-1, 0, 0), b, at(0, -1, -close), at(0, 1, -close),
                  at(-1, 0, 0), b},
       .contact_time = 0.5, .shows = "conservative_rescaling"},
      {.name = "edge-edge after tmax", .kind = Kind::edge_edge,
       .points = {at(0, -1, 1), at(0, 1, 1), at(-1, 0, 0), b, at(0, -1, -1), at(0, 1, -1), at(-1, 0, 0), b},
       .tmax = 0.25, .hit = false},
      {.name = "edge-edge tolerance", .kind = Kind::edge_edge,
       .points = {at(0.25, 1, 0.25), at(0, -0.5, -0.25), at(0.5, -0.25, -0.25), at(1, -1, 0), at(0.75, 1.5, 0.5),
                  at(0.5, 0, 0), at(0.5, -0.25, -0.25), at(1, -1, 0)},
       .min_distance = 0.25},
      {.name = "point-triangle", .kind = Kind::vertex_face,
       .points = {at(0.25, 0.25, 1), o, b, c, at(0.25, 0.25, -1), o, b, c}, .contact_time = 0.5},
      {.name = "point-triangle miss", .kind = Kind::vertex_face,
       .points = {at(2, 2, 1), o, b, c, at(2, 2, -1), o, b, c}, .hit = false},
      {.name = "point-triangle static, touching", .kind = Kind::vertex_face,
       .points = {at(0.25, 0.25, 0), o, b, c, at(0.25, 0.25, 0), o, b, c}, .contact_time = 0},
      {.name = "point-triangle with min_distance", .kind = Kind::vertex_face,
       .points = {at(0.25, 0.25, 1), o, b, c, at(0.25, 0.25, -1), o, b, c}, .min_distance = 0.25,
       .contact_time = 0.375},
      {.name = "point-triangle after tmax", .kind = Kind::vertex_face,
       .points = {at(0.25, 0.25, 1), o, b, c, at(0.25, 0.25, -1), o, b, c}, .tmax = 0.25, .hit = false},
      // A miss that conservative advancement leaves to the box search (a
      // miss after tmax it settles alone, without a box).
      {.name = "point-triangle miss needing boxes", .kind = Kind::vertex_face,
       .points = {at(0.375, 0.875, 0), at(-0.875, 0.875, -1), at(-0.625, 0.75, -1), at(0.875, 0.625, 0.125),
                  at(1, 0.125, 0.625), at(0.625, 0.5, 0.625), at(-0.75, 0.375, 0.625), at(0.125, -0.125, -0.125)},
       .min_distance = 0.25, .hit = false, .shows = "max_iterations"},
      {.name = "point-triangle before tmax", .kind = Kind::vertex_face,
       .points = {at(0.25, 0.25, 1), o, b, c, at(0.25, 0.25, -1), o, b, c}, .tmax = 0.75, .contact_time = 0.5},
      {.name = "point-triangle close", .kind = Kind::vertex_face,
       .points = {at(0.25, 0.25, close), o, b, c, at(0.25, 0.25, -close), o, b, c}, .contact_time = 0.5,
       .shows = "conservative_rescaling"},
      {.name = "point-triangle tolerance", .kind = Kind::vertex_face,
       .points = {at(0.25, -0.25, 0), at(-0.25, 0, 0), at(1, 0.75, 0.25), at(0.5, 0.25, -0.25), at(-0.5, -0.25, 0),
                  at(-0.25, 0, 0), at(1, 0.75, 0.25), at(0.5, 0.25, -0.25)},
       .min_distance = 0.25},
  };
}

struct NarrowPhaseAnswer {
  bool hit;
  double toi;
  bool operator==(const NarrowPhaseAnswer&) const = default;
};

constexpr double kUntouched = -1;

template <class Base>
NarrowPhaseAnswer ask_through(const Base& ccd, const NarrowPhaseCase& q) {
  using batchccd::Kind;
  const std::vector<VectorMax3d>& x = q.points;
  std::array<Eigen::Vector3d, 8> s;  // the 3D calls' points
  if (q.kind == Kind::edge_edge || q.kind == Kind::vertex_face)
    for (int k = 0; k < 8; ++k) s[k] = x[k];
  double toi = kUntouched;
  bool hit = false;
  switch (q.kind) {
    case Kind::vertex_vertex:
      hit = ccd.point_point_ccd(x[0], x[1], x[2], x[3], toi, q.min_distance, q.tmax);
      break;
    case Kind::vertex_edge:
      hit = ccd.point_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], toi, q.min_distance, q.tmax);
      break;
    case Kind::edge_edge:
      hit = ccd.edge_edge_ccd(s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], toi, q.min_distance, q.tmax);
      break;
    case Kind::vertex_face:
      hit = ccd.point_triangle_ccd(s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], toi, q.min_distance, q.tmax);
      break;
  }
  return {hit, toi};
}

// The free functions given the settings: what the class must answer.
NarrowPhaseAnswer ask_free_functions(const ipc::NarrowPhase& settings, const NarrowPhaseCase& q) {
  using batchccd::Kind;
  const std::vector<VectorMax3d>& x = q.points;
  const double tolerance = settings.tolerance, rescaling = settings.conservative_rescaling;
  const long iterations = settings.max_iterations;
  double toi = kUntouched;
  bool hit = false;
  switch (q.kind) {
    case Kind::vertex_vertex:
      hit = ipc::point_point_ccd(x[0], x[1], x[2], x[3], toi, q.min_distance, q.tmax, tolerance, iterations,
                                 rescaling);
      break;
    case Kind::vertex_edge:
      hit = ipc::point_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], toi, q.min_distance, q.tmax, tolerance,
                                iterations, rescaling);
      break;
    case Kind::edge_edge:
      hit = ipc::edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, q.min_distance, q.tmax,
                               tolerance, iterations, rescaling);
      break;
    case Kind::vertex_face:
      hit = ipc::point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, q.min_distance, q.tmax,
                                    tolerance, iterations, rescaling);
      break;
  }
  return {hit, toi};
}

struct NamedSettings {
  const char* changed;  // the member that differs from the defaults
  ipc::NarrowPhase settings;
};

// Through a `const NarrowPhaseCCD&`, the adapter answers as the free
// functions given its settings: the defaults, and each member changed alone,
// which changes the answers of the cases that show it (so a call that does
// not forward a member fails). The tolerance shows in none: it only permits
// false positives, and at the separations these calls always ask for, near
// misses are proven misses whatever it is (IpcNarrowPhase.RefusesWhatTheCallsRefuse
// shows every call reads it).
template <class Base>
void expect_adapter_answers_as_free_functions() {
  const std::vector<NarrowPhaseCase> cases = narrow_phase_cases();
  const ipc::NarrowPhase defaults;
  const NamedSettings variants[] = {
      {"none", defaults},
      {"tolerance", ipc::NarrowPhase(0.05)},
      {"max_iterations", ipc::NarrowPhase(ipc::DEFAULT_CCD_TOLERANCE, 0)},
      {"conservative_rescaling",
       ipc::NarrowPhase(ipc::DEFAULT_CCD_TOLERANCE, ipc::DEFAULT_CCD_MAX_ITERATIONS, 0.5)},
  };
  for (const NamedSettings& variant : variants) {
    SCOPED_TRACE(std::string("changed: ") + variant.changed);
    const BatchccdCCD<Base> adapter(variant.settings);
    const Base& ccd = adapter;
    for (const NarrowPhaseCase& q : cases) {
      SCOPED_TRACE(q.name);
      const NarrowPhaseAnswer answer = ask_through(ccd, q), expected = ask_free_functions(variant.settings, q);
      EXPECT_EQ(answer.hit, expected.hit);
      EXPECT_EQ(answer.toi, expected.toi);
      // A search out of iterations reports a contact: misses hold with a budget.
      if (q.hit || variant.settings.max_iterations != 0) {
        EXPECT_EQ(answer.hit, q.hit);
      }
      if (answer.hit) {
        EXPECT_GE(answer.toi, 0.0);
        EXPECT_LE(answer.toi, q.contact_time);
      } else {
        EXPECT_EQ(answer.toi, kUntouched);
      }
      if (q.shows != nullptr && std::string(q.shows) == variant.changed) {
        EXPECT_FALSE(answer == ask_free_functions(defaults, q)) << "the change shows nowhere else";
      }
    }
  }

  // ipc-toolkit's defaults for min_distance and tmax, through the base.
  const BatchccdCCD<Base> adapter;
  const Base& ccd = adapter;
  const Eigen::Vector3d p_t0(0.25, 0.25, 1), p_t1(0.25, 0.25, -1);
  double toi = kUntouched, expected_toi = kUntouched;
  EXPECT_TRUE(ccd.point_triangle_ccd(p_t0, kA, kB, kC, p_t1, kA, kB, kC, toi));
  EXPECT_TRUE(ipc::point_triangle_ccd(p_t0, kA, kB, kC, p_t1, kA, kB, kC, expected_toi));
  EXPECT_EQ(toi, expected_toi);
}

TEST(IpcNarrowPhase, AdapterToIpcToolkit13AnswersAsTheFreeFunctions) {
  expect_adapter_answers_as_free_functions<ipc_stand_in::Version13>();
}

TEST(IpcNarrowPhase, AdapterToIpcToolkit14AnswersAsTheFreeFunctions) {
  expect_adapter_answers_as_free_functions<ipc_stand_in::Version14>();
}

// Cases from ipc-toolkit's own CCD tests (the facts, written anew).

// Two points crossing diagonally meet at t = 1/2, in 2D and in 3D, at every
// separation its tests use: a hit no later than 1/2.
TEST(IpcToolkitCases, PointsMeetAtOneHalfIn2DAnd3D) {
  const Eigen::Vector3d p0_t0(0, 0, 0), p0_t1(1, 1, 1), p1_t0(1, 1, 0), p1_t1(0, 0, 1);
  for (const int dim : {2, 3})
    for (const double min_distance : {0.0, 1e-6, 1e-4, 1e-2}) {
      const Eigen::VectorXd a0 = p0_t0.head(dim), a1 = p0_t1.head(dim), b0 = p1_t0.head(dim), b1 = p1_t1.head(dim);
      double toi = 2;
      ASSERT_TRUE(ipc::point_point_ccd(a0, b0, a1, b1, toi, min_distance)) << dim << "D, " << min_distance;
      EXPECT_LE(toi, 0.5);
      EXPECT_GT(toi, 0.5 * ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING - 1e-9);
    }
}

// A 2D edge that shrinks through a single point before the point reaches
// it: the edge (-1 + 4t .. 1 - 4t on the x axis) is a point at t = 1/4, the
// point (0, 1 - 2t) crosses the axis at t = 1/2, inside the edge again (then
// [-1, 1] reversed): the contact is at 1/2, not at the degenerate moment.
TEST(IpcToolkitCases, EdgeDegeneratingBeforeTheImpact) {
  const Eigen::Vector2d p_t0(0, 1), p_t1(0, -1), e0_t0(-1, 0), e0_t1(3, 0), e1_t0(1, 0), e1_t1(-3, 0);
  double toi = 2;
  ASSERT_TRUE(ipc::point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, toi));
  EXPECT_LE(toi, 0.5);
  EXPECT_GT(toi, 0.5 - 1e-4);  // the effective separation (1e-4) kept free at speed 2, and tolerance
  // Stopping at 0.4, the point never reaches the edge.
  EXPECT_FALSE(ipc::point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, toi, 0.0, 0.4));
}

}  // namespace

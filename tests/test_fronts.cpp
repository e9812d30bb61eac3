// The calls shaped like ipc-toolkit's (ipc.hpp) and Tight Inclusion's
// (tight_inclusion.hpp): the same arguments in the same order, the same
// meaning; and which points the per-kind calls (ccd.hpp) take. Coordinates
// are exact in binary, so contact times are exact.
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batchccd/batchccd.hpp"
#include "expect_refused.hpp"

namespace {

using batchccd::Vec3;
using Points = std::array<Vec3, 8>;  // four at t0, then the same four at t1

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A box budget the search below runs out of before it settles its query.
constexpr long kExhaustingIterations = 16;

// Vertex (1/4, 1/4) falls from z = 1 to z = -1 through the static unit
// triangle in z = 0: at height h at t = (1 - h) / 2.
Points falling_vertex(double scale = 1.0) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Points x = {Vec3(0.25, 0.25, 1), a, b, c, Vec3(0.25, 0.25, -1), a, b, c};
  for (Vec3& point : x) point *= scale;
  return x;
}

// Edge a along x falls from z = 1 to z = -1 across the static edge b along y.
Points crossing_edges() {
  const Vec3 b0(0, -1, 0), b1(0, 1, 0);
  return {Vec3(-1, 0, 1), Vec3(1, 0, 1), b0, b1, Vec3(-1, 0, -1), Vec3(1, 0, -1), b0, b1};
}

// Edge a on the x axis, still, ending a little short of x = 1/2; edge b
// turns about its middle, held 1.625 2^-7 above the axis at x = 1/2. b's
// line comes within 1.625 2^-7 / sqrt(2) of a's line, below the
// separation 1e-2, but beyond a's end: the edges keep sqrt(end gap^2 +
// that^2) = 1.07e-2 apart, their closest at a's end (so neither the
// distance between the lines nor any fixed direction proves it), a miss
// only a long search proves.
Points turning_edge_above() {
  const double height = 0x1p-7 * 1.625, end = 0.5 - 0x1p-7 * 0.75;
  return {Vec3(0, 0, 0),       Vec3(end, 0, 0),         Vec3(0.5, -1, 1 + height), Vec3(0.5, 1, -1 + height),
          Vec3(0, 0, 0),       Vec3(end, 0, 0),         Vec3(0.5, -1, -1 + height), Vec3(0.5, 1, 1 + height)};
}

bool point_triangle(const Points& x, double& toi, double min_distance = 0, double tmax = 1) {
  return batchccd::ipc::point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, min_distance, tmax);
}

// ipc-toolkit's effective separation around Tight Inclusion: the caller's
// plus min(0.2 (d0 - min_distance), 1e-4) with the default rescaling 0.8.
double effective_separation(double initial_distance, double min_distance) {
  return std::min(0.2 * (initial_distance - min_distance), 1e-4) + min_distance;
}

TEST(IpcFront, PointTriangleStopsShortOfTheEffectiveSeparation) {
  for (const double min_distance : {0.0, 0.1}) {
    double toi = -1;
    ASSERT_TRUE(point_triangle(falling_vertex(), toi, min_distance));
    const double expected = (1 - effective_separation(1, min_distance)) / 2;
    EXPECT_LE(toi, expected);
    EXPECT_GE(toi, expected - 1e-6);
  }
}

// A port of ipc's (..., toi, 0.0, tmax) keeps its meaning: min_distance
// then tmax, never tmax = 0.
TEST(IpcFront, ArgumentsInIpcToolkitsOrder) {
  double toi = -1;
  EXPECT_FALSE(point_triangle(falling_vertex(), toi, 0.0, 0.4));
  EXPECT_EQ(toi, -1);  // untouched when false, as there
  EXPECT_TRUE(point_triangle(falling_vertex(), toi, 0.0, 0.6));
  EXPECT_LE(toi, 0.5);
}

TEST(IpcFront, EveryKind) {
  double toi = -1;
  const Points e = crossing_edges();
  ASSERT_TRUE(batchccd::ipc::edge_edge_ccd(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], toi, 0.25));
  EXPECT_NEAR(toi, (1 - effective_separation(1, 0.25)) / 2, 1e-6);
  // A point passing 0.3 above an edge's middle, and another point.
  const Vec3 e0(0, 0, 0), e1(1, 0, 0), p0(0.5, 0.3, -1), p1(0.5, 0.3, 1);
  EXPECT_TRUE(batchccd::ipc::point_edge_ccd(p0, e0, e1, p1, e0, e1, toi, 0.3));
  EXPECT_LE(toi, 0.5);
  EXPECT_FALSE(batchccd::ipc::point_edge_ccd(p0, e0, e1, p1, e0, e1, toi, 0.25));
  EXPECT_TRUE(batchccd::ipc::point_point_ccd(p0, Vec3(0.5, 0, 0), p1, Vec3(0.5, 0, 0), toi, 0.3));
  EXPECT_FALSE(batchccd::ipc::point_point_ccd(p0, Vec3(0.5, 0, 0), p1, Vec3(0.5, 0, 0), toi, 0.29));
}

TEST(IpcFront, NoMotionAndStartingWithinTheSeparation) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), p(0.25, 0.25, 0.05);
  double toi = -1;
  // As ipc-toolkit: nothing moves, so only the initial distance counts.
  EXPECT_FALSE(batchccd::ipc::point_triangle_ccd(p, a, b, c, p, a, b, c, toi, 0.01));
  EXPECT_EQ(toi, -1);
  EXPECT_TRUE(batchccd::ipc::point_triangle_ccd(p, a, b, c, p, a, b, c, toi, 0.1));
  EXPECT_EQ(toi, 0.0);
  toi = -1;
  const Vec3 moved(0.25, 0.25, 0.5);
  EXPECT_TRUE(batchccd::ipc::point_triangle_ccd(p, a, b, c, moved, a, b, c, toi, 0.1));
  EXPECT_EQ(toi, 0.0);
}

TEST(IpcFront, SmallToiIsRescaled) {
  // 1e-6 above the triangle, falling 2 in the step: the effective separation
  // leaves a toi below 1e-6, so the separation alone is asked for and the
  // toi scaled by 0.8.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  double toi = -1;
  ASSERT_TRUE(batchccd::ipc::point_triangle_ccd(Vec3(0.25, 0.25, 1e-6), a, b, c, Vec3(0.25, 0.25, -2 + 1e-6), a, b, c,
                                                toi));
  EXPECT_GT(toi, 0.0);
  EXPECT_LE(toi, 0.8 * 0.5e-6);
  EXPECT_GE(toi, 0.8 * 0.5e-6 * (1 - 1e-6) - 1e-7);
}

TEST(IpcFront, BadArguments) {
  double toi = 0;
  const Points x = falling_vertex();
  for (const double min_distance : {-1.0, kNaN, kInfinity})
    EXPECT_THROW(point_triangle(x, toi, min_distance), std::invalid_argument);
  for (const double tmax : {-0.1, 1.5, kNaN}) EXPECT_THROW(point_triangle(x, toi, 0, tmax), std::invalid_argument);
  EXPECT_THROW(batchccd::ipc::point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, 0, 1, 0.0),
               std::invalid_argument);
  EXPECT_THROW(batchccd::ipc::point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, 0, 1, 1e-6,
                                                 100, 0.0),
               std::invalid_argument);
  Points bad = x;
  bad[5].y() = kNaN;
  EXPECT_TRUE(point_triangle(bad, toi));
  EXPECT_EQ(toi, 0.0);
}

// A search that exhausts max_iterations reports a contact, never a miss;
// -1 (or the default) lets it decide.
TEST(IpcFront, MaxIterationsExhaustedIsAContact) {
  const Points x = turning_edge_above();
  const auto call = [&](long max_iterations, double& toi) {
    return batchccd::ipc::edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, 1e-2, 1.0, 1e-6,
                                        max_iterations);
  };
  double toi = -1;
  EXPECT_FALSE(call(-1, toi));
  EXPECT_FALSE(call(batchccd::ipc::DEFAULT_CCD_MAX_ITERATIONS, toi));
  EXPECT_EQ(toi, -1);
  EXPECT_TRUE(call(kExhaustingIterations, toi));
  EXPECT_GE(toi, 0.0);
  EXPECT_LE(toi, 1.0);
}

TEST(IpcFront, BadToleranceRescalingAndTmaxEnds) {
  const Points x = falling_vertex();
  const auto call = [&](double tolerance, double rescaling, double& toi, double tmax = 1.0) {
    return batchccd::ipc::point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, 0.0, tmax, tolerance,
                                             100, rescaling);
  };
  double toi = -1;
  // Refused naming the argument (not for a consequence of its value further on).
  const auto expect_refused = [&](double tolerance, double rescaling, const std::string& argument) {
    try {
      call(tolerance, rescaling, toi);
      ADD_FAILURE() << argument << " accepted: tolerance " << tolerance << ", rescaling " << rescaling;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(argument), std::string::npos) << error.what();
    }
  };
  for (const double tolerance : {kNaN, kInfinity, -1e-6}) expect_refused(tolerance, 0.8, "tolerance");
  for (const double rescaling : {1.5, 1.0 + 0x1p-52, kNaN, -0.5}) expect_refused(1e-6, rescaling, "conservative_rescaling");
  EXPECT_TRUE(call(1e-6, 1.0, toi));  // the end of the range is a value like any other
  EXPECT_LE(toi, 0.5);
  // tmax = 0: no time to move, so no contact unless already within the separation.
  toi = -1;
  EXPECT_FALSE(call(1e-6, 0.8, toi, 0.0));
  EXPECT_EQ(toi, -1);
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), p(0.25, 0.25, 0.05), below(0.25, 0.25, -1);
  EXPECT_TRUE(batchccd::ipc::point_triangle_ccd(p, a, b, c, below, a, b, c, toi, 0.1, 0.0));
  EXPECT_EQ(toi, 0.0);
}

TEST(TightInclusionFront, SeparationAndStepLimit) {
  const Points x = falling_vertex();
  const batchccd::ticcd::Array3 err(-1, -1, -1);
  double toi = -1, output_tolerance = -1;
  ASSERT_TRUE(batchccd::ticcd::vertexFaceCCD(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], err, 0.1, toi, 1e-6,
                                             1.0, 1'000'000, output_tolerance));
  EXPECT_LE(toi, 0.45);
  EXPECT_GE(toi, 0.45 - 1e-6);
  EXPECT_EQ(output_tolerance, 1e-6);
  EXPECT_FALSE(batchccd::ticcd::vertexFaceCCD(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], err, 0.1, toi, 1e-6,
                                              0.4, 1'000'000, output_tolerance));
  EXPECT_EQ(toi, kInfinity);
  const Points e = crossing_edges();
  ASSERT_TRUE(batchccd::ticcd::edgeEdgeCCD(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], err, 0.0, toi, 1e-6, 1.0,
                                           -1, output_tolerance));
  EXPECT_LE(toi, 0.5);
  EXPECT_GE(toi, 0.5 - 1e-6);
  EXPECT_THROW(batchccd::ticcd::edgeEdgeCCD(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], err, -0.1, toi, 1e-6,
                                            1.0, -1, output_tolerance),
               std::invalid_argument);
}

TEST(TightInclusionFront, MissBadInputAndExhaustedSearch) {
  const batchccd::ticcd::Array3 err(-1, -1, -1);
  double toi = -1, output_tolerance = -1;
  const auto vertex_face = [&](const Points& x, double ms, double tolerance, double t_max, long max_itr) {
    return batchccd::ticcd::vertexFaceCCD(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], err, ms, toi, tolerance,
                                          t_max, max_itr, output_tolerance);
  };
  // A miss: toi = +infinity.
  const Points turning = turning_edge_above();
  const auto edge_edge = [&](long max_itr) {
    return batchccd::ticcd::edgeEdgeCCD(turning[0], turning[1], turning[2], turning[3], turning[4], turning[5],
                                        turning[6], turning[7], err, 1e-2, toi, 1e-6, 1.0, max_itr, output_tolerance);
  };
  EXPECT_FALSE(edge_edge(-1));
  EXPECT_EQ(toi, kInfinity);
  // Out of iterations: a contact, never a miss.
  EXPECT_TRUE(edge_edge(kExhaustingIterations));
  EXPECT_GE(toi, 0.0);
  EXPECT_LE(toi, 1.0);
  // A NaN or infinite coordinate: a contact at 0.
  for (const double bad : {kNaN, kInfinity}) {
    Points x = falling_vertex();
    x[6].z() = bad;
    toi = -1;
    EXPECT_TRUE(vertex_face(x, 0.0, 1e-6, 1.0, -1)) << bad;
    EXPECT_EQ(toi, 0.0) << bad;
  }
  const Points x = falling_vertex();
  for (const double tolerance : {0.0, -1e-6, kNaN, kInfinity})
    EXPECT_THROW(vertex_face(x, 0.0, tolerance, 1.0, -1), std::invalid_argument) << tolerance;
  for (const double t_max : {0.0, -0.5, 1.5, kNaN})
    EXPECT_THROW(vertex_face(x, 0.0, 1e-6, t_max, -1), std::invalid_argument) << t_max;
  for (const double ms : {-1e-3, kNaN, kInfinity})
    EXPECT_THROW(vertex_face(x, ms, 1e-6, 1.0, -1), std::invalid_argument) << ms;
}

// The tolerance is a distance in the caller's units: coordinates, separation
// and tolerance scaled together by a power of two give the same toi.
TEST(TightInclusionFront, ScalesWithTheCoordinates) {
  const batchccd::ticcd::Array3 err(-1, -1, -1);
  double toi = -1, scaled_toi = -2, output_tolerance = 0;
  const Points x = falling_vertex(), big = falling_vertex(0x1p40);
  ASSERT_TRUE(batchccd::ticcd::vertexFaceCCD(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], err, 0.125, toi, 1e-6,
                                             1.0, -1, output_tolerance));
  ASSERT_TRUE(batchccd::ticcd::vertexFaceCCD(big[0], big[1], big[2], big[3], big[4], big[5], big[6], big[7], err,
                                             0.125 * 0x1p40, scaled_toi, 1e-6 * 0x1p40, 1.0, -1, output_tolerance));
  EXPECT_EQ(toi, scaled_toi);
}

// The per-kind calls (ccd.hpp): any Eigen vector of doubles, of the length
// the call takes; never read past its end.

using Eigen::Vector2d;
using Eigen::VectorXd;
using MapXd = Eigen::Map<const VectorXd>;
using RefXd = Eigen::Ref<const VectorXd>;

// Which points each call takes, asked at compile time.
template <class P, class Q = P>
concept VertexFaceTakes = requires(const P& p, const Q& q) { batchccd::vertex_face_ccd(p, q, q, q, p, q, q, q); };
template <class P, class Q = P>
concept EdgeEdgeTakes = requires(const P& p, const Q& q) { batchccd::edge_edge_ccd(p, q, q, q, p, q, q, q); };
template <class P, class Q = P>
concept VertexEdgeTakes = requires(const P& p, const Q& q) { batchccd::vertex_edge_ccd(p, q, q, p, q, q); };
template <class P, class Q = P>
concept VertexVertexTakes = requires(const P& p, const Q& q) { batchccd::vertex_vertex_ccd(p, q, p, q); };

// 3D only; lengths fixed at compile time that do not fit are refused then.
static_assert(VertexFaceTakes<Vec3> && VertexFaceTakes<VectorXd> && VertexFaceTakes<MapXd> &&
              VertexFaceTakes<RefXd> && VertexFaceTakes<Eigen::RowVector3d> && VertexFaceTakes<Vec3, VectorXd>);
static_assert(!VertexFaceTakes<Vector2d> && !VertexFaceTakes<Vec3, Vector2d> && !VertexFaceTakes<Eigen::Vector4d> &&
              !VertexFaceTakes<Eigen::Vector3f> && !VertexFaceTakes<Eigen::Matrix3d>);
static_assert(EdgeEdgeTakes<Vec3> && EdgeEdgeTakes<VectorXd> && EdgeEdgeTakes<MapXd> && EdgeEdgeTakes<Vec3, RefXd>);
static_assert(!EdgeEdgeTakes<Vector2d> && !EdgeEdgeTakes<Vec3, Vector2d> && !EdgeEdgeTakes<VectorXd, Vector2d> &&
              !EdgeEdgeTakes<Eigen::Vector4d>);
// The point calls: 2D or 3D, all of one length.
static_assert(VertexEdgeTakes<Vector2d> && VertexEdgeTakes<Vec3> && VertexEdgeTakes<VectorXd> &&
              VertexEdgeTakes<MapXd> && VertexEdgeTakes<Vector2d, VectorXd> && VertexEdgeTakes<Eigen::RowVector2d>);
static_assert(!VertexEdgeTakes<Vector2d, Vec3> && !VertexEdgeTakes<Vec3, Vector2d> &&
              !VertexEdgeTakes<Eigen::Vector4d> && !VertexEdgeTakes<Eigen::Matrix<double, 1, 1>> &&
              !VertexEdgeTakes<Eigen::Vector2f>);
static_assert(VertexVertexTakes<Vector2d> && VertexVertexTakes<Vec3> && VertexVertexTakes<RefXd> &&
              VertexVertexTakes<Vec3, VectorXd>);
static_assert(!VertexVertexTakes<Vector2d, Vec3> && !VertexVertexTakes<Eigen::Vector4d>);
// Tight Inclusion's names take the same 3D points.
template <class P, class Q = P>
concept TightInclusionTakes = requires(const P& p, const Q& q, double toi, double output) {
  batchccd::ticcd::vertexFaceCCD(p, q, q, q, p, q, q, q, batchccd::ticcd::Array3::Zero(), 0.0, toi, 1e-6, 1.0, 100,
                                 output);
  batchccd::ticcd::edgeEdgeCCD(p, q, q, q, p, q, q, q, batchccd::ticcd::Array3::Zero(), 0.0, toi, 1e-6, 1.0, 100,
                               output);
};
static_assert(TightInclusionTakes<Vec3> && TightInclusionTakes<VectorXd> && TightInclusionTakes<Vec3, MapXd>);
static_assert(!TightInclusionTakes<Vector2d> && !TightInclusionTakes<Vec3, Vector2d> &&
              !TightInclusionTakes<Eigen::Vector4d>);
// Braced lists: three numbers are a point; two are not (a Vec3 would take
// {1, 2} as its sizes and leave its coordinates unset), nor are four.
template <class Number>
concept TakesBracedPairs = requires(Number n) { batchccd::vertex_vertex_ccd({n, n}, {n, n}, {n, n}, {n, n}); };
template <class Number>
concept TakesBracedTriples =
    requires(Number n) { batchccd::vertex_vertex_ccd({n, n, n}, {n, n, n}, {n, n, n}, {n, n, n}); };
template <class Number>
concept TakesBracedQuadruples =
    requires(Number n) { batchccd::vertex_vertex_ccd({n, n, n, n}, {n, n, n, n}, {n, n, n, n}, {n, n, n, n}); };
static_assert(TakesBracedTriples<double> && !TakesBracedPairs<int> && !TakesBracedPairs<double> &&
              !TakesBracedQuadruples<int> && !TakesBracedQuadruples<double>);

// A point kept in a buffer with a NaN right after it: a call that reads past
// the vector's end sees the NaN (status invalid_input, hit, toi 0).
class FencedPoints {
 public:
  template <class Point>
  explicit FencedPoints(const std::vector<Point>& points) {
    for (const Point& point : points) {
      starts_.push_back(storage_.size());
      lengths_.push_back(point.size());
      for (Eigen::Index i = 0; i < point.size(); ++i) storage_.push_back(point[i]);
      storage_.push_back(kNaN);
    }
  }
  MapXd operator[](std::size_t k) const { return MapXd(storage_.data() + starts_[k], lengths_[k]); }

 private:
  std::vector<double> storage_;
  std::vector<std::size_t> starts_;
  std::vector<Eigen::Index> lengths_;
};

void expect_same(const batchccd::QueryResult& result, const batchccd::QueryResult& expected) {
  EXPECT_EQ(result.hit, expected.hit);
  EXPECT_EQ(result.toi, expected.toi);
  EXPECT_EQ(result.status, expected.status);
}

// Vec3, expressions, blocks and braced lists in one call: the same answer.
TEST(PerKindCalls, MixedArguments) {
  const Points x = falling_vertex();
  const batchccd::QueryResult expected = batchccd::vertex_face_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7]);
  ASSERT_TRUE(expected.hit);
  const Vec3 fall(0, 0, -2);
  Eigen::Matrix3d corners;
  corners << 0, 1, 0, 0, 0, 1, 0, 0, 0;  // a, b, c as columns
  const VectorXd dynamic_a = x[1];
  expect_same(batchccd::vertex_face_ccd(x[0], dynamic_a, corners.col(1), {0, 1, 0}, x[0] + fall, x[5],
                                        MapXd(x[6].data(), 3), corners.col(2)),
              expected);
  const Points e = crossing_edges();
  expect_same(batchccd::edge_edge_ccd(e[0], e[1], {0, -1, 0}, e[3], e[0] - 2 * Vec3::UnitZ(), e[5], e[6], e[7]),
              batchccd::edge_edge_ccd(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]));
}

// A 2D point crossing an edge in the plane, and a 2D point passing another:
// the lifted 3D query's answer, through fixed 2-vectors and through dynamic
// ones in fenced buffers.
TEST(PerKindCalls, PlanarPointCallsAreTheLiftedQuery) {
  using batchccd::Kind;
  const std::vector<Vector2d> crossing = {{0.5, 1}, {0, 0}, {1, 0}, {0.5, -1}, {0, 0}, {1, 0}};
  const std::vector<Vector2d> passing = {{2, 1}, {0, 0}, {1, 0}, {2, -1}, {0, 0}, {1, 0}};  // 1 from e1
  for (const std::vector<Vector2d>& x : {crossing, passing})
    for (const double min_distance : {0.0, 0.5, 1.0}) {
      batchccd::Options options;
      options.min_distance = min_distance;
      const batchccd::QueryResult lifted = batchccd::query_ccd(
          Kind::vertex_edge, batchccd::lifted(batchccd::make_query(Kind::vertex_edge, std::span(x).first(3), std::span(x).last(3))),
          options);
      EXPECT_EQ(lifted.status, batchccd::Status::ok);
      const FencedPoints fenced(x);
      expect_same(batchccd::vertex_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], options), lifted);
      expect_same(batchccd::vertex_edge_ccd(fenced[0], fenced[1], fenced[2], fenced[3], fenced[4], fenced[5], options),
                  lifted);
      expect_same(batchccd::vertex_edge_ccd(x[0], fenced[1], x[2], fenced[3], x[4], fenced[5], options), lifted);
    }
  // Touching: the crossing at t = 1/2, the pass (1 from e1) not.
  batchccd::Options options;
  const batchccd::QueryResult crossed =
      batchccd::vertex_edge_ccd(crossing[0], crossing[1], crossing[2], crossing[3], crossing[4], crossing[5], options);
  EXPECT_TRUE(crossed.hit);
  EXPECT_LE(crossed.toi, 0.5);
  EXPECT_GE(crossed.toi, 0.5 - options.toi_tolerance);
  EXPECT_FALSE(
      batchccd::vertex_edge_ccd(passing[0], passing[1], passing[2], passing[3], passing[4], passing[5], options).hit);

  // p passes 0.25 from q.
  const std::vector<Vector2d> points = {{-1, 0}, {0, 0.25}, {1, 0}, {0, 0.25}};
  const FencedPoints fenced(points);
  for (const double min_distance : {0.2, 0.3}) {
    options.min_distance = min_distance;
    const batchccd::QueryResult lifted =
        batchccd::query_ccd(Kind::vertex_vertex,
                            batchccd::lifted(batchccd::make_query(Kind::vertex_vertex, std::span(points).first(2),
                                                                  std::span(points).last(2))),
                            options);
    EXPECT_EQ(lifted.hit, min_distance > 0.25);
    expect_same(batchccd::vertex_vertex_ccd(points[0], points[1], points[2], points[3], options), lifted);
    expect_same(batchccd::vertex_vertex_ccd(fenced[0], fenced[1], fenced[2], fenced[3], options), lifted);
  }
}

// Lengths known only at run time that do not fit: refused, naming the call
// and the first argument that does not fit, before anything is read.
TEST(PerKindCalls, LengthsThatDoNotFitAreRefusedAtRunTime) {
  const FencedPoints fenced(std::vector<VectorXd>{Vector2d(0.5, 1), Vec3(0.5, 1, 0), Eigen::Vector4d(0.5, 1, 0, 0),
                                                  VectorXd::Constant(1, 0.5), VectorXd()});
  const MapXd planar = fenced[0], spatial = fenced[1], four = fenced[2], one = fenced[3], empty = fenced[4];
  const Vec3 a(0, 0, 0);
  // 3D only: a 2-vector through every argument of the 3D calls.
  const std::array<std::string, 8> vertex_face_names = {"p_t0", "a_t0", "b_t0", "c_t0",
                                                        "p_t1", "a_t1", "b_t1", "c_t1"};
  const std::array<std::string, 8> edge_edge_names = {"ea0_t0", "ea1_t0", "eb0_t0", "eb1_t0",
                                                      "ea0_t1", "ea1_t1", "eb0_t1", "eb1_t1"};
  for (std::size_t k = 0; k < 8; ++k) {
    // Argument k planar, the others spatial.
    const auto x = [&](std::size_t i) -> const MapXd& { return i == k ? planar : spatial; };
    expect_refused([&] { batchccd::vertex_face_ccd(x(0), x(1), x(2), x(3), x(4), x(5), x(6), x(7)); },
                   "batchccd::vertex_face_ccd", vertex_face_names[k]);
    expect_refused([&] { batchccd::edge_edge_ccd(x(0), x(1), x(2), x(3), x(4), x(5), x(6), x(7)); },
                   "batchccd::edge_edge_ccd", edge_edge_names[k]);
  }
  expect_refused([&] { batchccd::vertex_face_ccd(a, a, a, a, a, a, a, planar); }, "batchccd::vertex_face_ccd",
                 "c_t1");
  expect_refused([&] { batchccd::edge_edge_ccd(four, a, a, a, a, a, a, a); }, "batchccd::edge_edge_ccd", "ea0_t0");
  // The point calls: 2D or 3D, all like the first.
  const std::array<std::string, 6> vertex_edge_names = {"p_t0", "e0_t0", "e1_t0", "p_t1", "e0_t1", "e1_t1"};
  for (std::size_t k = 1; k < 6; ++k) {
    // Argument k spatial, the others planar like the first.
    const auto x = [&](std::size_t i) -> const MapXd& { return i == k ? spatial : planar; };
    expect_refused([&] { batchccd::vertex_edge_ccd(x(0), x(1), x(2), x(3), x(4), x(5)); },
                   "batchccd::vertex_edge_ccd", vertex_edge_names[k]);
  }
  for (const MapXd& wrong : {four, one, empty}) {
    expect_refused([&] { batchccd::vertex_edge_ccd(wrong, wrong, wrong, wrong, wrong, wrong); },
                   "batchccd::vertex_edge_ccd", "p_t0");
    expect_refused([&] { batchccd::vertex_vertex_ccd(wrong, wrong, wrong, wrong); }, "batchccd::vertex_vertex_ccd",
                   "p_t0");
  }
  expect_refused([&] { batchccd::vertex_vertex_ccd(a, spatial, planar, a); }, "batchccd::vertex_vertex_ccd", "p_t1");
  expect_refused([&] { batchccd::vertex_vertex_ccd(planar, planar, planar, spatial); },
                 "batchccd::vertex_vertex_ccd", "q_t1");
  // Tight Inclusion's names: 3D only, every argument checked.
  const batchccd::ticcd::Array3 err(-1, -1, -1);
  double toi = 0, output = 0;
  expect_refused([&] { batchccd::ticcd::vertexFaceCCD(a, a, a, a, a, a, a, planar, err, 0.0, toi, 1e-6, 1.0, 100, output); },
                 "batchccd::ticcd::vertexFaceCCD", "face_vertex2_end");
  expect_refused([&] { batchccd::ticcd::edgeEdgeCCD(four, a, a, a, a, a, a, a, err, 0.0, toi, 1e-6, 1.0, 100, output); },
                 "batchccd::ticcd::edgeEdgeCCD", "edge0_vertex0_start");
}

}  // namespace

// What the modes promise and the baselines (lab.hpp) do not: the contact
// that moved fast and cubic out of the public modes. A vertex lies inside
// the triangle at t = 0 (barycentric about 0.075 / 0.52 / 0.41), found by an
// adversarial search; the plain-double search and the cubic solver both
// missed it, conservative and exact mode hit it at t = 0.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "exact_distance.hpp"

namespace batchccd {
namespace {

// Every coordinate has a power-of-two denominator: exact as a double.
double ratio(double numerator, double denominator) { return numerator / denominator; }

constexpr double k25 = 33554432;  // 2^25

// The reproducer, row for row as in its 7-column query file (truth 1).
const Query kContactAtZero{{
    Vec3(ratio(34814413, k25), ratio(116885781, k25), ratio(120879811, k25)),  // p at t0
    Vec3(ratio(-2309, 65536), ratio(24939, 8192), ratio(70909, 32768)),        // a
    Vec3(ratio(81853, 32768), ratio(278955, 65536), ratio(365683, 65536)),     // b
    Vec3(ratio(4739, 8192), ratio(154089, 65536), ratio(189013, 65536)),       // c
    Vec3(ratio(-7325235, k25), ratio(208472341, k25), ratio(136182467, k25)),  // p at t1
    Vec3(ratio(11771, 65536), ratio(22667, 8192), ratio(76669, 32768)),
    Vec3(ratio(119741, 32768), ratio(222379, 65536), ratio(419187, 65536)),
    Vec3(ratio(8483, 8192), ratio(127465, 65536), ratio(241749, 65536)),
}};

void expect_contact_at_zero(const QueryResult& r, const std::string& where) {
  EXPECT_EQ(r.status, Status::ok) << where;
  EXPECT_TRUE(r.hit) << where << ": a false negative";
  EXPECT_EQ(r.toi, 0.0) << where << ": the first contact is at t = 0";
}

// The truth, proven in rationals: the vertex touches the triangle at t = 0.
TEST(ContactAtZero, IsAContactInExactArithmetic) {
  EXPECT_EQ(testing::squared_distance_at(Kind::vertex_face, kContactAtZero, 0), 0);
}

TEST(ContactAtZero, EveryModeHitsItAtZeroThroughEveryCall) {
  const auto& x = kContactAtZero.points;
  for (const Mode mode : {Mode::conservative, Mode::exact}) {
    const std::string name = to_string(mode);
    Options options;
    options.mode = mode;
    expect_contact_at_zero(query_ccd(Kind::vertex_face, kContactAtZero, options), name + " query_ccd");
    expect_contact_at_zero(vertex_face_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], options),
                           name + " vertex_face_ccd");
    for (const Isa isa : available_isas()) {
      options.isa = isa;
      const std::string where = name + " " + to_string(isa);
      const BatchResult batch = batch_ccd(Kind::vertex_face, std::vector<Query>{kContactAtZero}, options);
      ASSERT_EQ(batch.results.size(), 1u);
      expect_contact_at_zero(batch.results[0], where + " batch_ccd");
      EXPECT_EQ(batch.earliest_toi, 0.0) << where;
      Eigen::MatrixXd t0(4, 3), t1(4, 3);
      for (Eigen::Index k = 0; k < 4; ++k) {
        t0.row(k) = x[static_cast<std::size_t>(k)];
        t1.row(k) = x[static_cast<std::size_t>(k) + 4];
      }
      const Eigen::MatrixXi faces = (Eigen::MatrixXi(1, 3) << 1, 2, 3).finished();
      Candidates candidates;
      candidates.vertex_face = {{0, 0}};
      const BatchResult mesh = mesh_ccd({t0, t1, faces}, candidates, options);
      ASSERT_EQ(mesh.results.size(), 1u);
      expect_contact_at_zero(mesh.results[0], where + " mesh_ccd");
    }
  }
}

// The baselines promise nothing but a well-formed answer; what they answer
// is printed for the record.
TEST(ContactAtZero, BaselinesAnswerWellFormed) {
  for (const lab::Method& method : {lab::kFast, lab::kCubic}) {
    const QueryResult r = lab::query_ccd(Kind::vertex_face, kContactAtZero, method.applied_to({}), method.settings());
    EXPECT_EQ(r.status, Status::ok) << lab::to_string(method);
    if (r.hit) {
      EXPECT_GE(r.toi, 0.0) << lab::to_string(method);
      EXPECT_LE(r.toi, 1.0) << lab::to_string(method);
    } else {
      EXPECT_EQ(r.toi, std::numeric_limits<double>::infinity()) << lab::to_string(method);
    }
    std::printf("[ record   ] %s baseline: %s (toi %g)\n", lab::to_string(method), r.hit ? "hit" : "miss", r.toi);
  }
}

}  // namespace
}  // namespace batchccd

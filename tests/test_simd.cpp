// The lane kernels against the scalar reference filter, survivor for
// survivor, on every instruction set this processor runs: random,
// adversarial and real queries, raw and from meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <ostream>
#include <random>
#include <tuple>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "simd/filter.hpp"
#include "same_answers.hpp"
#include "shared_data.hpp"

namespace batchccd {
namespace {

std::vector<const simd::FilterKernels*> vector_kernels() {
  std::vector<const simd::FilterKernels*> kernels;
  for (const auto& [name, isa] : isa_names()) {  // x86's sets, NEON: what this build and processor run
    if (isa == Isa::automatic || isa == Isa::scalar) continue;
    try {
      kernels.push_back(&simd::filter_kernels(isa));
    } catch (const std::invalid_argument&) {
      // not on this processor
    }
  }
  return kernels;
}

// What a filter function says of a range: its survivors, the pieces of
// their steps proven free, and how many each filter culled.
struct Filtered {
  std::vector<std::uint32_t> kept;
  std::vector<std::uint8_t> free_pieces;
  std::array<std::size_t, 4> culls;  // sign, separation, pieces, swept boxes
  bool operator==(const Filtered&) const = default;
};

std::ostream& operator<<(std::ostream& out, const Filtered& filtered) {
  out << filtered.kept.size() << " kept, culls " << filtered.culls[0] << " / " << filtered.culls[1] << " / "
      << filtered.culls[2] << " / " << filtered.culls[3] << ", free pieces";
  for (const std::uint8_t free : filtered.free_pieces) out << ' ' << int(free);
  return out;
}

template <class Source>
Filtered survivors(simd::FilterFunction<Source> filter, const Source& source, std::size_t begin, std::size_t end,
                   const reference::FilterSettings& settings) {
  Filtered out{std::vector<std::uint32_t>(end - begin), std::vector<std::uint8_t>(end - begin), {}};
  simd::FilterCounts counts;
  const std::size_t kept = filter(source, begin, end, settings, out.kept.data(), out.free_pieces.data(), counts);
  out.kept.resize(kept);
  out.free_pieces.resize(kept);
  out.culls = {counts.sign, counts.separation, counts.pieces, counts.swept_box};
  return out;
}

// Per-candidate separations of every scale, 0 and subnormal included.
const std::vector<double>& candidate_separations() {
  static const std::vector<double> values = [] {
    std::mt19937_64 random(7);
    std::vector<double> v(1 << 20);  // as many as the largest test source
    for (double& x : v) {
      const int which = static_cast<int>(random() % 4);
      x = which == 0 ? 0.0 : std::ldexp(1.0 + static_cast<double>(random() % 1024) / 1024,
                                        which == 1 ? -1074 + static_cast<int>(random() % 1200) : -static_cast<int>(random() % 12));
    }
    return v;
  }();
  return values;
}

// Certified and plain, each filter alone and both, the sign test with and
// without its V = 2 step, over the whole step or 2, 4 or 8 pieces, with and
// without the swept boxes; and with separations (one for all, of several
// scales, or one per candidate), each filter alone and both, likewise.
std::vector<reference::FilterSettings> all_settings() {
  std::vector<reference::FilterSettings> settings;
  for (bool certified : {true, false}) {
    for (auto [sign, subdivide, separation] :
         {std::tuple{true, true, false}, {true, false, false}, {false, true, true},
          {true, true, true}, {true, false, true}})
      for (auto [pieces, swept_box] : {std::pair{1, false}, {1, true}, {4, true}, {2, false}, {8, false}})
        if (separation || pieces == 1)
          settings.push_back({.certified = certified, .sign = sign, .subdivide = subdivide,
                              .separation = separation, .pieces = pieces, .swept_box = swept_box});
    settings.push_back({.certified = certified, .sign = false, .separation = false, .pieces = 1, .swept_box = true});
    for (auto [sign, separation] : {std::pair{true, true}, {true, false}, {false, true}}) {
      int variant = 0;  // the separations take turns at 2, 4 (with the boxes) and 8 pieces
      for (const double min_distance : {0.0, 1e-3, 0.25, 0x1p-1060, 1e300}) {
        const int pieces = 2 << (variant++ % 3);
        settings.push_back({.certified = certified, .sign = sign, .separation = separation,
                            .pieces = pieces, .swept_box = pieces == 4, .within = true,
                            .min_distance = min_distance});
      }
      settings.push_back({.certified = certified, .sign = sign, .separation = separation, .pieces = 1,
                          .within = true, .min_distance = 1e-3});
      settings.push_back({.certified = certified, .sign = sign, .separation = separation, .pieces = 4,
                          .swept_box = true, .within = true, .min_distances = candidate_separations().data()});
    }
  }
  return settings;
}

std::string describe(const reference::FilterSettings& s) {
  std::string text = std::string(s.certified ? "certified" : "plain") +
                     (s.sign ? (s.subdivide ? " sign" : " sign-dnf") : "") + (s.separation ? " separation" : "") +
                     " pieces " + std::to_string(s.pieces) + (s.swept_box ? " swept-box" : "");
  if (s.within)
    text += s.min_distances ? " within per-candidate" : " within " + std::to_string(s.min_distance);
  return text;
}

// Queries that stress every step of the lane arithmetic.
class QueryGenerator {
 public:
  explicit QueryGenerator(std::uint64_t seed) : random_(seed) {}

  Query next() {
    Query q = base_query();
    switch (pick(8)) {
      case 0: break;                                   // plain random
      case 1: flatten(q, std::ldexp(1.0, -pick(60))); break;  // near coplanar
      case 2: collapse(q); break;                      // coincident points, zero-length edges
      case 3: scale(q, pick(2090) - 1070); break;      // any exponent, subnormals included
      case 4: mix_magnitudes(q); break;                // 1e300 beside 1e-300
      case 5: round_to_grid(q); break;                 // exact zeros in the coefficients
      case 6: poison(q); break;                        // NaN and infinities
      case 7: stiff(q); break;                         // tiny motion at a large offset
    }
    return q;
  }

 private:
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  double coordinate() { return std::uniform_real_distribution<double>(-1, 1)(random_); }
  Vec3 point() { return {coordinate(), coordinate(), coordinate()}; }

  Query base_query() {
    Query q;
    for (Vec3& p : q.points) p = point();
    return q;
  }
  void flatten(Query& q, double height) {
    for (Vec3& p : q.points) p.z() *= height;
  }
  void collapse(Query& q) {
    const int times = 1 + pick(4);
    for (int n = 0; n < times; ++n) q.points[pick(8)] = q.points[pick(8)];
  }
  void scale(Query& q, int exponent) {
    for (Vec3& p : q.points)
      for (int c = 0; c < 3; ++c) p[c] = std::ldexp(p[c], exponent);
  }
  void mix_magnitudes(Query& q) {
    for (Vec3& p : q.points)
      for (int c = 0; c < 3; ++c) p[c] = std::ldexp(p[c], pick(2) ? 1000 : -1000);
  }
  void round_to_grid(Query& q) {
    for (Vec3& p : q.points)
      for (int c = 0; c < 3; ++c) p[c] = std::round(p[c] * 4);
  }
  void poison(Query& q) {
    const double values[] = {std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
    q.points[pick(8)][pick(3)] = values[pick(3)];
  }
  void stiff(Query& q) {
    const Vec3 offset = 1e8 * point();
    for (int k = 0; k < 4; ++k) {
      q.points[k] += offset;
      q.points[k + 4] = q.points[k] + 1e-3 * point();
    }
  }

  std::mt19937_64 random_;
};

TEST(SimdKernels, MatchTheReferenceFilterOnAdversarialQueries) {
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
  QueryGenerator generator(20261121);
  // 2^17: some 16,000 of each kind the generator makes, 24 MB (streamed:
  // the lanes prefetch), in seconds on two shared cores. Under
  // AddressSanitizer a quarter of that: still streamed (6 MB).
#if defined(__SANITIZE_ADDRESS__)
  std::vector<Query> queries(1 << 15);
#else
  std::vector<Query> queries(1 << 17);
#endif
  for (Query& q : queries) q = generator.next();
  for (Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
    const simd::RawQueries source = simd::raw_queries(kind, queries.data(), queries.size());
    ASSERT_TRUE(source.stream);  // more than a cache holds: the lanes prefetch
    for (const reference::FilterSettings& settings : all_settings()) {
      // Odd range ends exercise the partial last lane group. All the
      // queries for the whole step and for the default stages; the many
      // other settings take an eighth of them (the sanitizer build runs
      // this test too).
      const reference::FilterSettings defaults;
      const bool whole_step = settings.pieces == 1 && !settings.swept_box;
      const bool as_default = settings.sign == defaults.sign && settings.subdivide == defaults.subdivide &&
                              settings.separation == defaults.separation && settings.pieces == defaults.pieces &&
                              settings.swept_box == defaults.swept_box;
      const bool fewer = settings.within || !(whole_step || as_default);
      const std::size_t begin = 3, end = fewer ? begin + queries.size() / 8 + 1 : queries.size() - 5;
      const auto expected = survivors(simd::kScalarKernels.raw, source, begin, end, settings);
      EXPECT_LT(expected.kept.size(), end - begin);  // something is culled
      for (const simd::FilterKernels* k : kernels)
        EXPECT_EQ(survivors(k->raw, source, begin, end, settings), expected)
            << to_string(k->isa) << " " << to_string(kind) << " " << describe(settings);
    }
  }
}

// On meshes of finite coordinates (the lanes then skip their NaN checks
// and, without a separation, test the boxes before any magnitude:
// PackedPositions knows), plain or with huge, overflowing, tiny and nearly
// coincident vertices, and on one with NaN and infinite ones besides (the
// lanes keep their checks). `fine`: ten clusters of vertices at 1000, 0.05
// apart, each 6e-4 wide; most candidates join two clusters (apart, so the
// coarse boxes in floats run throughout: AVX-512, AVX2), one in twenty lies in
// one cluster, with gaps of the order of floats' roundings there (6e-5);
// float-subnormal and 1e25 vertices among them. A coarse threshold of 0
// makes this test fail.
TEST(SimdKernels, MatchTheReferenceFilterOnMeshIndexLists) {
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
  enum class Mesh { plain, fine, extreme, poisoned };
  for (const Mesh mesh : {Mesh::plain, Mesh::fine, Mesh::extreme, Mesh::poisoned}) {
    const bool poisoned = mesh == Mesh::poisoned;
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> coordinate(-1, 1);
    const int vertices = 200, faces = 300, pairs = 20000;
    Eigen::MatrixXd t0(vertices, 3), t1(vertices, 3);
    const bool fine = mesh == Mesh::fine;
    constexpr int kClusters = 10;  // vertex v in cluster v % kClusters
    const double spread = fine ? 3e-4 : 1;
    for (int i = 0; i < vertices; ++i)
      for (int c = 0; c < 3; ++c) {
        t0(i, c) = (fine ? 1000 + (c == 0 ? 0.05 * (i % kClusters) : 0) : 0) + spread * coordinate(random);
        t1(i, c) = t0(i, c) + 0.1 * spread * coordinate(random);
      }
    if (mesh == Mesh::fine) {
      t0.row(5) *= 1e-43, t1.row(5) *= 1e-43;  // below floats' normal range
      t0.row(9) *= 1e-43, t1.row(9) = t0.row(9) * 2;
      t0.row(37) *= 1e22, t1.row(37) *= 1e22;
    }
    if (mesh == Mesh::extreme || poisoned) {
      t0.row(13) *= 1e300, t1.row(13) *= 1e300;  // outside the direct frames' window
      t1.row(17) = t0.row(17) = t0.row(19) + Eigen::RowVector3d::Constant(1e-300);
      t1.row(19) = t0.row(19);
      t0.row(23).setConstant(1.5e308), t1.row(23).setConstant(1.6e308);  // differences overflow
      t0.row(29).setConstant(-1.5e308), t1.row(29).setConstant(-1.4e308);
      t0.row(31) *= 1e-310, t1.row(31) *= 1e-310;  // subnormal
    }
    if (poisoned) {
      t0(3, 1) = std::numeric_limits<double>::quiet_NaN();
      t1(7, 2) = std::numeric_limits<double>::infinity();
      t0(11, 0) = -std::numeric_limits<double>::infinity();
    }
    Eigen::MatrixXi face_matrix(faces, 3);
    std::uniform_int_distribution<int> vertex(0, vertices - 1), face(0, faces - 1);
    // Fine: a face's corners in cluster f % kClusters; a candidate's two
    // primitives in one cluster once in twenty, else in two.
    std::uniform_int_distribution<int> cluster(0, kClusters - 1), member(0, vertices / kClusters - 1),
        other(1, kClusters - 1), twentieth(0, 19);
    const auto in_cluster = [&](int k) { return k + kClusters * member(random); };
    const auto pair_of = [&](int k) { return twentieth(random) == 0 ? k : (k + other(random)) % kClusters; };
    for (int f = 0; f < faces; ++f)
      for (int c = 0; c < 3; ++c) face_matrix(f, c) = fine ? in_cluster(f % kClusters) : vertex(random);
    std::vector<std::array<int, 2>> vf(pairs);
    std::vector<std::array<int, 4>> ee(pairs);
    for (auto& p : vf) {
      const int k = cluster(random);
      p = fine ? std::array{in_cluster(k), pair_of(k) + kClusters * (face(random) / kClusters)}
               : std::array{vertex(random), face(random)};
    }
    for (auto& e : ee) {
      const int k = cluster(random), l = pair_of(k);
      e = fine ? std::array{in_cluster(k), in_cluster(k), in_cluster(l), in_cluster(l)}
               : std::array{vertex(random), vertex(random), vertex(random), vertex(random)};
    }
    const simd::PackedPositions packed(t0, t1);
    const simd::MeshPositions positions = packed.view();
    EXPECT_EQ(positions.finite, !poisoned);
    EXPECT_EQ(positions.coarse != nullptr, mesh == Mesh::plain || mesh == Mesh::fine);
    const simd::PackedFaces packed_faces(face_matrix, faces);
    const simd::MeshVertexFace vf_source{positions, packed_faces.view(), vf.data()};
    const simd::MeshEdgeEdge ee_source{positions, ee.data()};
    for (const reference::FilterSettings& settings : all_settings()) {
      const auto vf_expected = survivors(simd::kScalarKernels.vertex_face, vf_source, 1, pairs, settings);
      const auto ee_expected = survivors(simd::kScalarKernels.edge_edge, ee_source, 1, pairs, settings);
      for (const simd::FilterKernels* k : kernels) {
        EXPECT_EQ(survivors(k->vertex_face, vf_source, 1, pairs, settings), vf_expected)
            << to_string(k->isa) << " " << describe(settings) << " mesh ";
        EXPECT_EQ(survivors(k->edge_edge, ee_source, 1, pairs, settings), ee_expected)
            << to_string(k->isa) << " " << describe(settings) << " mesh ";
      }
    }
  }
}

// The point kinds (vertex-edge, vertex-vertex: edge-edge queries of a
// point, Query's layout) under their own separation filter
// (FilterSettings::point_kind), lanes against the reference: raw queries
// from the adversarial generator made into points, and mesh lists over
// finite and poisoned vertices.
Query as_point_kind(Kind kind, Query q) {
  q.points[1] = q.points[0], q.points[5] = q.points[4];
  if (kind == Kind::vertex_vertex) q.points[3] = q.points[2], q.points[7] = q.points[6];
  return q;
}

TEST(SimdKernels, MatchTheReferenceFilterOnPointKinds) {
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
#if defined(__SANITIZE_ADDRESS__)
  constexpr std::size_t kQueries = 1 << 12;
#else
  constexpr std::size_t kQueries = 1 << 15;  // streamed (6 MB): the lanes prefetch
#endif
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  const int vertices = 200, pairs = 20000;
  Eigen::MatrixXd t0(vertices, 3), t1(vertices, 3);
  for (int i = 0; i < vertices; ++i)
    for (int c = 0; c < 3; ++c) t0(i, c) = coordinate(random), t1(i, c) = t0(i, c) + 0.1 * coordinate(random);
  t0.row(13) *= 1e300, t1.row(13) *= 1e300;  // outside the direct frames' window
  t0.row(31) *= 1e-310, t1.row(31) *= 1e-310;
  t0.row(37) = t0.row(36), t1.row(37) = t1.row(36);  // a zero-length edge (36, 37)
  Eigen::MatrixXd poisoned_t0 = t0;
  poisoned_t0(3, 1) = std::numeric_limits<double>::quiet_NaN();
  std::uniform_int_distribution<int> vertex(0, vertices - 1);
  std::vector<std::array<int, 4>> vertex_edge(pairs), vertex_vertex(pairs);
  for (auto& p : vertex_edge) {  // one in ten against the zero-length edge
    const int v = vertex(random), a = vertex(random);
    p = a % 10 == 0 ? std::array{v, v, 36, 37} : std::array{v, v, a, vertex(random)};
  }
  for (auto& p : vertex_vertex) {
    const int v = vertex(random), w = vertex(random);
    p = {v, v, w, w};
  }
  QueryGenerator generator(20261127);
  for (const Kind kind : {Kind::vertex_edge, Kind::vertex_vertex}) {
    std::vector<Query> queries(kQueries);
    for (Query& q : queries) q = as_point_kind(kind, generator.next());
    const simd::RawQueries raw = simd::raw_queries(Kind::edge_edge, queries.data(), queries.size());
    const auto& list = kind == Kind::vertex_edge ? vertex_edge : vertex_vertex;
    for (const bool poisoned : {false, true}) {
      const simd::PackedPositions packed(poisoned ? poisoned_t0 : t0, t1);
      const simd::MeshEdgeEdge mesh{packed.view(), list.data()};
      for (reference::FilterSettings settings : all_settings()) {
        settings.point_kind = kind;
        const std::string what = std::string(to_string(kind)) + " " + describe(settings);
        const auto raw_expected = survivors(simd::kScalarKernels.raw, raw, 3, queries.size() - 5, settings);
        const auto mesh_expected = survivors(simd::kScalarKernels.edge_edge, mesh, 1, pairs, settings);
        for (const simd::FilterKernels* k : kernels) {
          if (!poisoned) {
            EXPECT_EQ(survivors(k->raw, raw, 3, queries.size() - 5, settings), raw_expected)
                << to_string(k->isa) << " " << what;
          }
          EXPECT_EQ(survivors(k->edge_edge, mesh, 1, pairs, settings), mesh_expected)
              << to_string(k->isa) << " " << what << (poisoned ? " poisoned mesh" : " mesh");
        }
      }
    }
  }
}

// The point kinds' separation filter culls no query that comes within its
// separation: sampled distances (a point against a segment, or a point) at
// 1,025 times, against the scalar reference's culls, for point-kind
// queries whose motion passes near each other.
TEST(SimdKernels, PointKindCullsAreSound) {
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  const auto distance_at = [](Kind kind, const Query& q, double t) {
    const auto at = [&](int k) -> Vec3 { return (1 - t) * q.points[k] + t * q.points[k + 4]; };
    const Vec3 p = at(0), a = at(2), b = at(3);
    if (kind == Kind::vertex_vertex) return (p - a).norm();
    const Vec3 d = b - a;
    const double along = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (p - (a + along * d)).norm();
  };
  int culled = 0, near = 0;
  for (const Kind kind : {Kind::vertex_edge, Kind::vertex_vertex})
    for (int n = 0; n < 20000; ++n) {
      Query q;
      for (Vec3& p : q.points) p = {coordinate(random), coordinate(random), coordinate(random)};
      q = as_point_kind(kind, q);
      for (int k = 4; k < 8; ++k) q.points[k] = q.points[k - 4] + 0.3 * (q.points[k] - q.points[k - 4]);
      const double separation = std::ldexp(1.0, -static_cast<int>(random() % 8));
      double closest = std::numeric_limits<double>::infinity();
      for (int i = 0; i <= 1024; ++i) closest = std::min(closest, distance_at(kind, q, i / 1024.0));
      for (bool within : {false, true}) {
        reference::FilterSettings settings{.sign = false, .pieces = 4, .within = within,
                                           .min_distance = within ? separation : 0.0, .point_kind = kind};
        const bool cull = reference::run_filters(Kind::edge_edge, q, settings).culled();
        culled += cull;
        const bool comes_near = closest <= (within ? separation : 0.0) * 0.999;
        near += comes_near;
        if (comes_near) {
          EXPECT_FALSE(cull) << to_string(kind) << " query " << n;
        }
      }
    }
  EXPECT_GT(culled, 10000);  // the filter culls, and some queries come near
  EXPECT_GT(near, 100);
}

// The second pass gets survivors with a gap, and a last partial group whose
// spare lanes repeat its last candidate: [4, 5, 7, 7] on four lanes,
// [0, ..., 5, 7, 7] on eight. Its ends lie as far apart as those of
// consecutive candidates, which they are not (a past version took them for
// consecutive, evaluated query 6 in query 7's lane and culled a collision).
TEST(SimdKernels, SecondPassEvaluatesTheSurvivorsItIsGiven) {
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Query falls_through{{Vec3(0.25, 0.25, 1), a, b, c, Vec3(0.25, 0.25, -1), a, b, c}};
  const Query stays_above{{Vec3(0.25, 0.25, 5), a, b, c, Vec3(0.25, 0.25, 4), a, b, c}};
  std::vector<Query> queries(8, falls_through);
  queries[6] = stays_above;
  const simd::RawQueries source{Kind::vertex_face, queries.data()};
  const std::vector<std::uint32_t> collisions = {0, 1, 2, 3, 4, 5, 7};
  for (const reference::FilterSettings& settings : all_settings()) {
    if (!settings.sign && !settings.separation) continue;
    if (settings.within && (settings.min_distances != nullptr || settings.min_distance > 1)) continue;  // within reach
    for (const simd::FilterKernels* k : kernels) {
      const std::vector<std::uint32_t> kept = survivors(k->raw, source, 0, queries.size(), settings).kept;
      EXPECT_EQ(kept, collisions) << to_string(k->isa) << " " << describe(settings);
    }
  }
}

// The packed rows know their largest coordinate magnitude, over both
// times and every range packed (the lanes bound the boxes' threshold at a
// separation with it: lane_kernels.hpp, threshold_bound), and infinity
// once a coordinate is not finite.
TEST(SimdKernels, PackedRowsKnowTheirLargestMagnitude) {
  Eigen::MatrixXd t0(4, 3), t1(4, 3);
  t0 << 1, -2, 0.5, 0, 0, 0, 3, 1, 1, -0.25, 0, 0;
  t1 = t0;
  t1(2, 1) = -7.5;  // at t1, negative, in the range packed first
  simd::PackedPositions packed(4);
  packed.pack(t0, t1, 2, 4);
  packed.pack(t0, t1, 0, 2);
  EXPECT_EQ(packed.view().largest, 7.5);
  packed.resize(4);  // packed anew: the old rows' largest forgotten
  t1(2, 1) = 0.5;
  packed.pack(t0, t1, 0, 4);
  EXPECT_EQ(packed.view().largest, 3.0);
  t0(1, 2) = std::numeric_limits<double>::quiet_NaN();
  packed.resize(4);
  packed.pack(t0, t1, 0, 4);
  EXPECT_EQ(packed.view().largest, std::numeric_limits<double>::infinity());
}

// At a separation s the lanes settle most groups on a bound of the boxes'
// threshold for the whole mesh before the exact test (threshold_bound).
// Static edges along x whose boxes lie s + 2^-42 apart at coordinates of
// 1024: above s, but within the threshold's margin for coordinates'
// rounding (8 u of 1025, about 2^-40), so the exact test keeps them, and
// so must the lanes; 2^-36 apart, beyond the margin, all cull them.
TEST(SimdKernels, BoxesAtASeparationKeepTheirMarginForRounding) {
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
  const double separation = 0x1p-10;
  for (const double beyond : {0x1p-42, 0x1p-36}) {
    const double gap = separation + beyond;
    Eigen::MatrixXd t0(4, 3);
    t0 << 0, 0, 0, 1024, 0, 0, 1024 + gap, 0, 0, 1025 + gap, 0, 1;
    const simd::PackedPositions packed(t0, t0);
    const std::vector<std::array<int, 4>> pairs(8, std::array{0, 1, 2, 3});
    const simd::MeshEdgeEdge source{packed.view(), pairs.data()};
    const reference::FilterSettings settings{.sign = false, .separation = false, .pieces = 1, .swept_box = true,
                                             .within = true, .min_distance = separation};
    const auto expected = survivors(simd::kScalarKernels.edge_edge, source, 0, pairs.size(), settings);
    const bool kept = beyond < 0x1p-40;
    EXPECT_EQ(expected.culls[3], kept ? 0u : pairs.size()) << "boxes' culls, " << beyond << " beyond";
    for (const simd::FilterKernels* k : kernels)
      EXPECT_EQ(survivors(k->edge_edge, source, 0, pairs.size(), settings), expected)
          << to_string(k->isa) << ", " << beyond << " beyond";
  }
}

// The coarse boxes in floats (simd/coarse_boxes.hpp: AVX-512, AVX2) cull
// only what the double boxes cull, where float rounding works against
// them. Along x, x1 lies at P at t0, which rounds up to a float by nearly
// half its spacing, and at Q at t1, which rounds down as far: the first
// box reaches H = 1.5 - P (at t0), the second starts at H + g (at t1),
// exactly g apart in doubles (g = 0, or the separation), which keep the
// candidate; in floats the gap is g + 2^-23, which the floats alone would
// cull, and only the rounding bound (8 S, S about 3.5 2^-24 here) keeps
// it. The same at scales of 2^-60 to 2^97 (where floats round alike),
// among float subnormals (2^-135) and below floats (2^-160), and with a
// vertex that leaves the mesh without coarse rows (a NaN, an infinity,
// 2^101). The lists start with candidates 0.25 further apart (so the
// coarse test stays on past its trial), then the ones at the boundary,
// then one at the boundary in every eight; per-candidate separations
// take two values four by four. Threshold 0 (no 8 S), the rounding
// bounds e at 2^-30 |x| instead of 2^-24, or AVX2's per-candidate
// separations read with their halves swapped makes this test fail.
TEST(SimdKernels, CoarseBoxesCullOnlyWhatTheDoubleBoxesCull) {
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
  const double P = 1 + 0x1p-24 + 0x1p-33, Q = 1 + 0x1p-24 - 0x1p-33, H = 1.5 - P;
  const double separation = 0x1p-10;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double g : {0.0, separation}) {
    // In floats, the boundary's gap beyond g exceeds g's own rounding up.
    const float float_gap = (static_cast<float>(Q + H + g) - static_cast<float>(Q)) - (1.5F - static_cast<float>(P));
    EXPECT_GT(float_gap, static_cast<float>(g * (1 + 0x1p-20)));
    for (const int scale : {0, -60, 60, 97, -135, -160})
      for (const double unused : {0.0, nan, inf, 0x1p101}) {
        if (scale != 0 && unused != 0) continue;
        // Vertices: x1, x2 (EE and the face), the boundary's x3, x4 (EE;
        // x3 is VF's vertex), the face's third corner, the far x3, x4, and
        // one no candidate names.
        Eigen::MatrixXd t0(8, 3), t1(8, 3);
        t0 << P, 0, 0, 1.5, 0, 0, 2 + g, 0, 0, 2.5 + g, 0, 0, 1.25, 1, 0, 2.25 + g, 0, 0, 2.75 + g, 0, 0, unused, 0, 0;
        t1 << Q, 0, 0, 1.25, 0, 0, Q + H + g, 0, 0, 2.5 + g, 0, 0, 1.25, 1, 0, Q + H + g + 0.25, 0, 0, 2.75 + g, 0, 0,
            0, 0, 0;
        t0.topRows(7) *= std::ldexp(1.0, scale), t1.topRows(7) *= std::ldexp(1.0, scale);
        const simd::PackedPositions packed(t0, t1);
        const simd::MeshPositions positions = packed.view();
        EXPECT_EQ(positions.coarse != nullptr, unused == 0 && scale < 98) << scale << " " << unused;
        const Eigen::MatrixXi faces = (Eigen::MatrixXi(1, 3) << 0, 1, 4).finished();
        const simd::PackedFaces packed_faces(faces, 1);
        std::vector<std::array<int, 4>> ee;
        std::vector<std::array<int, 2>> vf;
        std::vector<double> separations;
        for (int n = 0; n < 256; ++n) {
          const bool boundary = (n >= 64 && n < 128) || (n >= 128 && n % 8 == 3);
          ee.push_back(boundary ? std::array{0, 1, 2, 3} : std::array{0, 1, 5, 6});
          vf.push_back(boundary ? std::array{2, 0} : std::array{5, 0});
          // The far ones kept where their separation exceeds their gap.
          separations.push_back(std::ldexp(boundary || n % 8 < 4 ? separation : 0.5, scale));
        }
        const simd::MeshEdgeEdge ee_source{positions, ee.data()};
        const simd::MeshVertexFace vf_source{positions, packed_faces.view(), vf.data()};
        const reference::FilterSettings boxes{.sign = false, .separation = false, .pieces = 1, .swept_box = true};
        std::vector<reference::FilterSettings> settings(2, boxes);
        settings[1] = {};  // every stage
        if (g > 0)
          for (std::size_t i = 0, n = settings.size(); i < n; ++i) {
            settings[i].within = true, settings[i].min_distance = std::ldexp(separation, scale);
            settings.push_back(settings[i]);
            settings.back().min_distances = separations.data();
          }
        for (const reference::FilterSettings& s : settings) {
          const std::string what = describe(s) + ", scale 2^" + std::to_string(scale) + ", unused " +
                                   std::to_string(unused) + ", gap " + std::to_string(g);
          const auto ee_expected = survivors(simd::kScalarKernels.edge_edge, ee_source, 0, ee.size(), s);
          const auto vf_expected = survivors(simd::kScalarKernels.vertex_face, vf_source, 0, vf.size(), s);
          if (&s == &settings[0] && std::abs(scale) <= 97) {
            // The double boxes keep every candidate at the boundary, and cull the far ones.
            EXPECT_EQ(ee_expected.kept.size(), 64u + 16u) << what;
            EXPECT_EQ(vf_expected.kept.size(), 64u + 16u) << what;
          }
          for (const simd::FilterKernels* k : kernels) {
            EXPECT_EQ(survivors(k->edge_edge, ee_source, 0, ee.size(), s), ee_expected)
                << to_string(k->isa) << " edge-edge, " << what;
            EXPECT_EQ(survivors(k->vertex_face, vf_source, 0, vf.size(), s), vf_expected)
                << to_string(k->isa) << " vertex-face, " << what;
          }
        }
      }
  }
}

// Every instruction set gives the same final answers as the scalar path.
TEST(SimdKernels, FinalDecisionsAreIdenticalOnSharedData) {
  if (!testing::shared_data_present()) GTEST_SKIP() << testing::kSharedData << " is absent";
  const auto kernels = vector_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no vector instruction set on this processor";
  auto same = [](const BatchResult& a, const BatchResult& b, const std::string& what) {
    testing::expect_same_answers(b, a, what);
    testing::expect_same_counts(b, a, what);
  };
  for (const simd::FilterKernels* k : kernels) {
    std::size_t inputs = 0;
    Options scalar, vector;
    scalar.isa = Isa::scalar;
    vector.isa = k->isa;
    const lab::Settings stages{.filter_pieces = 4, .swept_box_filter = true};
    for (const std::filesystem::path& path : testing::shared_query_files()) {
      const QueryFile file = read_query_csv(path, *kind_from_path(path));
      same(lab::batch_ccd(file.kind, file.queries, scalar, stages),
           lab::batch_ccd(file.kind, file.queries, vector, stages), path.string() + " " + to_string(k->isa));
      ++inputs;
    }
    for (const std::filesystem::path& directory : testing::shared_scene_directories()) {
      const Scene scene = read_scene(directory);
      const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
      same(lab::mesh_ccd(mesh, scene.candidates, scalar, stages),
           lab::mesh_ccd(mesh, scene.candidates, vector, stages), directory.string() + " " + to_string(k->isa));
      ++inputs;
    }
    EXPECT_GT(inputs, 0u) << "no query file or scene under " << testing::kSharedData;
  }
}

}  // namespace
}  // namespace batchccd

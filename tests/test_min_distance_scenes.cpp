// Minimum separation on the shared scenes' candidates (issue 19), labelled as
// ../shared/data/min-distance/unit-ms1e-3 was: a hit by an exact rational
// witness, a miss by a certified Lipschitz lower bound of the distance over
// [0, 1], anything else unlabelled and counted. Both certified modes are then
// held to the labels at D = 1e-3 and 1e-2 mean edge lengths, on the scenes'
// own lists and on a sample of a complete broad phase for D.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "batchccd/batch.hpp"
#include "batchccd/candidates.hpp"
#include "batchccd/io.hpp"
#include "broad_phase.hpp"
#include "exact_distance.hpp"

namespace batchccd {
namespace {

using testing::Rational;
using testing::squared_distance_at;

const std::filesystem::path kScenes = std::filesystem::path(BATCHCCD_SHARED_DATA) / "scenes";

// Bounds on the labelling's work per candidate: past them it is unlabelled.
constexpr int kSearchSamples = 1 << 12;  // double-precision witness search
constexpr int kExactSamples = 1 << 11;   // exact samples of the certification
constexpr int kWitnessTries = 4;         // double witnesses checked exactly
constexpr double kFinest = 0x1p-32;      // the witness search's time resolution

enum class Label { hit, miss, unlabelled };

struct Labelled {
  Label label = Label::unlabelled;
  double witness = 0;      // hit: earliest time found with exact distance <= D
  double lower_bound = 0;  // miss: certified lower bound of the distance over [0, 1]
  double lipschitz = 0;    // certified upper bound of |d'(t)|
  double size = 0;         // >= the query's size as Options::tolerance measures it
};

// Certified bounds of sqrt(x2) (x2 exact): the double is nudged until the exact square agrees.
double sqrt_below(const Rational& x2) {
  if (sgn(x2) <= 0) return 0;
  double r = std::sqrt(x2.get_d()) * (1 - 0x1p-40);
  while (Rational(r) * Rational(r) > x2) r *= 1 - 0x1p-40;
  return r;
}
double sqrt_above(const Rational& x2) {
  if (sgn(x2) <= 0) return 0;
  double r = std::max(std::sqrt(x2.get_d()) * (1 + 0x1p-40), std::numeric_limits<double>::denorm_min());
  while (Rational(r) * Rational(r) < x2) r *= 1 + 0x1p-40;
  return r;
}

// d(t) moves no faster than the largest relative velocity of a vertex of one
// primitive against one of the other (points of the primitives move with
// convex combinations of their vertices' velocities).
double lipschitz_bound(Kind kind, const Query& q) {
  const std::vector<int> a = kind == Kind::vertex_face ? std::vector{0} : std::vector{0, 1};
  const std::vector<int> b = kind == Kind::vertex_face ? std::vector{1, 2, 3} : std::vector{2, 3};
  Rational largest = 0;
  for (const int i : a)
    for (const int j : b) {
      Rational norm2 = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const Rational v = (Rational(q.points[i + 4][axis]) - Rational(q.points[i][axis])) -
                           (Rational(q.points[j + 4][axis]) - Rational(q.points[j][axis]));
        norm2 += v * v;
      }
      largest = std::max(largest, norm2);
    }
  return sqrt_above(largest);
}

double query_size(const Query& q) {
  double size = 0;
  for (const Vec3& p : q.points)
    for (const Vec3& r : q.points) size = std::max(size, (p - r).cwiseAbs().maxCoeff());
  return size;
}

double distance_in_double(Kind kind, const Query& q, double t) {
  std::array<reference::Point<double>, 4> x;
  for (int k = 0; k < 4; ++k)
    for (int axis = 0; axis < 3; ++axis)
      x[k][axis] = q.points[k][axis] + t * (q.points[k + 4][axis] - q.points[k][axis]);
  return std::sqrt(reference::squared_distance(kind == Kind::vertex_face, x));
}

struct Interval {
  double a, da, b, db;  // the ends and the distance (or its lower bound) there
};

// Times where the double distance is <= D, earliest first: a left-first
// Lipschitz search that keeps refining before its earliest find. Only
// candidates for a witness; nothing here is trusted.
std::vector<double> witness_candidates(Kind kind, const Query& q, double separation, double m) {
  const double d0 = distance_in_double(kind, q, 0), d1 = distance_in_double(kind, q, 1);
  if (d0 <= separation) return {0.0};
  std::vector<double> found;
  double earliest = 2;
  if (d1 <= separation) {
    found.push_back(1);
    earliest = 1;
  }
  std::vector<Interval> stack{{0, d0, 1, d1}};
  for (int samples = 2; !stack.empty() && samples < kSearchSamples;) {
    const Interval i = stack.back();
    stack.pop_back();
    if (i.a >= earliest || i.b - i.a < kFinest) continue;
    if (i.da + i.db - m * (i.b - i.a) > 2 * separation * (1 + 1e-9)) continue;
    const double c = (i.a + i.b) / 2, dc = distance_in_double(kind, q, c);
    ++samples;
    if (dc <= separation) {
      found.push_back(c);
      earliest = c;
    } else {
      stack.push_back({c, dc, i.b, i.db});
    }
    stack.push_back({i.a, i.da, c, dc});
  }
  std::sort(found.begin(), found.end());
  return found;
}

// Exact labelling: a sample with exact squared distance <= D^2 is a witness;
// an interval [a, b] is cleared when lower bounds la, lb of the distance at
// its ends give (la + lb - m (b - a)) / 2 > D, the least the Lipschitz cones
// from both ends allow inside it. Left-first, at most kExactSamples samples.
void certify(Kind kind, const Query& q, double separation, Labelled& out) {
  const Rational d(separation), d2 = d * d, m(out.lipschitz);
  double lower = std::numeric_limits<double>::infinity();
  const auto sample = [&](double t, double& bound) {
    const Rational s2 = squared_distance_at(kind, q, Rational(t));
    bound = sqrt_below(s2);
    return s2 <= d2;
  };
  double l0 = 0, l1 = 0;
  for (const double t : {0.0, 1.0})
    if (sample(t, t == 0 ? l0 : l1)) {
      out.label = Label::hit;
      out.witness = t;
      return;
    }
  std::vector<Interval> stack{{0, l0, 1, l1}};
  for (int samples = 2; !stack.empty();) {
    const Interval i = stack.back();
    stack.pop_back();
    const Rational cleared = (Rational(i.da) + Rational(i.db) - m * (Rational(i.b) - Rational(i.a))) / 2;
    if (cleared > d) {
      lower = std::min(lower, cleared.get_d());  // get_d truncates: still a lower bound
      continue;
    }
    if (samples++ >= kExactSamples) return;  // unlabelled
    const double c = (i.a + i.b) / 2;
    double lc = 0;
    if (sample(c, lc)) {
      out.label = Label::hit;
      out.witness = c;
      return;
    }
    stack.push_back({c, lc, i.b, i.db});
    stack.push_back({i.a, i.da, c, lc});
  }
  out.label = Label::miss;
  out.lower_bound = lower;
}

Labelled label(Kind kind, const Query& q, double separation) {
  Labelled out;
  out.lipschitz = lipschitz_bound(kind, q);
  out.size = query_size(q);
  const Rational d(separation), d2 = d * d;
  const std::vector<double> times = witness_candidates(kind, q, separation, out.lipschitz);
  for (std::size_t k = 0; k < times.size() && k < kWitnessTries; ++k)
    if (squared_distance_at(kind, q, Rational(times[k])) <= d2) {
      out.label = Label::hit;
      out.witness = times[k];
      return out;
    }
  certify(kind, q, separation, out);
  return out;
}

double mean_edge_length(const Eigen::MatrixXd& positions, const Eigen::MatrixXi& faces) {
  const Eigen::MatrixXi edges = unique_edges(faces);
  double total = 0;
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    total += (positions.row(edges(e, 0)) - positions.row(edges(e, 1))).norm();
  return total / static_cast<double>(edges.rows());
}

std::string describe(const Query& q) {
  std::ostringstream text;
  text.precision(17);
  for (const Vec3& p : q.points) text << " (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return text.str();
}

// Every `stride`-th candidate of each list (deterministic).
Candidates every(const Candidates& all, std::size_t stride) {
  Candidates some;
  for (std::size_t i = 0; i < all.vertex_face.size(); i += stride) some.vertex_face.push_back(all.vertex_face[i]);
  for (std::size_t i = 0; i < all.edge_edge.size(); i += stride) some.edge_edge.push_back(all.edge_edge[i]);
  return some;
}

// Labels `candidates` at separation D, runs both certified modes on them and
// holds them to the labels; prints the counts.
void check_labels(const std::string& name, const MeshView& mesh, const Candidates& candidates, double factor,
                  double separation) {
  SCOPED_TRACE(name + " D = " + std::to_string(factor) + " mean edge");
  std::vector<std::pair<Kind, Query>> queries;  // mesh_ccd's order: vf, then ee
  for (const auto& c : candidates.vertex_face) queries.push_back({Kind::vertex_face, vertex_face_query(mesh, c)});
  for (const auto& c : candidates.edge_edge) queries.push_back({Kind::edge_edge, edge_edge_query(mesh, c)});
  ASSERT_FALSE(queries.empty());
  std::vector<Labelled> labels(queries.size());
  tbb::parallel_for(std::size_t{0}, queries.size(),
                    [&](std::size_t i) { labels[i] = label(queries[i].first, queries[i].second, separation); });
  int hits = 0, misses = 0, unlabelled = 0;
  for (const Labelled& l : labels) {
    hits += l.label == Label::hit;
    misses += l.label == Label::miss;
    unlabelled += l.label == Label::unlabelled;
  }

  Options options;
  options.min_distance = separation;
  int negatives[2] = {0, 0}, positives[2] = {0, 0}, excused = 0, too_close = 0;
  for (const Mode mode : {Mode::conservative, Mode::exact}) {
    options.mode = mode;
    const BatchResult batch = mesh_ccd(mesh, candidates, options);
    ASSERT_EQ(batch.results.size(), queries.size());
    const int m = mode == Mode::exact;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const Labelled& l = labels[i];
      const QueryResult& r = batch.results[i];
      const Query& q = queries[i].second;
      if (l.label == Label::hit) {
        negatives[m] += !r.hit;
        EXPECT_TRUE(r.hit) << to_string(mode) << " false negative: candidate " << i << " ("
                           << to_string(queries[i].first) << "), witness t = " << l.witness << ", points"
                           << describe(q);
        if (r.hit) {
          EXPECT_LE(r.toi, l.witness) << to_string(mode) << " candidate " << i;
        }
      } else if (l.label == Label::miss && r.hit) {
        ++positives[m];
        // The promised slack: min_distance + tolerance x size, or toi_tolerance
        // (2^-45 in exact mode) after tmax, where d(t) >= bound - m (t - 1).
        const double band = mode == Mode::exact ? 0x1p-40 * l.size + l.lipschitz * 0x1p-45
                                                : options.tolerance * l.size + l.lipschitz * options.toi_tolerance;
        const bool close = l.lower_bound <= separation + band || l.lower_bound <= separation * (1 + 1e-9);
        if (close) ++(mode == Mode::exact ? too_close : excused);
        std::cout << "  " << name << " f=" << factor << " " << to_string(mode) << " false positive: candidate " << i
                  << " lower bound / D - 1 = " << l.lower_bound / separation - 1
                  << (close ? " (within the promised band)" : "") << "\n";
        EXPECT_TRUE(close) << to_string(mode) << " false positive: candidate " << i << ", certified distance >= "
                           << l.lower_bound << " > D = " << separation << ", points" << describe(q);
      }
    }
  }
  std::cout << name << " D = " << factor << " mean edge (" << separation << "): " << queries.size()
            << " candidates, " << hits << " labelled hits, " << misses << " labelled misses, " << unlabelled
            << " unlabelled; conservative FN " << negatives[0] << " FP " << positives[0] << " (" << excused
            << " within tolerance); exact FN " << negatives[1] << " FP " << positives[1] << " (" << too_close
            << " within the band)\n";
  ::testing::Test::RecordProperty(name + "_f" + std::to_string(factor),
                                  std::to_string(queries.size()) + " candidates, " + std::to_string(hits) +
                                      " hits, " + std::to_string(misses) + " misses, " + std::to_string(unlabelled) +
                                      " unlabelled");
  // The labelling must settle nearly everything, or the check says little.
  EXPECT_LE(unlabelled, static_cast<int>(queries.size()) / 20);
}

constexpr double kFactors[] = {1e-3, 1e-2};  // D in mean edge lengths

// The scene's own candidates (vf.csv, ee.csv).
void check_scene(const std::string& name) {
  if (!is_scene_directory(kScenes / name)) GTEST_SKIP() << kScenes / name << " is absent";
  const Scene scene = read_scene(kScenes / name);
  const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
  const double edge = mean_edge_length(scene.positions_t0, scene.faces);
  for (const double factor : kFactors) check_labels(name, mesh, scene.candidates, factor, factor * edge);
}

// The scenes' own lists are all within D (IPC keeps contacts that close), so
// misses come from a swept-box broad phase with margin D: complete for
// separation D (boxes of points within D overlap when grown by D / 2), sampled
// down to at most kSampled candidates a list.
constexpr std::size_t kSampled = 1500;
void check_broad_phase_sample(const std::string& name) {
  if (!is_scene_directory(kScenes / name)) GTEST_SKIP() << kScenes / name << " is absent";
  const Scene scene = read_scene(kScenes / name);
  const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
  const double edge = mean_edge_length(scene.positions_t0, scene.faces);
  for (const double factor : kFactors) {
    const Candidates all = scenes::swept_box_candidates(mesh, factor * edge);
    const std::size_t longest = std::max(all.vertex_face.size(), all.edge_edge.size());
    check_labels(name + " (broad phase, every " + std::to_string(longest / kSampled + 1) + "th)", mesh,
                 every(all, longest / kSampled + 1), factor, factor * edge);
  }
}

TEST(SharedSceneMinDistance, ArmadilloRollers326) { check_scene("armadillo-rollers-326"); }
TEST(SharedSceneMinDistance, ClothFunnel227) { check_scene("cloth-funnel-227"); }
TEST(SharedSceneMinDistance, RodTwist3036) { check_scene("rod-twist-3036"); }
TEST(SharedSceneMinDistance, ArmadilloRollers326BroadPhase) { check_broad_phase_sample("armadillo-rollers-326"); }
TEST(SharedSceneMinDistance, ClothFunnel227BroadPhase) { check_broad_phase_sample("cloth-funnel-227"); }
TEST(SharedSceneMinDistance, RodTwist3036BroadPhase) { check_broad_phase_sample("rod-twist-3036"); }

}  // namespace
}  // namespace batchccd

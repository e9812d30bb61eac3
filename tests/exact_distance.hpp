#pragma once

// The exact squared distance between a query's primitives at a rational
// time, in GMP rationals (every double is one): a value <= min_distance^2
// proves a contact there. And labels of queries at a separation D built on
// it: a hit by an exact rational witness, a miss by a certified Lipschitz
// lower bound of the distance over [0, 1], anything else unlabelled.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <gmpxx.h>

#include "batchccd/query.hpp"
#include "reference/closest_distance.hpp"

namespace batchccd::testing {

using Rational = mpq_class;

inline Rational squared_distance_at(Kind kind, const Query& query, const Rational& t) {
  std::array<reference::Point<Rational>, 4> x;
  for (int k = 0; k < 4; ++k)
    for (int axis = 0; axis < 3; ++axis) {
      const Rational start(query.points[k][axis]), end(query.points[k + 4][axis]);
      x[k][axis] = start + t * (end - start);
    }
  return reference::squared_distance(kind == Kind::vertex_face, x);
}

// Bounds on the labelling's work per candidate: past them it is unlabelled.
inline constexpr int kSearchSamples = 1 << 12;  // double-precision witness search
inline constexpr int kExactSamples = 1 << 11;   // exact samples of the certification
inline constexpr int kWitnessTries = 4;         // double witnesses checked exactly
inline constexpr double kFinest = 0x1p-32;      // the witness search's time resolution

enum class Label { hit, miss, unlabelled };

struct Labelled {
  Label label = Label::unlabelled;
  double witness = 0;      // hit: earliest time found with exact distance <= D
  double lower_bound = 0;  // miss: certified lower bound of the distance over [0, 1]
  double lipschitz = 0;    // certified upper bound of |d'(t)|
  double size = 0;         // >= the query's size as Options::tolerance measures it
};

// sqrt(x2) in double, to within a few ulps where it is a double: where x2
// falls below the normal doubles (as a double subnormal, with few bits, or
// 0, while its root is still a normal double or a subnormal one) from x2
// scaled by 2^1200 (fuzz_query_kernels found the nudging below running for
// ever from such estimates).
inline double root_estimate(const Rational& x2) {
  const double x = x2.get_d();
  if (x >= std::numeric_limits<double>::min()) return std::sqrt(x);
  Rational scaled;
  mpq_mul_2exp(scaled.get_mpq_t(), x2.get_mpq_t(), 1200);
  return std::ldexp(std::sqrt(scaled.get_d()), -600);
}

// Certified bounds of sqrt(x2) (x2 exact): the double is nudged until the
// exact square agrees, each step at least one ulp (a subnormal times
// 1 +- 2^-40 rounds back to itself). Beyond the doubles' range (x2 above
// about 2^1024, lengths of queries scaled by 2^500): sqrt(DBL_MAX) below,
// +inf above (a Rational of an infinite double would trap inside GMP).
inline double sqrt_below(const Rational& x2) {
  if (sgn(x2) <= 0) return 0;
  double r = root_estimate(x2) * (1 - 0x1p-40);
  if (!std::isfinite(r)) r = std::sqrt(std::numeric_limits<double>::max()) * (1 - 0x1p-40);
  while (Rational(r) * Rational(r) > x2) {
    const double shrunk = r * (1 - 0x1p-40);
    r = shrunk < r ? shrunk : std::nextafter(r, 0.0);
  }
  return r;
}
inline double sqrt_above(const Rational& x2) {
  if (sgn(x2) <= 0) return 0;
  double r = std::max(root_estimate(x2) * (1 + 0x1p-40), std::numeric_limits<double>::denorm_min());
  if (!std::isfinite(r)) return std::numeric_limits<double>::infinity();
  while (Rational(r) * Rational(r) < x2) {
    const double grown = r * (1 + 0x1p-40);
    r = grown > r ? grown : std::nextafter(r, std::numeric_limits<double>::infinity());
    if (!std::isfinite(r)) return r;
  }
  return r;
}

// d(t) moves no faster than the largest relative velocity of a vertex of one
// primitive against one of the other (points of the primitives move with
// convex combinations of their vertices' velocities).
inline double lipschitz_bound(Kind kind, const Query& q) {
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

inline double query_size(const Query& q) {
  double size = 0;
  for (const Vec3& p : q.points)
    for (const Vec3& r : q.points) size = std::max(size, (p - r).cwiseAbs().maxCoeff());
  return size;
}

inline double distance_in_double(Kind kind, const Query& q, double t) {
  std::array<reference::Point<double>, 4> x;
  for (int k = 0; k < 4; ++k)
    for (int axis = 0; axis < 3; ++axis)
      x[k][axis] = q.points[k][axis] + t * (q.points[k + 4][axis] - q.points[k][axis]);
  return std::sqrt(reference::squared_distance(kind == Kind::vertex_face, x));
}

struct DistanceInterval {
  double a, da, b, db;  // the ends and the distance (or its lower bound) there
};

// Times where the double distance is <= D, earliest first: a left-first
// Lipschitz search that keeps refining before its earliest find. Only
// candidates for a witness; nothing here is trusted.
inline std::vector<double> witness_candidates(Kind kind, const Query& q, double separation, double m) {
  const double d0 = distance_in_double(kind, q, 0), d1 = distance_in_double(kind, q, 1);
  if (d0 <= separation) return {0.0};
  std::vector<double> found;
  double earliest = 2;
  if (d1 <= separation) {
    found.push_back(1);
    earliest = 1;
  }
  std::vector<DistanceInterval> stack{{0, d0, 1, d1}};
  for (int samples = 2; !stack.empty() && samples < kSearchSamples;) {
    const DistanceInterval i = stack.back();
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
inline void certify(Kind kind, const Query& q, double separation, Labelled& out) {
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
  std::vector<DistanceInterval> stack{{0, l0, 1, l1}};
  for (int samples = 2; !stack.empty();) {
    const DistanceInterval i = stack.back();
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

inline Labelled label(Kind kind, const Query& q, double separation) {
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
  if (std::isfinite(out.lipschitz)) certify(kind, q, separation, out);  // else no cone clears anything
  return out;
}

}  // namespace batchccd::testing

#include "reference/planar_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "reference/ball.hpp"

namespace batchccd::reference {
namespace {

// Below this width an interval is not split again: the signs are too close
// to call in double, and the exact stage takes over.
constexpr double kSmallestWidth = 0x1p-45;
// Intervals examined before the search gives up (a bound; typical queries
// need a handful).
constexpr int kIntervalBudget = 512;

struct Point2 {
  Ball x, y;
};
struct Point3 {
  Ball x, y, z;
};

Point2 operator-(const Point2& a, const Point2& b) { return {a.x - b.x, a.y - b.y}; }
Point3 operator-(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

// a x b, the z component of the 3D cross product.
Ball cross(const Point2& a, const Point2& b) { return a.x * b.y - a.y * b.x; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

Ball dot(const Point2& a, const Point2& b) { return a.x * b.x + a.y * b.y; }
Ball dot(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// (1 - t) start + t end, coordinate by coordinate.
Point2 mix(const Ball& rest, const Ball& time, const Point2& start, const Point2& end) {
  return {rest * start.x + time * end.x, rest * start.y + time * end.y};
}
Point3 mix(const Ball& rest, const Ball& time, const Point3& start, const Point3& end) {
  return {rest * start.x + time * end.x, rest * start.y + time * end.y, rest * start.z + time * end.z};
}

// The query in the frame of x1 (at the origin), x2..x4 moving from [0] to
// [1]: projected on a plane (Point2) or as it is (Point3).
template <class Point>
struct Motion {
  std::array<std::array<Point, 2>, 3> relative;

  // x_{i+2}(t) for an exact time t in [0, 1].
  Point at(int i, double t) const {
    if (t == 0) return relative[i][0];  // the step's ends need no arithmetic
    if (t == 1) return relative[i][1];
    const Ball time{t, 0};
    return mix(Ball{1, 0} - time, time, relative[i][0], relative[i][1]);
  }
};
using PlanarMotion = Motion<Point2>;

// A scaled coordinate as a ball: one rounding and the frame's absolute error.
Ball scaled_ball(const ScaledQuery& query, double value) {
  return Ball{value, kUnitRoundoff * std::fabs(value) + query.absolute_error};
}

Motion<Point3> spatial(const ScaledQuery& query) {
  Motion<Point3> motion;
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau) {
      const Vec3& v = query.relative[i][tau];
      motion.relative[i][tau] = {scaled_ball(query, v[0]), scaled_ball(query, v[1]), scaled_ball(query, v[2])};
    }
  return motion;
}

PlanarMotion project(const ScaledQuery& query, int axis) {
  const int first = (axis + 1) % 3, second = (axis + 2) % 3;
  PlanarMotion motion;
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau) {
      const Vec3& v = query.relative[i][tau];
      motion.relative[i][tau] = {scaled_ball(query, v[first]), scaled_ball(query, v[second])};
    }
  return motion;
}

// The contact conditions are signs of products of two vectors spanned by
// the points (x1 = origin, a = x2, b = x3, c = x4 relative to it): cross
// products (orientations) and dot products (order along a line).
struct Factor {
  Point2 u, v;
  bool dot = false;
};
inline Ball product(const Point2& u, const Point2& v, bool is_dot) { return is_dot ? dot(u, v) : cross(u, v); }
Ball value(const Factor& factor) { return product(factor.u, factor.v, factor.dot); }

constexpr int kConditions = 4;
using Factors = std::array<Factor, kConditions>;

Factors factors(PlanarShape shape, const Point2& a, const Point2& b, const Point2& c) {
  const Point2 origin{};
  switch (shape) {
    case PlanarShape::triangle_vertex:  // orient(x1, x2, p), orient(x2, x3, p), orient(x3, x1, p)
      return {Factor{a, c}, Factor{b - a, c - a}, Factor{c, b}, Factor{}};
    case PlanarShape::segments:  // orient(x1, x2, x3), orient(x1, x2, x4); orient(x3, x4, x1), orient(x3, x4, x2)
      return {Factor{a, b}, Factor{a, c}, Factor{b, c}, Factor{c - b, a - b}};
    case PlanarShape::vertex_segment:  // p = x1 against x3 x4: on its line, between its ends
      return {Factor{b, c}, Factor{origin - b, c - b, true}, Factor{origin - c, b - c, true}, Factor{}};
    case PlanarShape::segment_vertex:  // x1 x2 against p = x3
      return {Factor{a, b}, Factor{b, a, true}, Factor{b - a, origin - a, true}, Factor{}};
    case PlanarShape::vertices:  // p = x1 against q = x3: both coordinates of q - p
      return {Factor{b, Point2{{1, 0}, {0, 0}}, true}, Factor{b, Point2{{0, 0}, {1, 0}}, true}, Factor{}, Factor{}};
  }
  return {};
}

int condition_count(PlanarShape shape) {
  switch (shape) {
    case PlanarShape::segments: return 4;
    case PlanarShape::vertices: return 2;
    default: return 3;
  }
}

// The same products as quadratics in t over an interval, in Bernstein form
// with the middle coefficient doubled (same signs): with U, V linear
// between their values at the interval's ends, U(t) * V(t) is
// (1-s)^2 U0*V0 + (1-s)s (U0*V1 + U1*V0) + s^2 U1*V1.
struct Quadratic {
  Ball start, middle, end;
};
using Quadratics = std::array<Quadratic, kConditions>;

Quadratic quadratic(const Factor& s, const Factor& e) {
  return {product(s.u, s.v, s.dot), product(s.u, e.v, s.dot) + product(e.u, s.v, s.dot), product(e.u, e.v, s.dot)};
}

// +1 or -1 where the sign is certain over the whole interval, else 0.
int sign_over(const Quadratic& q) {
  if (q.start.certainly_positive() && q.middle.certainly_positive() && q.end.certainly_positive()) return 1;
  if (q.start.certainly_negative() && q.middle.certainly_negative() && q.end.certainly_negative()) return -1;
  return 0;
}

int sign_of(const Ball& value) {
  return value.certainly_positive() ? 1 : (value.certainly_negative() ? -1 : 0);
}

// What the signs over an interval say: the conditions for a contact there,
// as "sign * orientation[index] >= 0" left to hold.
struct Requirement {
  int index = 0;
  int sign = 0;
};
struct Reading {
  bool excluded = false;      // no contact in the interval
  bool undetermined = false;  // too little is certain: split
  int requirements = 0;       // how many conditions remain (when neither above)
  Requirement requirement;    // the one, when requirements == 1
};

Reading read_signs(PlanarShape shape, const std::array<int, kConditions>& sign,
                   const std::array<int, kConditions>& at_start, const std::array<int, kConditions>& at_end) {
  Reading reading;
  const auto require = [&](int index, int required_sign) {
    if (reading.requirements++ == 0) reading.requirement = {index, required_sign};
  };
  switch (shape) {
    case PlanarShape::triangle_vertex: {
      // Inside the closed triangle: all three orientations of one sign (or 0).
      int known = 0;
      for (int i = 0; i < 3; ++i) {
        if (sign[i] == 0) continue;
        if (known != 0 && sign[i] != known) {
          reading.excluded = true;  // strictly outside: one edge each way
          return reading;
        }
        known = sign[i];
      }
      if (known == 0) {
        reading.undetermined = true;
        return reading;
      }
      for (int i = 0; i < 3; ++i)
        if (sign[i] == 0) require(i, known);
      return reading;
    }
    case PlanarShape::segments:
      // The segments meet: each one's ends on opposite sides of the other's
      // line (or on it). Of two disjoint segments not on one line, one line
      // always strictly separates the other segment.
      for (int pair = 0; pair < 2; ++pair) {
        const int first = sign[2 * pair], second = sign[2 * pair + 1];
        if (first != 0 && second != 0) {
          if (first == second) {
            reading.excluded = true;
            return reading;
          }
        } else if (first != 0) {
          require(2 * pair + 1, -first);
        } else if (second != 0) {
          require(2 * pair, -second);
        } else {
          reading.undetermined = true;
        }
      }
      return reading;
    case PlanarShape::vertex_segment:
    case PlanarShape::segment_vertex:
      // On the segment: on its line, and not beyond either end.
      if (sign[0] != 0 || sign[1] < 0 || sign[2] < 0) {
        reading.excluded = true;
        return reading;
      }
      // Between the ends throughout and crossing the line once: there.
      if (sign[1] > 0 && sign[2] > 0 && at_start[0] != 0 && at_end[0] == -at_start[0]) {
        require(0, -at_start[0]);
        return reading;
      }
      reading.undetermined = true;
      return reading;
    case PlanarShape::vertices:
      // Two points meet only where both coordinates agree: never certain.
      reading.excluded = sign[0] != 0 || sign[1] != 0;
      reading.undetermined = !reading.excluded;
      return reading;
  }
  return reading;
}

// A contact at one time, certain: VF strictly inside, EE a proper crossing.
// A point on a segment, or on another point, is never certain in signs.
bool certain_contact(PlanarShape shape, const std::array<int, kConditions>& sign) {
  if (shape == PlanarShape::triangle_vertex) return sign[0] != 0 && sign[0] == sign[1] && sign[1] == sign[2];
  if (shape == PlanarShape::segments) return sign[0] * sign[1] == -1 && sign[2] * sign[3] == -1;
  return false;
}

// The root in (0, 1) of (1-s)^2 c0 + 2 s (1-s) c1 + s^2 c2 with c0 < 0 <
// c2 (an estimate: the bracket around it is what is certified).
double quadratic_root(double c0, double c1, double c2) {
  const double a = c0 - 2 * c1 + c2, b = 2 * (c1 - c0), c = c0;
  double root = 0.5;
  if (std::fabs(a) <= 1e-12 * (std::fabs(b) + std::fabs(c))) {
    root = -c / b;
  } else {
    const double discriminant = std::max(0.0, b * b - 4 * a * c);
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    const double r1 = q / a, r2 = q != 0 ? c / q : 0.5;
    root = (r1 >= 0 && r1 <= 1) ? r1 : r2;
  }
  return std::isfinite(root) ? std::min(1.0, std::max(0.0, root)) : 0.5;
}

// What examining one interval found: a certain outcome (a contact at its
// start, a bracketed first contact, or nothing), or that it must be split.
struct Step {
  std::optional<PlanarOutcome> outcome;
  bool split = false;
  bool excluded() const { return !outcome && !split; }
};

// Dyadic intervals of [0, 1], earliest first, each examined by
// `examine(start, end)`, down to kSmallestWidth and within kIntervalBudget.
// The whole step whatever tmax: the intervals, and so the TOI, do not
// depend on it (a shrinking window gives every query the TOI it gets alone).
// A contact counts when its first time is certainly at most tmax; one
// certainly after tmax is a miss; one whose bracket straddles tmax is left
// uncertain.
template <class Examine>
PlanarOutcome search_intervals(const Examine& examine, double tmax) {
  struct Interval {
    double start, end;
  };
  std::array<Interval, 48> stack;  // depth first: at most one pending half a level, 45 levels
  int pending = 0;
  stack[pending++] = {0, 1};
  for (int budget = kIntervalBudget; pending > 0; --budget) {
    if (budget == 0) return {};
    const Interval interval = stack[--pending];
    if (interval.start > tmax) break;  // the earliest left: nothing later counts
    const Step step = examine(interval.start, interval.end);
    if (step.outcome) {
      const PlanarOutcome& outcome = *step.outcome;
      if (!outcome.hit || outcome.toi_upper <= tmax) return outcome;
      if (outcome.toi > tmax) return {true, false, 0, 0};
      return {};
    }
    if (!step.split) continue;
    if (interval.end - interval.start <= kSmallestWidth) return {};
    const double middle = 0.5 * (interval.start + interval.end);
    stack[pending++] = {middle, interval.end};
    stack[pending++] = {interval.start, middle};
  }
  return {true, false, 0, 0};  // every interval excluded
}

// A time in (start, end) bracketed to width: f(low) certainly negative (or
// low = start) and f(high) certainly positive (or high = end), probing
// around the estimate `t` of f's one root there.
template <class Signed>
std::optional<PlanarOutcome> bracket_root(const Signed& f, double t, double start, double end, double toi_width) {
  for (double width = toi_width / 64; width <= toi_width / 2; width *= 4) {
    const double low = std::max(start, t - width), high = std::min(end, t + width);
    if (low < high && (low == start || f(low).certainly_negative()) && (high == end || f(high).certainly_positive()))
      return PlanarOutcome{true, true, low, high};
  }
  return std::nullopt;
}

class PlanarSearch {
 public:
  PlanarSearch(PlanarShape shape, const PlanarMotion& motion, double toi_width)
      : shape_(shape), motion_(motion), toi_width_(toi_width) {}

  PlanarOutcome run(double tmax) const {
    return search_intervals([this](double start, double end) { return examine(start, end); }, tmax);
  }

  Step examine(double start, double end) const {
    const Factors at_start = factors_at(start), at_end = factors_at(end);
    Quadratics q;
    std::array<int, kConditions> over{}, first{}, last{};
    for (int i = 0; i < condition_count(shape_); ++i) {
      q[i] = quadratic(at_start[i], at_end[i]);
      over[i] = sign_over(q[i]);
      first[i] = sign_of(q[i].start);
      last[i] = sign_of(q[i].end);
    }
    // Every earlier interval holds no contact: one at `start` is the first.
    if (certain_contact(shape_, first)) return {PlanarOutcome{true, true, start, start}, false};
    const Reading reading = read_signs(shape_, over, first, last);
    if (reading.excluded) return {};
    if (reading.undetermined || reading.requirements > 1) return {std::nullopt, true};
    if (reading.requirements == 0) return {PlanarOutcome{true, true, start, start}, false};
    return single_condition(reading.requirement, q[reading.requirement.index], start, end);
  }

 private:
  std::array<Point2, 3> points_at(double t) const {
    return {motion_.at(0, t), motion_.at(1, t), motion_.at(2, t)};
  }

  Ball condition_at(int index, double t) const { return value(factors_at(t)[index]); }

  Factors factors_at(double t) const {
    const std::array<Point2, 3> p = points_at(t);
    return factors(shape_, p[0], p[1], p[2]);
  }

  // The one condition left, f = sign * q >= 0, the others certain over
  // [start, end]: its first point in the interval is the first contact.
  Step single_condition(const Requirement& requirement, const Quadratic& q, double start, double end) const {
    const double sign = requirement.sign;
    const auto signed_ball = [sign](const Ball& value) { return Ball{sign * value.middle, value.radius}; };
    const Ball f0 = signed_ball(q.start), f2 = signed_ball(q.end);
    if (f0.certainly_positive()) return {PlanarOutcome{true, true, start, start}, false};
    if (!(f0.certainly_negative() && f2.certainly_positive())) return {std::nullopt, true};
    // One root in (start, end): f rises through it once.
    const double root = quadratic_root(f0.middle, sign * 0.5 * q.middle.middle, f2.middle);
    const double t = start + root * (end - start);
    const auto f = [&](double time) { return signed_ball(condition_at(requirement.index, time)); };
    if (auto bracket = bracket_root(f, t, start, end, toi_width_)) return {bracket, false};
    return {std::nullopt, true};
  }

  PlanarShape shape_;
  const PlanarMotion& motion_;
  double toi_width_;
};

// The quartic U(t) * V(t) of two quadratics over an interval, from their
// scaled Bernstein coefficients (Quadratic: the middle one doubled): its
// Bernstein coefficients each times a positive constant (1, 4, 6, 4, 1),
// the same for every quartic, so a sum of them keeps its signs.
using Quartic = std::array<Ball, 5>;

Quartic times(const Quadratic& u, const Quadratic& v) {
  return {u.start * v.start, u.start * v.middle + u.middle * v.start,
          u.start * v.end + u.middle * v.middle + u.end * v.start, u.middle * v.end + u.end * v.middle,
          u.end * v.end};
}

// A quadratic as the quartic it is: times the constant 1.
Quartic elevated(const Quadratic& q) { return times(q, Quadratic{{1, 0}, {2, 0}, {1, 0}}); }

// u(t).v(t) over an interval, u and v linear with values u0, v0 at its
// start and u1, v1 at its end (Quadratic's scaled Bernstein form).
template <class Point>
Quadratic dot_over(const Point& u0, const Point& v0, const Point& u1, const Point& v1) {
  return {dot(u0, v0), dot(u0, v1) + dot(u1, v0), dot(u1, v1)};
}

// |u(t) x v(t)|^2 over an interval, as dot_over.
Quartic squared_cross_over(const Point2& u0, const Point2& v0, const Point2& u1, const Point2& v1) {
  const Quadratic c{cross(u0, v0), cross(u0, v1) + cross(u1, v0), cross(u1, v1)};
  return times(c, c);
}
Quartic squared_cross_over(const Point3& u0, const Point3& v0, const Point3& u1, const Point3& v1) {
  const Point3 start = cross(u0, v0), end = cross(u1, v1), middle_a = cross(u0, v1), middle_b = cross(u1, v0);
  Quartic sum;
  for (Ball Point3::*axis : {&Point3::x, &Point3::y, &Point3::z}) {
    const Quadratic c{start.*axis, middle_a.*axis + middle_b.*axis, end.*axis};
    const Quartic square = times(c, c);
    for (int k = 0; k < 5; ++k) sum[k] = sum[k] + square[k];
  }
  return sum;
}

// A condition "f(t) >= 0" over an interval: f's scaled Bernstein
// coefficients (3 of a quadratic, 5 of a quartic).
struct Condition {
  std::array<Ball, 5> coefficient;
  int degree = 2;

  static Condition of(const Quadratic& q) { return {{q.start, q.middle, q.end}, 2}; }
  static Condition of(const Quartic& q) { return {q, 4}; }
  const Ball& first() const { return coefficient[0]; }
  // +1 where f is certainly positive over the whole interval, -1 certainly
  // negative, else 0 (Bernstein coefficients bound the polynomial).
  int sign_over() const {
    bool positive = true, negative = true;
    for (int k = 0; k <= degree; ++k) {
      positive &= coefficient[k].certainly_positive();
      negative &= coefficient[k].certainly_negative();
    }
    return positive ? 1 : (negative ? -1 : 0);
  }
  // f < 0 at the start, f > 0 at the end and one sign change among the
  // coefficients: exactly one root inside, where f turns positive
  // (Descartes' rule in Bernstein form).
  bool rises_once() const {
    int previous = -1, changes = 0;
    for (int k = 0; k <= degree; ++k) {
      const int sign = sign_of(coefficient[k]);
      if (sign == 0) return false;
      changes += sign != previous;
      previous = sign;
    }
    return coefficient[0].certainly_negative() && changes == 1;
  }
  // Its root in (0, 1), estimated in double (the bracket is what is
  // certified): bisection on the sign of de Casteljau's value.
  double root_estimate() const {
    // The true Bernstein coefficients from the scaled ones, by degree.
    static constexpr double kQuadratic[5] = {1, 0.5, 1}, kQuartic[5] = {1, 0.25, 1.0 / 6, 0.25, 1};
    const double* scale = degree == 2 ? kQuadratic : kQuartic;
    double c[5] = {};
    for (int k = 0; k <= degree; ++k) c[k] = coefficient[k].middle * scale[k];
    const auto at = [&](double s) {
      double b[5];
      std::copy(c, c + degree + 1, b);
      for (int level = degree; level > 0; --level)
        for (int k = 0; k < level; ++k) b[k] = (1 - s) * b[k] + s * b[k + 1];
      return b[0];
    };
    double low = 0, high = 1;
    for (int i = 0; i < 60 && high - low > 0x1p-52; ++i) {
      const double middle = 0.5 * (low + high);
      (at(middle) < 0 ? low : high) = middle;
    }
    return 0.5 * (low + high);
  }
};

// Planar motion with a separation d (min_distance > 0), in a plane the
// projection maps isometrically (an axis plane: a coordinate all points
// share); or, in 3D, a point against a segment or a point, at any d >= 0.
// The primitives come within d when they meet (PlanarSearch) or
// when a vertex of one comes within d of a segment of the other: of two
// disjoint convex polygons (points and segments included) the closest pair
// is a vertex and an edge. A point p and a segment [A, B] are within d when
//   |p - A|^2 <= d^2, or |p - B|^2 <= d^2, or
//   (p - A).(B - A) >= 0, (p - B).(A - B) >= 0 and ((B - A) x (p - A))^2 <= d^2 |B - A|^2
// (the last with |B - A| > 0 for a witness), quadratics and a quartic in t.
// Intervals earliest first as PlanarSearch's: a contact at an interval's
// start is certain when one of these holds there with certainty; an
// interval is excluded when each fails throughout; where a single
// condition is left to change sign, its root is bracketed.
template <class Point>
class DistanceSearch {
 public:
  // `meeting`: the search for the primitives meeting (VF and EE in a
  // plane), nullptr where the pairs cover it (a point against the rest).
  DistanceSearch(PlanarShape shape, const Motion<Point>& motion, const PlanarSearch* meeting, double separation,
                 double toi_width)
      : shape_(shape), motion_(motion), meeting_(meeting), toi_width_(toi_width),
        squared_separation_(Ball{separation, 0} * Ball{separation, 0}) {}

  PlanarOutcome run(double tmax) const {
    return search_intervals([this](double start, double end) { return examine(start, end); }, tmax);
  }

 private:
  // A vertex (point index: 0 = x1 at the origin, 1..3 = x2..x4) against a
  // segment between two of them (equal for a point), and which of its
  // clauses to test (bit j: kClauses[j]): a pair of vertices is tested once
  // (a triangle's corner ends two of its edges; an end of one segment meets
  // each end of the other in two pairs).
  struct Pair {
    int point = 0, end0 = 0, end1 = 0;
    unsigned clauses = 0;
  };
  static constexpr int kMostPairs = 4;
  static constexpr int kConditionsPerPair = 6;  // |p-A|, |p-B|, the two dots, the quartic, reach
  static constexpr unsigned kNearA = 1, kNearB = 2, kOnLine = 4;

  int pairs(std::array<Pair, kMostPairs>& pair) const {
    switch (shape_) {
      case PlanarShape::triangle_vertex:  // the vertex x4 against the triangle's edges
        pair = {Pair{3, 0, 1, kNearA | kOnLine}, Pair{3, 1, 2, kNearA | kOnLine}, Pair{3, 2, 0, kNearA | kOnLine},
                Pair{}};
        return 3;
      case PlanarShape::segments:  // each end against the other segment
        pair = {Pair{0, 2, 3, kNearA | kNearB | kOnLine}, Pair{1, 2, 3, kNearA | kNearB | kOnLine},
                Pair{2, 0, 1, kOnLine}, Pair{3, 0, 1, kOnLine}};
        return 4;
      case PlanarShape::vertex_segment: pair[0] = {0, 2, 3, kNearA | kNearB | kOnLine}; return 1;
      case PlanarShape::segment_vertex: pair[0] = {2, 0, 1, kNearA | kNearB | kOnLine}; return 1;
      case PlanarShape::vertices: pair[0] = {0, 2, 2, kNearA}; return 1;
    }
    return 0;
  }

  std::array<Point, 4> points_at(double t) const {
    return {Point{}, motion_.at(0, t), motion_.at(1, t), motion_.at(2, t)};
  }

  // A pair's conditions over [start, end] (s and e: the points at its
  // ends), each "f >= 0", computed when first asked for: 0 the point within
  // d of A, 1 of B, 2 and 3 beyond neither end, 4 within d of the line, 5
  // within sqrt(d^2 + |B - A|^2) of A (implied by 2, 3 and 4 together).
  class PairConditions {
   public:
    PairConditions(const Pair& pair, const std::array<Point, 4>& s, const std::array<Point, 4>& e,
                   const Ball& squared_separation)
        : pair_(pair), s_(s), e_(e), squared_separation_(squared_separation) {}

    const Condition& f(int k) {
      if (!(known_ >> k & 1)) {
        f_[k] = compute(k);
        known_ |= 1 << k;
      }
      return f_[k];
    }

    // |B - A|^2 (after f(4)).
    const Quadratic& length() const { return length_; }

   private:
    // (x_to - x_from).(x_to2 - x_from2) over the interval.
    Quadratic dot_of(int from, int to, int from2, int to2) const {
      return dot_over(s_[to] - s_[from], s_[to2] - s_[from2], e_[to] - e_[from], e_[to2] - e_[from2]);
    }
    Quadratic within(int end) const {  // d^2 - |p - end|^2
      const Quadratic distance = dot_of(end, pair_.point, end, pair_.point);
      const Ball& d2 = squared_separation_;
      return {d2 - distance.start, (d2 + d2) - distance.middle, d2 - distance.end};
    }
    Condition compute(int k) {
      const int p = pair_.point, a = pair_.end0, b = pair_.end1;
      switch (k) {
        case 0: return Condition::of(within(a));
        case 1: return Condition::of(within(b));
        case 2: return Condition::of(dot_of(a, p, a, b));
        case 3: return Condition::of(dot_of(b, p, b, a));
        case 5: {  // d^2 + |B - A|^2 - |p - A|^2
          const Quadratic near = within(a), ends = dot_of(a, b, a, b);
          return Condition::of(Quadratic{near.start + ends.start, near.middle + ends.middle, near.end + ends.end});
        }
        default: {
          length_ = dot_of(a, b, a, b);
          const Quartic on_line = squared_cross_over(s_[b] - s_[a], s_[p] - s_[a], e_[b] - e_[a], e_[p] - e_[a]);
          const Quartic reach = elevated(length_);
          Quartic f;
          for (int i = 0; i < 5; ++i) f[i] = squared_separation_ * reach[i] - on_line[i];
          return Condition::of(f);
        }
      }
    }

    Pair pair_;
    const std::array<Point, 4>& s_;
    const std::array<Point, 4>& e_;
    const Ball& squared_separation_;
    std::array<Condition, kConditionsPerPair> f_;
    Quadratic length_;
    unsigned known_ = 0;
  };

  // The clauses of a pair, conjunctions of its conditions: near A {0},
  // near B {1}, on the line between the ends {2, 3, 4}. Cheap conditions
  // first: a clause is excluded by its first condition certainly negative
  // throughout.
  static constexpr std::array<std::array<int, 3>, 3> kClauses{{{0, -1, -1}, {1, -1, -1}, {2, 3, 4}}};

  Step examine(double start, double end) const {
    // Meeting (distance 0): VF inside, EE crossing. A point's contacts with
    // a segment or a point are within every d: the pairs cover them.
    Step meeting;
    if (meeting_ != nullptr) {
      meeting = meeting_->examine(start, end);
      if (meeting.outcome && meeting.outcome->toi == start) return meeting;  // at the start: the first
    }
    const std::array<Point, 4> s = points_at(start), e = points_at(end);
    std::array<Pair, kMostPairs> pair;
    const int count = pairs(pair);
    int open = meeting.excluded() ? 0 : 1;  // what may hold somewhere in the interval
    std::optional<Uncertain> rising;          // the one open clause's one uncertain condition
    for (int i = 0; i < count; ++i) {
      PairConditions c(pair[i], s, e, squared_separation_);
      for (int j = 0; j < 3; ++j) {
        if (!(pair[i].clauses >> j & 1)) continue;
        // Within d of the line between the ends, p is within
        // sqrt(d^2 + |B - A|^2) of A: where it certainly is not, the clause
        // fails, also where its own conditions all vanish (B = A, a segment
        // of zero length at an interval's end).
        const bool on_line = j == 2;
        if (on_line && c.f(5).sign_over() < 0) continue;
        bool holds_at_start = true, excluded = false;
        int uncertain = 0, which = -1;
        for (const int k : kClauses[j]) {
          if (k < 0) continue;
          const Condition& f = c.f(k);
          const int sign = f.sign_over();
          if (sign < 0) {
            excluded = true;
            break;
          }
          holds_at_start &= f.first().certainly_positive();
          if (sign == 0) ++uncertain, which = k;
        }
        if (excluded) continue;
        // A witness on the line needs |B - A| > 0.
        if (holds_at_start && (!on_line || c.length().start.certainly_positive()))
          return {PlanarOutcome{true, true, start, start}, false};
        const bool simple = uncertain == 1 && c.f(which).rises_once() && (!on_line || sign_over(c.length()) > 0);
        rising = ++open == 1 && simple ? std::optional<Uncertain>({i, which, c.f(which)}) : std::nullopt;
      }
    }
    if (open == 0) return {};
    if (open == 1 && !meeting.excluded()) return meeting;  // the meeting alone: its own answer
    if (open == 1 && rising) {
      // Before its root the clause fails and so does everything else; from
      // it on, the clause holds: the first contact.
      const Pair& p = pair[rising->pair];
      const int k = rising->condition;
      const double t = start + rising->f.root_estimate() * (end - start);
      const auto at = [&](double time) {
        const std::array<Point, 4> x = points_at(time);
        return PairConditions(p, x, x, squared_separation_).f(k).first();
      };
      if (auto bracket = bracket_root(at, t, start, end, toi_width_)) return {bracket, false};
    }
    return {std::nullopt, true};
  }

  struct Uncertain {
    int pair, condition;
    Condition f;  // over the interval
  };

  PlanarShape shape_;
  const Motion<Point>& motion_;
  const PlanarSearch* meeting_;
  double toi_width_;
  Ball squared_separation_;
};

}  // namespace

PlanarOutcome solve_planar(PlanarShape shape, const ScaledQuery& query, int axis, double tmax,
                           double toi_width) {
  const PlanarMotion motion = project(query, axis);
  return PlanarSearch(shape, motion, toi_width).run(tmax);
}

PlanarOutcome solve_planar_within(PlanarShape shape, const ScaledQuery& query, int axis, double separation,
                                  double tmax, double toi_width) {
  const PlanarMotion motion = project(query, axis);
  const bool meets = shape == PlanarShape::triangle_vertex || shape == PlanarShape::segments;
  const PlanarSearch meeting(shape, motion, toi_width);
  return DistanceSearch<Point2>(shape, motion, meets ? &meeting : nullptr, separation, toi_width).run(tmax);
}

PlanarOutcome solve_point_within(PlanarShape shape, const ScaledQuery& query, double separation, double tmax,
                                 double toi_width) {
  const Motion<Point3> motion = spatial(query);
  return DistanceSearch<Point3>(shape, motion, nullptr, separation, toi_width).run(tmax);
}

}  // namespace batchccd::reference

namespace batchccd::reference {

PlanarShape planar_shape(Kind kind, const Query& query) {
  if (kind == Kind::vertex_face) return PlanarShape::triangle_vertex;
  const auto& p = query.points;
  const bool a_is_point = p[0] == p[1] && p[4] == p[5], b_is_point = p[2] == p[3] && p[6] == p[7];
  if (a_is_point && b_is_point) return PlanarShape::vertices;
  if (a_is_point) return PlanarShape::vertex_segment;
  if (b_is_point) return PlanarShape::segment_vertex;
  return PlanarShape::segments;
}

}  // namespace batchccd::reference

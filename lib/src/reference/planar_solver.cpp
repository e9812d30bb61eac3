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

Point2 operator-(const Point2& a, const Point2& b) { return {a.x - b.x, a.y - b.y}; }

// a x b, the z component of the 3D cross product.
Ball cross(const Point2& a, const Point2& b) { return a.x * b.y - a.y * b.x; }

// The projected query: x1 at the origin, x2..x4 moving from [0] to [1].
struct PlanarMotion {
  std::array<std::array<Point2, 2>, 3> relative;

  // x_{i+2}(t) for an exact time t in [0, 1].
  Point2 at(int i, double t) const {
    if (t == 0) return relative[i][0];  // the step's ends need no arithmetic
    if (t == 1) return relative[i][1];
    const Ball time{t, 0};
    const Ball rest = Ball{1, 0} - time;
    const Point2& start = relative[i][0];
    const Point2& end = relative[i][1];
    return {rest * start.x + time * end.x, rest * start.y + time * end.y};
  }
};

PlanarMotion project(const ScaledQuery& query, int axis) {
  const int first = (axis + 1) % 3, second = (axis + 2) % 3;
  PlanarMotion motion;
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau) {
      const Vec3& v = query.relative[i][tau];
      const auto ball = [&](double value) {
        return Ball{value, kUnitRoundoff * std::fabs(value) + query.absolute_error};
      };
      motion.relative[i][tau] = {ball(v[first]), ball(v[second])};
    }
  return motion;
}

Ball dot(const Point2& a, const Point2& b) { return a.x * b.x + a.y * b.y; }

// The contact conditions are signs of products of two vectors spanned by
// the points (x1 = origin, a = x2, b = x3, c = x4 relative to it): cross
// products (orientations) and dot products (order along a line).
struct Factor {
  Point2 u, v;
  bool dot = false;
};
Ball product(const Point2& u, const Point2& v, bool is_dot) { return is_dot ? dot(u, v) : cross(u, v); }
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

class PlanarSearch {
 public:
  PlanarSearch(PlanarShape shape, const PlanarMotion& motion, double toi_width)
      : shape_(shape), motion_(motion), toi_width_(toi_width) {}

  PlanarOutcome run(double tmax) {
    struct Interval {
      double start, end;
    };
    std::array<Interval, 48> stack;  // depth first: at most one pending half a level, 45 levels
    int pending = 0;
    // The whole step, whatever tmax: the intervals, and so the TOI, do not
    // depend on it (a shrinking window gives every query the TOI it gets alone).
    stack[pending++] = {0, 1};
    for (int budget = kIntervalBudget; pending > 0; --budget) {
      if (budget == 0) return {};
      const Interval interval = stack[--pending];
      if (interval.start > tmax) break;  // the earliest left: nothing later counts
      const Step step = examine(interval.start, interval.end);
      if (step.outcome) return within(*step.outcome, tmax);
      if (!step.split) continue;
      if (interval.end - interval.start <= kSmallestWidth) return {};
      const double middle = 0.5 * (interval.start + interval.end);
      stack[pending++] = {middle, interval.end};
      stack[pending++] = {interval.start, middle};
    }
    return {true, false, 0, 0};  // every interval excluded
  }

 private:
  struct Step {
    std::optional<PlanarOutcome> outcome;
    bool split = false;
  };

  std::array<Point2, 3> points_at(double t) const {
    return {motion_.at(0, t), motion_.at(1, t), motion_.at(2, t)};
  }

  Ball condition_at(int index, double t) const { return value(factors_at(t)[index]); }

  Factors factors_at(double t) const {
    const std::array<Point2, 3> p = points_at(t);
    return factors(shape_, p[0], p[1], p[2]);
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

  // A contact counts when its first time is certainly at most tmax; one
  // certainly after tmax is a miss; one whose bracket straddles tmax is left
  // to the exact stage.
  static PlanarOutcome within(const PlanarOutcome& outcome, double tmax) {
    if (!outcome.hit || outcome.toi_upper <= tmax) return outcome;
    if (outcome.toi > tmax) return {true, false, 0, 0};
    return {};
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
    for (double width = toi_width_ / 64; width <= toi_width_ / 2; width *= 4) {
      const double low = std::max(start, t - width), high = std::min(end, t + width);
      if (low < high && (low == start || f(low).certainly_negative()) &&
          (high == end || f(high).certainly_positive()))
        return {PlanarOutcome{true, true, low, high}, false};
    }
    return {std::nullopt, true};
  }

  // The root in (0, 1) of (1-s)^2 c0 + 2 s (1-s) c1 + s^2 c2 with c0 < 0 <
  // c2 (an estimate: the bracket around it is what is certified).
  static double quadratic_root(double c0, double c1, double c2) {
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

  PlanarShape shape_;
  const PlanarMotion& motion_;
  double toi_width_;
};

}  // namespace

PlanarOutcome solve_planar(PlanarShape shape, const ScaledQuery& query, int axis, double tmax,
                           double toi_width) {
  const PlanarMotion motion = project(query, axis);
  return PlanarSearch(shape, motion, toi_width).run(tmax);
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

#include "reference/inclusion_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/filter.hpp"
#include "reference/inside_proof.hpp"
#include "reference/separation_filter.hpp"
#include "reference/sign_filter.hpp"
#include "reference/turning_gap.hpp"

namespace batchccd::reference {
namespace {

// Parameters are never split below this width: dyadic boxes stay exact and
// (1 - t), 1 - v and u + v never round.
constexpr double kSmallestWidth = 0x1p-45;

// Time intervals wider than this search the parameters with a small budget,
// then (when the cubic certainly has a root there) narrow on its signs.
constexpr double kWideInterval = 0x1p-8;
constexpr std::int64_t kWideBudget = 16;
constexpr std::int64_t kWideDistanceBudget = 1;  // with a minimum separation

// The parts of a plain-double estimate of how far the primitives stay apart
// that a step tries to certify, longest first: all but a sliver (close to
// a contact, where the estimate is nearly exact, the step then lands
// within a hair of it), else 1/16 short of it.
constexpr double kReachFractions[] = {1 - 0x1p-10, 0.9375};

// How near its estimated reach (in time) the plane step tries the first
// of kReachFractions, all but a sliver of the way.
constexpr double kNearReach = 0x1p-4;

// The step of conservative advancement from which it also tries a
// direction that turns with the closest pair (cleared_turning), when the
// steps shrink by less than half each: before it, the other steps nearly
// always suffice, and the turning step costs about five of theirs.
constexpr int kTurningFromStep = 12;

// x rounded down to the 2^-45 grid (kSmallestWidth) the steps' interval
// ends lie on: exact, as the grid is a power of two.
double down_to_grid(double x) { return std::floor(x / kSmallestWidth) * kSmallestWidth; }

// The part `fraction` of the way from t to `reach` (not past 1), on the grid.
double step_length(double t, double reach, double fraction) {
  return down_to_grid(std::min(1.0, t + (reach - t) * fraction) - t);
}

// Where f, positive and falling at t (value h, derivative slope there),
// reaches 0: up to four Newton steps from t in plain double, kept within
// [t, 1]. f(s, slope) returns f(s) and sets slope to f'(s).
template <class Function>
double newton_reach(const Function& f, double t, double h, double slope) {
  double reach = t;
  for (int iteration = 0; iteration < 4 && slope < 0 && std::isfinite(h); ++iteration) {
    reach = std::clamp(reach - h / slope, t, 1.0);
    if (iteration < 3) h = f(reach, slope);
  }
  return reach;
}

struct Interval {
  double low, high;
  double width() const { return high - low; }
  double middle() const { return 0.5 * (low + high); }
};

// Earliest start first: a min-heap on the time interval's start.
bool starts_later(const Interval& a, const Interval& b) { return a.low > b.low; }

struct ParameterBox {
  Interval u, v;
};

using V3 = Vector3<double>;

V3 as_vector(const Vec3& v) { return {v[0], v[1], v[2]}; }
V3 absolute(const V3& v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }
V3 largest(const V3& a, const V3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
V3 interpolate(const V3& a, const V3& b, double t) {
  const double s = 1 - t;
  return {s * a.x + t * b.x, s * a.y + t * b.y, s * a.z + t * b.z};
}
V3 weighted_sum(const std::array<double, 3>& w, const std::array<V3, 3>& p) {
  return {w[0] * p[0].x + w[1] * p[1].x + w[2] * p[2].x,
          w[0] * p[0].y + w[1] * p[1].y + w[2] * p[2].y,
          w[0] * p[0].z + w[1] * p[1].z + w[2] * p[2].z};
}
double component(const V3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

// F = sum_i w_i * relative_i in the frame of x1 (see ScaledQuery):
//   VF: p - a - u (b - a) - v (c - a)            -> weights (-u, -v, 1)
//   EE: ea0 + u (ea1 - ea0) - eb0 - v (eb1 - eb0) -> weights (u, v - 1, -v)
std::array<double, 3> weights(Kind kind, double u, double v) {
  if (kind == Kind::vertex_face) return {-u, -v, 1.0};
  return {u, v - 1, -v};
}

// found: within tolerance; witnessed (minimum separation only): a point of
// contact certainly within min_distance.
enum class Search { excluded, found, witnessed, unresolved, out_of_iterations };

// The positions x2..x4 (relative to x1) and their magnitudes at both ends
// of a time interval.
struct Endpoints {
  std::array<V3, 3> position[2];
  std::array<V3, 3> magnitude[2];
};

class InclusionSolver {
 public:
  InclusionSolver(Kind kind, const ScaledQuery& query, const SolverSettings& settings)
      : kind_(kind), settings_(settings) {
    // The floor first: std::max keeps it against a NaN as well.
    settings_.toi_tolerance = std::max(kSmallestWidth, settings_.toi_tolerance);
    if (settings_.pieces != 2 && settings_.pieces != 4 && settings_.pieces != 8) {  // not dyadic pieces: none
      settings_.pieces = 1;
      settings_.free_pieces = 0;
    }
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) {
        position_[i][tau] = as_vector(query.relative[i][tau]);
        magnitude_[i][tau] = absolute(position_[i][tau]);
      }
    for (int i = 0; i < 3; ++i) reach_[i] = largest(magnitude_[i][0], magnitude_[i][1]);
    if (settings.certified) {
      cubic_error_ = interpolated_coefficient_error(query.absolute_error);
      function_error_ = collision_function_error(query.absolute_error);
    }
    // A separation raised to 2^-1022 (to_scaled_length) cannot witness a contact.
    absolute_error_ = query.absolute_error;
    witness_distance_ = settings.min_distance > 0x1p-1022 ? settings.min_distance : 0;
  }

  // Outer search over time, earliest interval first, so the first interval
  // settled as a contact starts no later than the first contact.
  SolverOutcome run() {
    std::vector<Interval>& heap = time_heap();
    if (settings_.free_pieces == 0) heap.assign(1, Interval{0, 1});
    else push_open_pieces(heap);
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), starts_later);
      Interval time = heap.back();
      heap.pop_back();
      if (time.low > settings_.tmax) break;  // the earliest left: nothing later counts
      if (settings_.min_distance > 0) {
        if (const std::optional<SolverOutcome> outcome = search_within_distance(time)) return *outcome;
        continue;
      }
      const Endpoints ends = endpoints(time);
      const CubicSigns cubic = cubic_signs(ends);
      if (cubic.root_free) continue;
      const bool wide = time.width() > kWideInterval;
      if (cubic.certain_root && wide) {
        // The cubic's signs alone narrow a wide interval to its first root,
        // far cheaper than any proof or search over all of it. What they
        // drop before it is root-free, so contact-free; what follows it
        // waits its turn, unless the halves it was cut from were root-free.
        const Narrowed narrowed = narrow_to_first_root(time, kWideInterval, cubic.halved);
        if (narrowed.first.width() < time.width()) {
          push(heap, narrowed.first);
          if (!narrowed.rest_root_free && narrowed.first.high < time.high)
            push(heap, Interval{narrowed.first.high, time.high});
          continue;
        }
      }
      // Over a narrow interval the positions' balls are tight: coplanar
      // somewhere in it, but where the projections certainly miss
      // throughout, it holds no contact and needs no search.
      const bool prove = !wide || cubic.certain_root;
      const PositionBalls balls = prove ? position_balls(ends) : PositionBalls{};
      if (!wide && certainly_outside(kind_, balls)) continue;
      const bool settled = time.width() <= settings_.toi_tolerance || !settings_.need_toi;
      // A certain root and a certain inside test over the interval: a
      // contact lies in it, no need to search the parameters.
      const bool contact = cubic.certain_root && certainly_inside(kind_, balls);
      if (!contact && cubic.certain_root && time.width() > settings_.toi_tolerance) {
        // A certain root the inside test cannot settle (a contact at an
        // edge's end, say): the cubic's signs narrow the interval to its
        // first root first. Searched at every halving instead, the
        // parameters could neither exclude such a contact nor find it (the
        // interval's motion keeps their image wide) and spent the budget.
        const Narrowed narrowed = narrow_to_first_root(time, settings_.toi_tolerance, cubic.halved);
        if (narrowed.first.width() < time.width()) {
          push(heap, narrowed.first);
          if (!narrowed.rest_root_free && narrowed.first.high < time.high)
            push(heap, Interval{narrowed.first.high, time.high});
          continue;
        }
      }
      if (!contact) {
        // Wide intervals get a small parameter budget: their search mostly
        // ends unresolved, and splitting time is cheaper.
        const std::int64_t budget = time.width() > kWideInterval ? kWideBudget : settings_.max_iterations;
        const Search search =
            search_parameters(ends, budget, settings_.tolerance * std::min(1.0, size_over(ends)));
        if (search == Search::excluded) continue;
        if (search == Search::out_of_iterations) return {true, time.low, true, false};
        if (search == Search::found && settled)
          return {.hit = true, .toi = time.low, .within_tolerance = true};
      } else {
        // A certain contact: the inside test holds over all of `time`, so
        // the cubic alone narrows it to its first root, much cheaper than
        // the search below, which goes on only when the signs get too close
        // to call first.
        // Located also when it may lie after tmax, to tell whether it counts.
        const bool locate = settings_.need_toi || time.high > settings_.tmax;
        if (locate) time = narrow_to_first_root(time, settings_.toi_tolerance, cubic.halved).first;
        if (time.width() <= settings_.toi_tolerance || !locate) return certain_contact(time);
        // Certified: the signs got too close to call first (a multiple
        // root, slow relative motion). The first contact is still the
        // cubic's first root in `time`: returned as such (toi_upper), for
        // the caller to locate exactly. Searching on would stop at the
        // first box within tolerance, which for a root of multiplicity k
        // lies about tolerance^(1/k) before it. Not while the interval is
        // wide: there it is mostly a root at the halving point (a zero
        // sign there), which the search locates at once in floating point.
        if (settings_.certified && settings_.need_toi && time.width() <= kWideInterval)
          return certain_contact(time);
      }
      if (time.width() <= kSmallestWidth) return {true, time.low, false, false};  // nothing left to refine
      split(time);
    }
    return {false, 0, false, settings_.certified};  // every time excluded
  }

 private:
  // The parts of the step the filters left open (SolverSettings::
  // free_pieces), each run of open pieces as the fewest aligned dyadic
  // intervals: halving those keeps every end on the grid, and a run
  // searched as one interval advances in long steps.
  void push_open_pieces(std::vector<Interval>& heap) const {
    heap.clear();
    const int pieces = settings_.pieces;
    const auto open = [&](int j) { return j < pieces && !(settings_.free_pieces >> j & 1); };
    for (int j = 0; j < pieces;) {
      if (!open(j)) {
        ++j;
        continue;
      }
      // The longest aligned block from j, all open: j a multiple of its length.
      int length = 1;
      while (j % (2 * length) == 0 && j + 2 * length <= pieces) {
        bool all_open = true;
        for (int k = j + length; k < j + 2 * length; ++k) all_open = all_open && open(k);
        if (!all_open) break;
        length *= 2;
      }
      push(heap, Interval{double(j) / pieces, double(j + length) / pieces});
      j += length;
    }
  }

  static void split(const Interval& time) {
    push(time_heap(), Interval{time.low, time.middle()});
    push(time_heap(), Interval{time.middle(), time.high});
  }

  // One time interval of the search with a minimum separation: its outcome,
  // or nothing when it was excluded or split. A contact found in an interval
  // not yet toi_tolerance wide splits it: the first contact may lie earlier.
  std::optional<SolverOutcome> search_within_distance(const Interval& time) {
    // Conservative advancement first: where it gets to a contact it
    // settles the query, and the times it passes need no search. Its first
    // step along the closest direction at the start nearly always does
    // what the one at the middle would; only an interval it does not start
    // (its start already advanced past) takes the middle's, below.
    const bool started = time.low < advanced_;
    if (!started && advance(time.low, std::min(time.high, settings_.tmax)))
      return SolverOutcome{true, advanced_, false, settings_.certified};
    // Every time up to advanced_ is free of contact, tmax included: nothing
    // after it counts, and searching the intervals that straddle it (down
    // to a width near tmax, log2(1 / tmax) halvings with a shrinking
    // window's small tmax) would only find what does not count.
    if (advanced_ >= settings_.tmax) return SolverOutcome{false, 0, false, settings_.certified};
    if (time.high <= advanced_) return std::nullopt;
    // Where advancement stopped short: the interval's ends, for the tests below.
    const Endpoints ends = endpoints(time);
    if ((started && separated_along_closest(time, ends)) || apart_over(ends)) return std::nullopt;
    const bool settled = time.width() <= settings_.toi_tolerance || !settings_.need_toi;
    // A wide interval gets one box: where conservative advancement stalled,
    // its boxes seldom settle anything before time is split.
    const std::int64_t budget = time.width() > kWideInterval ? kWideDistanceBudget : settings_.max_iterations;
    const Search search = search_parameters(ends, budget, settings_.tolerance);
    if (search == Search::excluded) return std::nullopt;
    // Every time before `start` is free of contact.
    const double start = std::max(time.low, advanced_);
    if (search == Search::out_of_iterations) return SolverOutcome{true, start, true, false};
    if (search == Search::witnessed) {
      // A contact at the middle: the first one lies in [start, middle].
      // Advancing conservatively from start usually locates it to
      // toi_tolerance at once; otherwise the search goes on from there.
      if (!settled && advance(start, std::min(time.middle(), settings_.tmax)))
        return SolverOutcome{true, advanced_, false, settings_.certified};
      const bool certain = settings_.certified && time.middle() <= settings_.tmax;
      if (settled || time.middle() - advanced_ <= settings_.toi_tolerance)
        return SolverOutcome{true, std::max(start, advanced_), false, certain};
    }
    if (search == Search::found && settled) {
      // Within the tolerance of a contact: the TOI. The decision is certain
      // when a contact follows, as it does where the primitives go on closer.
      const bool proven = settings_.certified && witness_after(start);
      return SolverOutcome{.hit = true, .toi = start, .certain = proven, .within_tolerance = !proven};
    }
    if (time.width() <= kSmallestWidth) return SolverOutcome{true, start, false, false};
    split(time);
    return std::nullopt;
  }

  // Whether one direction keeps the primitives more than min_distance apart
  // over the whole interval: the vector between their closest points at its
  // middle (docs/design.md §11). Along a direction n every point's
  // projection is linear in t, so the gap between the nearer side's lowest
  // and the other side's highest projection is concave in t and smallest
  // at an end of the interval: checking both ends, with the projections'
  // rounding bounded, clears all of it. Most survivors at a separation are
  // primitives sliding past each other, which this clears in a few
  // halvings where boxes of (t, u, v) take hundreds.
  bool separated_along_closest(const Interval& time, const Endpoints& ends) const {
    const std::optional<V3> n = closest_direction(time.middle());
    return n && separated_along(*n, ends);
  }

  // The positions x2..x4 at time t and the primitives' closest parameters
  // there, found in plain double.
  struct ClosestAt {
    std::array<V3, 3> position;
    std::array<double, 2> parameters;
    // Inside both primitives (VF: the triangle's interior; EE: both edges'),
    // where the distance is the plane's or the lines' (cleared_by_plane).
    bool interior(Kind kind) const {
      const auto [u, v] = parameters;
      return kind == Kind::vertex_face ? u > 0 && v > 0 && u + v < 1 : u > 0 && u < 1 && v > 0 && v < 1;
    }
  };
  ClosestAt closest_at(double t) const {
    ClosestAt closest;
    for (int i = 0; i < 3; ++i) closest.position[i] = interpolate(position_[i][0], position_[i][1], t);
    closest.parameters = closest_parameters(closest.position);
    return closest;
  }

  // F at the primitives' closest parameters (any direction serves
  // separated_along): none when it vanishes.
  std::optional<V3> closest_direction(const ClosestAt& closest) const {
    const auto [u, v] = closest.parameters;
    const V3 n = weighted_sum(weights(kind_, u, v), closest.position);  // VF: towards the vertex; EE: towards edge a
    const double length2 = dot(n, n);
    if (!(length2 > 0) || !std::isfinite(length2)) return std::nullopt;
    return n;
  }
  std::optional<V3> closest_direction(double t) const { return closest_direction(closest_at(t)); }

  // A direction n with what separated_along needs of it beyond the
  // positions: the threshold min_distance |n| and each point's projection
  // error. A projection's error is the interpolated position's (3 u of its
  // magnitude) and the dot product's (3 u), bounded by 8 u of n's magnitude
  // against reach_ (which bounds the position's magnitude at every time of
  // the step), plus the scaled frame's absolute error in each coordinate.
  struct Separating {
    V3 n;
    double threshold;
    double error[3];
  };
  std::optional<Separating> separating(const V3& n) const {
    const double length = std::sqrt(dot(n, n)) * (1 + 8 * kUnitRoundoff);
    if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
    const V3 magnitude = absolute(n);
    const double weight = magnitude.x + magnitude.y + magnitude.z;
    const double floor = settings_.certified ? weight * (absolute_error_ + 0x1p-1073) + kUnderflowFloor : 0;
    const double relative = settings_.certified ? 8 * kUnitRoundoff : 0;
    Separating direction{n, settings_.min_distance * length * (1 + 4 * kUnitRoundoff) + kUnderflowFloor, {}};
    for (int i = 0; i < 3; ++i) direction.error[i] = relative * dot(magnitude, reach_[i]) + floor;
    return direction;
  }

  // Whether the gap along the direction between the two primitives exceeds
  // min_distance |n| for the positions x2..x4 of one time. Points of the
  // side n points to ("upper") and of the other: VF the vertex x4 over the
  // triangle x1 = 0, x2, x3; EE edge a (0, x2) over edge b (x3, x4).
  bool separated_at(const Separating& direction, const std::array<V3, 3>& position) const {
    const bool vertex_face = kind_ == Kind::vertex_face;
    double upper_lowest = vertex_face ? std::numeric_limits<double>::infinity() : 0.0;
    double lower_highest = vertex_face ? 0.0 : -std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      const double projection = dot(direction.n, position[i]);
      const bool upper = vertex_face ? i == 2 : i == 0;
      if (upper) upper_lowest = std::min(upper_lowest, projection - direction.error[i]);
      else lower_highest = std::max(lower_highest, projection + direction.error[i]);
    }
    const double gap = (upper_lowest - lower_highest) * (1 - 4 * kUnitRoundoff);
    return gap > direction.threshold;
  }

  // Whether the gap along n exceeds min_distance |n| at both ends of the
  // interval `ends` holds, so (the gap being concave in t) throughout it.
  bool separated_along(const V3& n, const Endpoints& ends) const {
    const std::optional<Separating> direction = separating(n);
    return direction && separated_at(*direction, ends.position[0]) && separated_at(*direction, ends.position[1]);
  }

  std::array<V3, 3> positions_at(double t) const {
    std::array<V3, 3> position;
    for (int i = 0; i < 3; ++i) position[i] = interpolate(position_[i][0], position_[i][1], t);
    return position;
  }

  // How far from t (on the 2^-45 grid) the closest direction at t keeps
  // the primitives apart: along a fixed n each point's projection moves
  // linearly, so the gap between an upper and a lower point reaches
  // min_distance |n| at a time found in plain double; a little before the
  // earliest of those, separated_at certifies the interval (and the step
  // stops at `until`), or t is returned. Where the primitives slide past
  // each other the motion along n is a small part of m, and this step is
  // that much longer than conservative advancement's.
  double cleared_along_closest(double t, double until, const ClosestAt& closest) const {
    if (down_to_grid(t) != t) return t;  // off the grid: interpolation not bounded
    const std::optional<V3> n = closest_direction(closest);
    if (!n) return t;
    const std::optional<Separating> direction = separating(*n);
    if (!direction || !separated_at(*direction, closest.position)) return t;
    const double separation = settings_.min_distance * std::sqrt(dot(*n, *n));
    const bool vertex_face = kind_ == Kind::vertex_face;
    // Projections at t and their rates (x1, the origin, stays at 0).
    double at[4] = {0, 0, 0, 0}, rate[4] = {0, 0, 0, 0};
    for (int i = 0; i < 3; ++i) {
      at[i + 1] = dot(*n, closest.position[i]);
      rate[i + 1] = dot(*n, position_[i][1]) - dot(*n, position_[i][0]);
    }
    // Points 0..3 are x1..x4, pairs (upper, lower): VF upper {3}, lower
    // {0, 1, 2} (its last pair repeated); EE upper {0, 1}, lower {2, 3}.
    static constexpr int kPairs[2][4][2] = {{{3, 0}, {3, 1}, {3, 2}, {3, 2}}, {{0, 2}, {0, 3}, {1, 2}, {1, 3}}};
    double reach = std::numeric_limits<double>::infinity();
    for (const auto& [upper, lower] : kPairs[vertex_face ? 0 : 1]) {
      const double gap = at[upper] - at[lower] - separation, closing = rate[lower] - rate[upper];
      if (!(gap > 0)) return t;
      if (closing > 0) reach = std::min(reach, t + gap / closing);
    }
    // Nearly all the way to the plain-double reach, else 1/16 short of it
    // for separated_at's margins (the gap, concave, is certified at both
    // ends; t's above). Certified up to `end` whatever `until`, which only
    // caps the step: the steps towards a contact are the same for every
    // tmax beyond it, as conservative advancement's are (docs/design.md §12).
    double tried = t;
    for (const double fraction : kReachFractions) {
      const double end = std::min(1.0, t + down_to_grid((reach - t) * fraction));
      if (!(end > t)) return t;
      if (end == tried) continue;
      if (separated_at(*direction, positions_at(end))) return std::min(end, until);
      tried = end;
    }
    return t;
  }

  // How far from t (on the 2^-45 grid) the distance to the triangle's plane
  // (VF) or between the edges' lines (EE), |V| / |n| with n = a x b and V
  // the coplanarity cubic n . c, stays above min_distance. It bounds the
  // primitives' distance from below, and equals it while their closest
  // points lie inside both (docs/design.md §11): where a triangle or an edge
  // turns, a fixed direction's gap shrinks as fast as its farthest vertex
  // moves, this one only as fast as the distance. Newton's steps on
  // h = |V| - min_distance |n| from t, in plain double, estimate where it
  // reaches min_distance; 15/16 of the way there (on the grid), the sign
  // test with a separation, with the normal's Euclidean length, certifies
  // the interval (plane_distance_culls), or a half, quarter or eighth of it,
  // or t is returned. Certified up to its end whatever `until`, as
  // cleared_along_closest is. `sliver_failed`: the approach's state (see
  // below), false at its first step.
  double cleared_by_plane(double t, double until, const ClosestAt& closest, bool& sliver_failed) const {
    if (down_to_grid(t) != t) return t;  // off the grid: interpolation not bounded
    // a, b, c at time 0 and their rates: VF x21, x31, x41; EE x21, x43, x31.
    const bool vertex_face = kind_ == Kind::vertex_face;
    const V3 a0 = position_[0][0], b0 = vertex_face ? position_[1][0] : position_[2][0] - position_[1][0];
    const V3 c0 = vertex_face ? position_[2][0] : position_[1][0];
    const V3 a1 = position_[0][1], b1 = vertex_face ? position_[1][1] : position_[2][1] - position_[1][1];
    const V3 c1 = vertex_face ? position_[2][1] : position_[1][1];
    const V3 da = a1 - a0, db = b1 - b0, dc = c1 - c0;
    const double separation = settings_.min_distance;
    // h and its derivative at s.
    const auto h_at = [&](double s, double& slope) {
      const auto at = [s](const V3& p, const V3& d) { return V3{p.x + s * d.x, p.y + s * d.y, p.z + s * d.z}; };
      const V3 a = at(a0, da), b = at(b0, db), c = at(c0, dc);
      const V3 n = cross(a, b), dn = cross(da, b) + cross(a, db);
      const double v = dot(n, c), dv = dot(dn, c) + dot(n, dc), length = std::sqrt(dot(n, n));
      slope = (v < 0 ? -dv : dv) - separation * dot(n, dn) / length;
      return std::fabs(v) - separation * length;
    };
    double slope = 0;
    const double h = h_at(t, slope);
    if (!(h > 0)) return t;
    // Moving apart at t: the whole step, if nothing turns it.
    const double reach = slope < 0 ? newton_reach(h_at, t, h, slope) : 1;
    // Close to a contact the estimate is nearly exact: all but a sliver of
    // it first, within kNearReach of it. Farther, the coefficients' hull is
    // loose where the plane turns: 15/16 of it, then shorter intervals
    // (halved up to three times) fit it closer. Where the sliver failed
    // once that close, h meets the separation too shallowly for the hull
    // and it fails at every later step of the approach: not tried again.
    const auto length_of = [&](double fraction) { return step_length(t, reach, fraction); };
    const auto apart_for = [&](double length) { return plane_apart(closest.position, positions_at(t + length)); };
    const double nearly_all = length_of(kReachFractions[0]);
    double length = length_of(kReachFractions[1]);
    if (!sliver_failed && nearly_all > length && reach - t <= kNearReach) {
      if (apart_for(nearly_all)) return std::min(t + nearly_all, until);
      sliver_failed = true;
    }
    for (int attempt = 0; attempt < 4 && length > 0; ++attempt, length = down_to_grid(length * 0.5))
      if (apart_for(length)) return std::min(t + length, until);
    return t;
  }

  // How far from t (on the 2^-45 grid) a direction turning with the
  // closest pair keeps the primitives apart (docs/design.md §11). Where
  // the closest pair lies on an edge or a corner of a turning primitive,
  // any fixed direction's gap shrinks as fast as that primitive's far
  // vertex moves, the plane's is no bound, and the two steps above crawl.
  // Newton's steps on the plain-double distance |F| at the closest
  // parameters estimate where it reaches min_distance (its slope there is
  // F . dF/dt / |F|, the parameters held); n(s), linear from the closest
  // direction at t to the one at the interval's end e, then keeps every
  // upper-lower pair's gap n(s) . (x_upper(s) - x_lower(s)) -- a quadratic
  // in s -- above min_distance |n(s)| when its three Bernstein
  // coefficients exceed min_distance max(|n(t)|, |n(e)|) (turning_apart,
  // turning_gap.hpp). Certified up to e whatever `until`, as the other
  // steps are.
  double cleared_turning(double t, double until, const ClosestAt& closest) const {
    if (down_to_grid(t) != t) return t;  // off the grid: interpolation not bounded
    const std::optional<V3> start_direction = closest_direction(closest);
    if (!start_direction) return t;
    const double separation = settings_.min_distance;
    std::array<V3, 3> rate;
    for (int i = 0; i < 3; ++i) rate[i] = position_[i][1] - position_[i][0];
    // |F| - min_distance and its slope at s, the parameters closest there.
    const auto distance_at = [&](const ClosestAt& at, double& slope) {
      const std::array<double, 3> w = weights(kind_, at.parameters[0], at.parameters[1]);
      const V3 f = weighted_sum(w, at.position), df = weighted_sum(w, rate);
      const double length = std::sqrt(dot(f, f));
      slope = dot(f, df) / length;
      return length - separation;
    };
    double slope = 0;
    const double h = distance_at(closest, slope);
    if (!(h > 0)) return t;
    const auto distance_from_closest = [&](double s, double& slope_at) { return distance_at(closest_at(s), slope_at); };
    // Moving apart at t: the whole step, if nothing turns it.
    const double reach = slope < 0 ? newton_reach(distance_from_closest, t, h, slope) : 1;
    const auto length_of = [&](double fraction) { return step_length(t, reach, fraction); };
    double length = length_of(kReachFractions[0]);
    for (int attempt = 0; attempt < 3 && length > 0; ++attempt) {
      const double end = t + length;
      const ClosestAt far = closest_at(end);
      if (const std::optional<V3> end_direction = closest_direction(far);
          end_direction && turning_apart(kind_, *start_direction, closest.position, *end_direction, far.position,
                                         reach_, absolute_error_, settings_.min_distance, settings_.certified))
        return std::min(end, until);
      length = attempt == 0 ? std::min(length_of(kReachFractions[1]), down_to_grid(length * 0.5))
                            : down_to_grid(length * 0.5);
    }
    return t;
  }

  // Whether a witness stands at one of the times toi_tolerance, twice that,
  // four times that, ... after `start`, up to tmax.
  bool witness_after(double start) const {
    const double end = down_to_grid(std::min(settings_.tmax, 1.0));
    for (double step = std::max(down_to_grid(settings_.toi_tolerance), kSmallestWidth);; step *= 2) {
      const double t = std::min(start + step, end);  // on the grid: exact
      if (witnessed_at(t)) return true;
      if (t >= end) return false;
    }
  }

  // Conservative advancement (docs/design.md §11): the distance changes by
  // at most m (the largest relative displacement) per unit of time, so at a
  // distance d > s at time t no contact comes before t + (d - s) / m; along
  // the closest direction often much later (cleared_along_closest), and a
  // step takes the longer of the two. Steps
  // from `from` towards `until` while they get anywhere, on a 2^-45 grid
  // (dyadic times keep the interpolation's error bound), and records how far
  // the times are free of contact. Once its steps get shorter than
  // toi_tolerance it looks for a pair of points certainly within s at most
  // toi_tolerance ahead (where it stops, at the time itself): a contact
  // there locates the first one, and it returns true.
  bool advance(double from, double until) {
    constexpr int kSteps = 64;
    const SeparationErrorModel error = separation_error(absolute_error_, settings_.certified);
    if (!error.enabled) return false;
    constexpr double shrink = SeparationErrors::shrink;
    double t = from, previous_step = 0;
    bool sliver_failed = false;  // cleared_by_plane's state over this approach
    for (int step = 0; step < kSteps && t < until; ++step) {
      // Along the closest direction a step often clears all the way (and
      // then t itself holds no contact).
      const ClosestAt closest = closest_at(t);
      double cleared = cleared_along_closest(t, until, closest);
      if (cleared < until && closest.interior(kind_))
        cleared = std::max(cleared, cleared_by_plane(t, until, closest, sliver_failed));
      // Many steps already, each at least half the one before (towards a
      // contact they shrink fast): the closest pair may lie on an edge or a
      // corner that turns, which neither step above follows.
      if (cleared < until && step >= kTurningFromStep && (cleared - t) * 2 >= previous_step)
        cleared = std::max(cleared, cleared_turning(t, until, closest));
      if (cleared >= until) {
        t = until;
        break;
      }
      // A step that cleared anything cleared t itself, and outruns m's
      // nearly always: the certified distance, the dearest part of a step,
      // only where neither did.
      double step_length = cleared - t;
      if (!(step_length > 0)) {
        Vector3<double> at_t[3][2];
        for (int i = 0; i < 3; ++i) at_t[i][0] = at_t[i][1] = closest.position[i];
        const double distance = std::sqrt(distance2_at(kind_, at_t, 0, error.relative, error.floor)) * shrink;
        const double gap = (distance - settings_.min_distance * SeparationErrors::grow) * shrink;
        if (!(gap > 0)) {
          advanced_ = std::max(advanced_, t);
          return witnessed(t, closest);
        }
        // Whole grid steps: t is on the grid, so the sum is exact. Without
        // relative motion (the fast baseline's m may be 0) the whole way.
        step_length = down_to_grid(gap / motion() * shrink);
      }
      const double next = std::min(t + step_length, until);
      if (step_length < settings_.toi_tolerance) {
        const double ahead = std::min(t + down_to_grid(settings_.toi_tolerance), until);
        if (ahead > t && witnessed_at(ahead)) {
          advanced_ = std::max(advanced_, next);
          return true;
        }
      } else if (step_length * (1 - kReachFractions[0]) < settings_.toi_tolerance && next < until) {
        // A step that went nearly all the way to a contact left less than
        // toi_tolerance of the way: a witness that far past `next` ends
        // the search a step early (a failed one costs a fraction of a step).
        const double ahead = std::min(next + down_to_grid(settings_.toi_tolerance), until);
        if (witnessed_at(ahead)) {
          advanced_ = std::max(advanced_, next);
          return true;
        }
      }
      if (next <= t) break;
      previous_step = next - t;
      t = next;
    }
    advanced_ = std::max(advanced_, t);
    return false;
  }

  // Whether the primitives are certainly within the separation at time t
  // (on the 2^-45 grid): F at their closest parameters, found in plain
  // double and put on the same grid (any parameters of the primitives bound
  // the distance from above), evaluated with error bounds.
  bool witnessed_at(double t) const { return witnessed(t, closest_at(t)); }
  // The same where the closest pair at t is known: F at that one point of
  // the primitives, bounded as evaluate bounds a box's centre (here all
  // eight corners are that point, their sum 8 F exactly).
  bool witnessed(double t, const ClosestAt& closest) const {
    const auto [u, v] = closest.parameters;
    std::array<double, 3> w = weights(kind_, down_to_grid(u), down_to_grid(v));
    const V3 value = weighted_sum(w, closest.position);
    for (double& x : w) x = std::fabs(x);
    std::array<V3, 3> magnitude;
    for (int i = 0; i < 3; ++i) magnitude[i] = interpolate(magnitude_[i][0], magnitude_[i][1], t);
    const V3 value_magnitude = weighted_sum(w, magnitude);
    const double error = function_error_at(std::max({value_magnitude.x, value_magnitude.y, value_magnitude.z}));
    const double largest = std::max({std::fabs(value.x), std::fabs(value.y), std::fabs(value.z)});
    return centre_distance_bound(V3{8 * value.x, 8 * value.y, 8 * value.z}, largest, error) <= witness_distance_;
  }

  // Parameters (u, v) of F's smallest value at one time, in plain double:
  // VF F = p - u b - v c over the triangle u, v >= 0, u + v <= 1; EE
  // F = u a1 - b0 - v (b1 - b0) over [0, 1]^2 (positions relative to x1).
  // Any parameters serve their callers (each step certifies what it takes
  // from them), so the closest ones are found the cheap way, by the
  // regions of the triangle or the clamped segment parameters (as in
  // Ericson, Real-Time Collision Detection, 5.1.5 and 5.1.9); where the
  // regions divide by zero (a degenerate triangle), by minimising over the
  // domain's inside and its sides.
  std::array<double, 2> closest_parameters(const std::array<V3, 3>& x) const {
    const std::array<double, 2> found =
        kind_ == Kind::vertex_face ? closest_on_triangle(x[0], x[1], x[2]) : closest_on_segments(x[0], x[1], x[2]);
    if (std::isfinite(found[0]) && std::isfinite(found[1])) return found;
    return closest_by_minimising(x);
  }

  // The point p's closest parameters on the triangle (0, b, c), by the
  // region p projects into; NaN where a degenerate triangle leaves a
  // division by zero.
  static std::array<double, 2> closest_on_triangle(const V3& b, const V3& c, const V3& p) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    const double d1 = dot(b, p), d2 = dot(c, p);
    if (d1 <= 0 && d2 <= 0) return {0, 0};  // the corner at the origin
    const V3 from_b = p - b;
    const double d3 = dot(b, from_b), d4 = dot(c, from_b);
    if (d3 >= 0 && d4 <= d3) return {1, 0};  // corner b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return {d1 / (d1 - d3), 0};  // side 0b
    const V3 from_c = p - c;
    const double d5 = dot(b, from_c), d6 = dot(c, from_c);
    if (d6 >= 0 && d5 <= d6) return {0, 1};  // corner c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return {0, d2 / (d2 - d6)};  // side 0c
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {  // side bc
      const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      return {1 - w, w};
    }
    const double sum = va + vb + vc;  // inside; the sum is |b x c|^2
    return sum > 0 ? std::array<double, 2>{vb / sum, vc / sum} : std::array<double, 2>{nan, nan};
  }

  // The closest parameters of the segments u a (from the origin) and
  // b0 + v (b1 - b0); a zero-length one is a point.
  static std::array<double, 2> closest_on_segments(const V3& a, const V3& b0, const V3& b1) {
    const V3 b = b1 - b0;
    const double aa = dot(a, a), bb = dot(b, b), b_from_a = -dot(b, b0);
    if (!(aa > 0) && !(bb > 0)) return {0, 0};
    if (!(aa > 0)) return {0, std::clamp(b_from_a / bb, 0.0, 1.0)};
    const double a_from_b = -dot(a, b0);
    if (!(bb > 0)) return {std::clamp(-a_from_b / aa, 0.0, 1.0), 0};
    const double ab = dot(a, b), determinant = aa * bb - ab * ab;
    // The lines' closest u, clamped (parallel: any u, 0), then v for it,
    // clamped, then u again for that v.
    double u = determinant > 0 ? std::clamp((ab * b_from_a - a_from_b * bb) / determinant, 0.0, 1.0) : 0.0;
    double v = (ab * u + b_from_a) / bb;
    if (v < 0) {
      v = 0;
      u = std::clamp(-a_from_b / aa, 0.0, 1.0);
    } else if (v > 1) {
      v = 1;
      u = std::clamp((ab - a_from_b) / aa, 0.0, 1.0);
    }
    return {u, v};
  }

  std::array<double, 2> closest_by_minimising(const std::array<V3, 3>& x) const {
    const std::array<double, 3> at_origin = weights(kind_, 0, 0);
    V3 direction[2];
    for (int d = 0; d < 2; ++d) {
      std::array<double, 3> w = weights(kind_, d == 0 ? 1 : 0, d == 1 ? 1 : 0);
      for (int i = 0; i < 3; ++i) w[i] -= at_origin[i];
      direction[d] = weighted_sum(w, x);
    }
    const V3 origin = weighted_sum(at_origin, x);
    const double aa = dot(direction[0], direction[0]), ab = dot(direction[0], direction[1]),
                 bb = dot(direction[1], direction[1]), ao = dot(direction[0], origin),
                 bo = dot(direction[1], origin), oo = dot(origin, origin), determinant = aa * bb - ab * ab;
    // |F|^2 = |origin + u direction_0 + v direction_1|^2, a convex quadratic.
    const auto value = [&](double u, double v) {
      return oo + 2 * (u * ao + v * bo) + u * (u * aa + 2 * v * ab) + v * v * bb;
    };
    const auto inside = [&](double u, double v) {
      return u >= 0 && v >= 0 && (kind_ == Kind::vertex_face ? u + v <= 1 : u <= 1 && v <= 1);
    };
    if (determinant > 0) {
      // Its unconstrained minimum: where it lies inside the domain, the answer.
      const double u = (ab * bo - bb * ao) / determinant, v = (ab * ao - aa * bo) / determinant;
      if (inside(u, v)) return {u, v};
    }
    // Else on the domain's boundary: where F is smallest along each side, clamped.
    std::array<double, 2> best{0, 0};
    double best_value = value(0, 0);
    const auto consider = [&](double u, double v) {
      u = std::clamp(u, 0.0, 1.0), v = std::clamp(v, 0.0, 1.0);
      if (kind_ == Kind::vertex_face && u + v > 1) v = 1 - u;
      if (const double f = value(u, v); f < best_value) best_value = f, best = {u, v};
    };
    // Along each side of the domain: u or v fixed at 0 or 1 (VF: the third side u + v = 1).
    if (aa > 0) consider(-ao / aa, 0), consider(-(ao + ab) / aa, 1);
    if (bb > 0) consider(0, -bo / bb), consider(1, -(bo + ab) / bb);
    if (kind_ == Kind::vertex_face) {
      const V3 side = direction[1] - direction[0];  // from (1, 0) towards (0, 1)
      const V3 at_corner = origin + direction[0];
      if (const double length2 = dot(side, side); length2 > 0) consider(1 + dot(side, at_corner) / length2, -dot(side, at_corner) / length2);
    }
    return best;
  }

  // The separation filter over one time interval (docs/design.md §11): the
  // motion within it is linear too, so the filter of the whole step holds
  // for the positions at its ends. Their interpolation adds 3 roundings to
  // the at most 21 the filter's 64 u bound.
  // The sign filter's form for a separation (the distance to the plane or
  // line pair) over the interval goes first, as the cubic's signs do
  // without one; its coefficients from interpolated positions.
  bool apart_over(const Endpoints& ends) const {
    if (plane_apart(ends)) return true;
    Vector3<double> relative[3][2];
    for (int i = 0; i < 3; ++i)
      for (int end = 0; end < 2; ++end) relative[i][end] = ends.position[end][i];
    const SeparationErrorModel error = separation_error(absolute_error_, settings_.certified);
    return error.enabled &&
           separation_filter_culls_within(kind_, relative, error.relative, error.floor, settings_.min_distance);
  }

  // The sign test with a separation over the interval, its coefficients
  // from interpolated positions, the normal's length bounded by its
  // Euclidean norm (sign_filter.hpp).
  bool plane_apart(const Endpoints& ends) const { return plane_apart(ends.position[0], ends.position[1]); }
  // The same from the positions at the interval's start and end.
  bool plane_apart(const std::array<V3, 3>& start, const std::array<V3, 3>& end) const {
    Vector3<double> relative[3][2];
    double largest[3][2];
    for (int i = 0; i < 3; ++i) {
      relative[i][0] = start[i];
      relative[i][1] = end[i];
      for (int e = 0; e < 2; ++e) largest[i][e] = largest_magnitude(relative[i][e]);
    }
    return plane_distance_culls(kind_, relative, largest, cubic_error_.floor, settings_.certified,
                                settings_.min_distance, cubic_error_.relative, true);
  }

  // The first contact lies in `time` at the cubic's first root there (a
  // certain root, a certain inside test over all of it, every earlier time
  // excluded): refined to refined_toi_width when asked.
  SolverOutcome certain_contact(Interval time) const {
    if (settings_.certified && settings_.need_toi && settings_.refined_toi_width > 0)
      time = narrow_to_first_root(time, settings_.refined_toi_width, halved_cubic(endpoints(time))).first;
    return {true, time.low, false, settings_.certified, time.high};
  }

  // The cubic's Bernstein coefficients over an interval, each within
  // `error` of the exact ones.
  struct HalvedCubic {
    double coefficient[4];
    double error;

    bool positive(int k) const { return coefficient[k] > error; }
    bool negative(int k) const { return coefficient[k] < -error; }
    bool root_free() const {
      const bool all_positive = positive(0) && positive(1) && positive(2) && positive(3);
      return all_positive || (negative(0) && negative(1) && negative(2) && negative(3));
    }
    bool certain_root() const { return (positive(0) && negative(3)) || (negative(0) && positive(3)); }

    // Each new coefficient is an average of averages (at most three
    // additions, each rounding by u of at most the largest coefficient;
    // halving is exact but for underflow), and averaging errors keeps
    // them: so the bound grows by 4 u of the largest plus the underflows.
    std::pair<HalvedCubic, HalvedCubic> halves() const {
      const double* c = coefficient;
      const double c01 = (c[0] + c[1]) * 0.5, c12 = (c[1] + c[2]) * 0.5, c23 = (c[2] + c[3]) * 0.5;
      const double c012 = (c01 + c12) * 0.5, c123 = (c12 + c23) * 0.5, middle = (c012 + c123) * 0.5;
      const double largest = std::max({std::fabs(c[0]), std::fabs(c[1]), std::fabs(c[2]), std::fabs(c[3])});
      const double grown = error + 4 * kUnitRoundoff * largest + 4 * 0x1p-1074;
      return {HalvedCubic{{c[0], c01, c012, middle}, grown}, HalvedCubic{{middle, c123, c23, c[3]}, grown}};
    }
  };

  // Narrows an interval with a certain root towards the cubic's first root
  // by halving on the cubic's signs alone: a root-free left half sends it
  // right, a certain sign change left, until `width` or a sign too close to
  // call. What it drops on the left is root-free; on the right, whatever
  // follows the returned interval.
  // The halves come from de Casteljau's averages of the interval's
  // coefficients rather than from positions interpolated anew: a fraction
  // of the work, for an error bound that grows by 4 u of the largest
  // coefficient a halving; once it has doubled, the coefficients are
  // computed afresh.
  // `cubic`: its coefficients over `time`.
  struct Narrowed {
    Interval first;
    bool rest_root_free;  // no root in the rest of the interval, after `first`
  };
  Narrowed narrow_to_first_root(Interval time, double width, HalvedCubic cubic) const {
    const double fresh_error = cubic.error;
    bool rest_root_free = true;
    while (time.width() > width) {
      if (cubic.error > 2 * fresh_error) cubic = halved_cubic(endpoints(time));
      const auto [left, right] = cubic.halves();
      if (left.root_free()) {
        time.low = time.middle();
        cubic = right;
      } else if (left.certain_root()) {
        rest_root_free = rest_root_free && right.root_free();
        time.high = time.middle();
        cubic = left;
      } else {
        break;
      }
    }
    return {time, rest_root_free};
  }


  HalvedCubic halved_cubic(const Endpoints& e) const { return halved_cubic(bernstein_over(e)); }
  BernsteinCubic<double> bernstein_over(const Endpoints& e) const {
    const auto& p = e.position;
    const auto& m = e.magnitude;
    BernsteinCubic<double> cubic = bernstein_cubic(p[0][0], p[1][0], p[0][1], p[1][1], p[0][2], p[1][2]);
    bernstein_magnitudes(cubic, m[0][0], m[1][0], m[0][1], m[1][1], m[0][2], m[1][2]);
    return cubic;
  }
  HalvedCubic halved_cubic(const BernsteinCubic<double>& cubic) const {
    // bernstein_cubic leaves out the binomial weights (1, 3, 3, 1): dividing
    // them out rounds by u at most.
    const double* c = cubic.coefficient;
    HalvedCubic halved{{c[0], c[1] / 3, c[2] / 3, c[3]}, 0};
    double largest = 0;
    for (int k = 0; k < 4; ++k) {
      halved.error = std::max(halved.error, cubic_error_.relative * cubic.magnitude[k] + cubic_error_.floor);
      largest = std::max(largest, std::fabs(c[k]));
    }
    halved.error += kUnitRoundoff * largest + 0x1p-1074;
    return halved;
  }

  struct Image {
    bool excluded = false;
    double width = 0;  // widest component range, error included
    // With a minimum separation: an upper bound of |F| at the box's centre.
    double centre_distance = INFINITY;
    // How much component `axis` of F changes along dimension d (0 t, 1 u, 2 v).
    double influence[3][3] = {};
  };

  static void push(std::vector<Interval>& heap, const Interval& time) {
    heap.push_back(time);
    std::push_heap(heap.begin(), heap.end(), starts_later);
  }

  static std::vector<Interval>& time_heap() {
    thread_local std::vector<Interval> buffer;
    return buffer;
  }
  static std::vector<ParameterBox>& parameter_stack() {
    thread_local std::vector<ParameterBox> buffer;
    return buffer;
  }

  Endpoints endpoints(const Interval& time) const {
    Endpoints ends;
    for (int end = 0; end < 2; ++end) {
      const double t = end == 0 ? time.low : time.high;
      for (int i = 0; i < 3; ++i) {
        ends.position[end][i] = interpolate(position_[i][0], position_[i][1], t);
        ends.magnitude[end][i] = interpolate(magnitude_[i][0], magnitude_[i][1], t);
      }
    }
    return ends;
  }

  struct CubicSigns {
    bool root_free;     // certainly no root in the interval
    bool certain_root;  // certainly opposite signs at its ends
    HalvedCubic halved;  // the coefficients, for narrow_to_first_root
  };

  // Root isolation on the coplanarity cubic over the interval.
  CubicSigns cubic_signs(const Endpoints& e) const {
    const BernsteinCubic<double> cubic = bernstein_over(e);
    const ErrorModel& error = cubic_error_;
    auto sign = [&](int k) {  // -1, 0 (uncertain) or +1
      const double bound = error.relative * cubic.magnitude[k] + error.floor;
      return cubic.coefficient[k] > bound ? 1 : cubic.coefficient[k] < -bound ? -1 : 0;
    };
    return {static_cast<bool>(certainly_root_free(cubic.coefficient, cubic.magnitude,
                                                  error.relative, error.floor)),
            sign(0) * sign(3) < 0, halved_cubic(cubic)};
  }

  // How far F computed from interpolated positions may be from the exact
  // value, where F with its weights' magnitudes on the positions'
  // magnitudes is at most `magnitude` (collision_function_error).
  double function_error_at(double magnitude) const {
    return function_error_.relative * magnitude + function_error_.floor;
  }

  // Each position component as a ball holding all its values over the
  // interval: between its two (certified) end values.
  PositionBalls position_balls(const Endpoints& e) const {
    PositionBalls balls;
    for (int i = 0; i < 3; ++i) {
      auto ball = [&](double low, double high, double magnitude_low, double magnitude_high) {
        const double error = function_error_at(std::max(magnitude_low, magnitude_high));
        const double middle = 0.5 * (low + high);
        return Ball{middle, ball_detail::grown(0.5 * std::fabs(high - low) + error, middle)};
      };
      const V3 &p0 = e.position[0][i], &p1 = e.position[1][i];
      const V3 &m0 = e.magnitude[0][i], &m1 = e.magnitude[1][i];
      balls[i] = {ball(p0.x, p1.x, m0.x, m1.x), ball(p0.y, p1.y, m0.y, m1.y),
                  ball(p0.z, p1.z, m0.z, m1.z)};
    }
    return balls;
  }

  // The query's size over a time interval, in the scaled frame: its largest
  // coordinate difference from the first point at either end, so at every
  // time of the interval (the differences move linearly). The frame's own
  // size (in [1, 2)) counts the whole motion: a corner moving 2^200 makes
  // it 2^200 times the primitives, and `tolerance` relative to it would
  // call a unit triangle and a vertex 1e48 away (or everything at t = 0)
  // within tolerance. The search takes the smaller of it and the frame's
  // unit, so it never calls more within tolerance than the frame did.
  static double size_over(const Endpoints& ends) {
    double size = 0;
    for (int end = 0; end < 2; ++end)
      for (const V3& x : ends.position[end])
        size = std::max({size, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
    return size;
  }

  // Inner search over (u, v) for one time interval, depth first: excluded
  // when every box is; found as soon as one box's image is at most
  // `found_width` wide (the tolerance, without a separation relative to the
  // query's size over the interval; see size_over);
  // unresolved when the time interval's own width keeps a box's image wide
  // (the outer search must split time first).
  Search search_parameters(const Endpoints& ends, std::int64_t budget, double found_width) {
    std::vector<ParameterBox>& stack = parameter_stack();
    stack.assign(1, ParameterBox{{0, 1}, {0, 1}});
    while (!stack.empty()) {
      const ParameterBox box = stack.back();
      stack.pop_back();
      if (++iterations_ > settings_.max_iterations) return Search::out_of_iterations;
      if (--budget < 0) return Search::unresolved;
      if (kind_ == Kind::vertex_face && box.u.low + box.v.low > 1) continue;  // outside the triangle
      const Image image = evaluate(ends, box);
      if (image.excluded) continue;
      if (settings_.min_distance > 0) {
        // The centre names a pair of points of the primitives (VF: inside the triangle).
        const bool on_primitives = kind_ == Kind::edge_edge || box.u.middle() + box.v.middle() <= 1;
        if (on_primitives && image.centre_distance <= witness_distance_) return Search::witnessed;
        if (on_primitives && image.centre_distance <= settings_.min_distance + settings_.tolerance)
          return Search::found;
      } else if (image.width <= found_width) {
        return Search::found;
      }
      const int dimension = dimension_to_split(box, image);
      if (dimension < 0) return Search::unresolved;
      ParameterBox low = box, high = box;
      Interval& low_range = dimension == 1 ? low.u : low.v;
      Interval& high_range = dimension == 1 ? high.u : high.v;
      low_range.high = high_range.low = low_range.middle();
      stack.push_back(high);
      stack.push_back(low);
    }
    return Search::excluded;
  }

  Image evaluate(const Endpoints& ends, const ParameterBox& box) const {
    V3 value[2][2][2];  // [t end][u end][v end]
    double largest_magnitude = 0;
    for (int ti = 0; ti < 2; ++ti)
      for (int ui = 0; ui < 2; ++ui)
        for (int vi = 0; vi < 2; ++vi) {
          std::array<double, 3> w = weights(kind_, ui ? box.u.high : box.u.low, vi ? box.v.high : box.v.low);
          value[ti][ui][vi] = weighted_sum(w, ends.position[ti]);
          for (double& x : w) x = std::fabs(x);
          const V3 magnitude = weighted_sum(w, ends.magnitude[ti]);
          largest_magnitude = std::max({largest_magnitude, magnitude.x, magnitude.y, magnitude.z});
        }
    const double error = function_error_at(largest_magnitude);

    Image image;
    for (int axis = 0; axis < 3; ++axis) {
      auto at = [&](int t, int u, int v) { return component(value[t][u][v], axis); };
      double low = INFINITY, high = -INFINITY;
      for (int corner = 0; corner < 8; ++corner) {
        const double x = at(corner >> 2, (corner >> 1) & 1, corner & 1);
        low = std::min(low, x);
        high = std::max(high, x);
      }
      if (low > error + settings_.min_distance || high < -(error + settings_.min_distance)) {
        image.excluded = true;
        return image;
      }
      image.width = std::max(image.width, high - low + 2 * error);
      double (&influence)[3] = image.influence[axis];
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          influence[0] = std::max(influence[0], std::fabs(at(1, a, b) - at(0, a, b)));
          influence[1] = std::max(influence[1], std::fabs(at(a, 1, b) - at(a, 0, b)));
          influence[2] = std::max(influence[2], std::fabs(at(a, b, 1) - at(a, b, 0)));
        }
    }
    image.excluded = separated_along_center(ends, value, error, image);
    return image;
  }

  // Exclusion along two more directions, both from F at the box's centre
  // (the mean of the corners, F being multilinear): that vector itself, and
  // its part normal to the directions in which u and v move F. Where the
  // contact set is a slanted line in (u, v) (zero-area triangles, parallel
  // edges) the axis tests need boxes as small as the distance to exclude a
  // strip along it; along the normal part a box is excluded whatever its
  // size in (u, v).
  // With a minimum separation s the image must lie farther than s along the
  // direction, and the centre's distance bound is kept in `image`.
  bool separated_along_center(const Endpoints& ends, const V3 (&value)[2][2][2], double error,
                              Image& image) const {
    V3 center{0, 0, 0};
    double largest = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const V3& x = value[corner >> 2][(corner >> 1) & 1][corner & 1];
      center = {center.x + x.x, center.y + x.y, center.z + x.z};
      largest = std::max({largest, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
    }
    const double separation = settings_.min_distance;
    if (separation > 0) image.centre_distance = centre_distance_bound(center, largest, error);
    // Any direction will do: the bound covers the corners' own error and the
    // rounding of the dot products (three terms), and the separation times
    // the direction's length (rounded up by the factor).
    auto separates = [&](const V3& direction) {
      const double weight = std::fabs(direction.x) + std::fabs(direction.y) + std::fabs(direction.z);
      const double length = separation > 0 ? std::sqrt(dot(direction, direction)) * (1 + 4 * kUnitRoundoff) : 0;
      const double bound = weight * (error + 4 * kUnitRoundoff * largest) + kUnderflowFloor + separation * length;
      for (int corner = 0; corner < 8; ++corner)
        if (!(dot(direction, value[corner >> 2][(corner >> 1) & 1][corner & 1]) > bound)) return false;
      return true;
    };
    return separates(center) || separates(normal_part(center, parameter_directions(ends)));
  }

  // An upper bound of |F| at the box's centre, which (F being affine in each
  // of t, u and v) is the mean of the corners: each corner within `error`,
  // the sum of eight rounded 7 times at most 8 largest each.
  static double centre_distance_bound(const V3& corner_sum, double largest, double error) {
    const double margin = error + 8 * kUnitRoundoff * largest + kUnderflowFloor;
    const V3 bound{std::fabs(corner_sum.x) * 0.125 + margin, std::fabs(corner_sum.y) * 0.125 + margin,
                   std::fabs(corner_sum.z) * 0.125 + margin};
    return std::sqrt(dot(bound, bound)) * (1 + 4 * kUnitRoundoff);
  }

  // dF/du and dF/dv at the interval's middle time (F is linear in each).
  std::array<V3, 2> parameter_directions(const Endpoints& ends) const {
    std::array<V3, 3> middle;
    for (int i = 0; i < 3; ++i) middle[i] = interpolate(ends.position[0][i], ends.position[1][i], 0.5);
    const std::array<double, 3> at_origin = weights(kind_, 0, 0);
    std::array<V3, 2> directions;
    for (int d = 0; d < 2; ++d) {
      std::array<double, 3> w = weights(kind_, d == 0 ? 1 : 0, d == 1 ? 1 : 0);
      for (int i = 0; i < 3; ++i) w[i] -= at_origin[i];
      directions[d] = weighted_sum(w, middle);
    }
    return directions;
  }

  // x minus its least-squares projection onto span{a, b}; onto the longer of
  // the two when they are (nearly) parallel.
  static V3 normal_part(const V3& x, const std::array<V3, 2>& span) {
    const V3 &a = span[0], &b = span[1];
    const double aa = dot(a, a), ab = dot(a, b), bb = dot(b, b);
    const double determinant = aa * bb - ab * ab;
    auto minus = [&](double alpha, const V3& p, double beta, const V3& q) {
      return V3{x.x - alpha * p.x - beta * q.x, x.y - alpha * p.y - beta * q.y,
                x.z - alpha * p.z - beta * q.z};
    };
    if (determinant > 1e-12 * aa * bb) {
      const double xa = dot(x, a), xb = dot(x, b);
      return minus((xa * bb - xb * ab) / determinant, a, (xb * aa - xa * ab) / determinant, b);
    }
    const V3& longer = aa >= bb ? a : b;
    const double length = std::max(aa, bb);
    if (length == 0) return x;
    return minus(dot(x, longer) / length, longer, 0, longer);
  }

  // u (1) or v (2), whichever changes F more, or -1 when splitting cannot
  // help: both are at their smallest width, or time changes F more than they
  // do (the outer search must split time first).
  static int dimension_to_split(const ParameterBox& box, const Image& image) {
    double influence[3] = {};
    for (const auto& axis : image.influence)
      for (int d = 0; d < 3; ++d) influence[d] = std::max(influence[d], axis[d]);
    if (box.u.width() <= kSmallestWidth) influence[1] = 0;
    if (box.v.width() <= kSmallestWidth) influence[2] = 0;
    const int best = influence[1] >= influence[2] ? 1 : 2;
    return influence[best] > influence[0] ? best : -1;
  }

  Kind kind_;
  SolverSettings settings_;
  V3 position_[3][2];
  V3 magnitude_[3][2];
  ErrorModel cubic_error_;
  ErrorModel function_error_;
  double witness_distance_ = 0;
  double absolute_error_ = 0;
  // Componentwise max(|x(0)|, |x(1)|) of x2..x4: at least the magnitude of
  // each of their positions in the step, (1 - t) |x(0)| + t |x(1)|.
  std::array<V3, 3> reach_;
  // An upper bound of the largest relative displacement, the distance's
  // Lipschitz constant (docs/design.md §11): computed where a step needs
  // it, which few do.
  double motion() {
    if (motion_ < 0) {
      const SeparationErrorModel error = separation_error(absolute_error_, settings_.certified);
      motion_ = std::sqrt(largest_displacement2(kind_, position_, error.relative, error.floor)) *
                SeparationErrors::grow;
    }
    return motion_;
  }
  double motion_ = -1;
  double advanced_ = 0;    // every time before it is free of contact (advance)
  std::int64_t iterations_ = 0;
};

}  // namespace

SolverOutcome solve_inclusion(Kind kind, const ScaledQuery& query, const SolverSettings& settings) {
  const SolverOutcome outcome = InclusionSolver(kind, query, settings).run();
  // Every time before a hit's toi is excluded: past tmax, nothing counts.
  if (outcome.hit && outcome.toi > settings.tmax) return {false, 0, false, settings.certified};
  return outcome;
}

}  // namespace batchccd::reference

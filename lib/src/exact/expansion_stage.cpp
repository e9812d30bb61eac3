#include "exact/expansion_stage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "exact/exact_motion.hpp"
#include "exact/expansion.hpp"
#include "exact/plane_axis.hpp"
#include "exact/polynomial.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::exact {
namespace {

using Value = BoundedExpansion;

// The TOI grid: roots are located to intervals [k, k + 1] 2^-40, and
// where signs need it to 2^-52 (the finest grid of doubles in [1/2, 1)),
// then for a numerator's sign to 2^-76, with times held as two doubles.
constexpr int kGridBits = static_cast<int>(kToiBits);
constexpr int kDoubleGridBits = 52;
constexpr int kFinerGridBits = 76;

// Why expansions stay exact here (expansion.hpp: no overflow, no
// underflow). The query is normalized: coordinates below 2 in magnitude,
// nonzero ones at least 2^-80, so each is a multiple of 2^-132 and so is
// every difference. The inside test's polynomials are sums of products of
// four such differences: coefficients below 2^24 and multiples of 2^-528.
// They are evaluated at times on the 2^-100 grid (degree 4: a factor
// 2^-400) or subdivided 40 times (degree 3: 2^-120): every term stays a
// multiple of 2^-928, above the smallest normal double (2^-1022).
constexpr int kCoordinateFloor = -80;
constexpr int kTimeFloor = 100;  // times evaluated exactly lie on the 2^-100 grid

bool on_time_grid(double t) {
  const double scaled = std::ldexp(t, kTimeFloor);
  return scaled == std::floor(scaled);
}

// A polynomial in t of degree at most 4 with exact coefficients.
struct Polynomial4 {
  std::array<Value, 5> c;  // c[i] multiplies t^i
  int size = 0;            // coefficients in use; leading ones may be zero

  int degree() const {
    for (int i = size - 1; i >= 0; --i)
      if (!c[i].is_zero()) return i;
    return -1;
  }
  // Exact for t on the time grid, a double or (past the doubles' grid) an
  // expansion.
  template <class Time>
  Value at(const Time& t) const {
    Value value;
    for (int i = size - 1; i >= 0; --i) value = value * t + c[i];
    return value;
  }
};

Polynomial4 operator+(const Polynomial4& a, const Polynomial4& b) {
  Polynomial4 sum;
  sum.size = std::max(a.size, b.size);
  for (int i = 0; i < sum.size; ++i) sum.c[i] = (i < a.size ? a.c[i] : Value()) + (i < b.size ? b.c[i] : Value());
  return sum;
}

Polynomial4 operator-(Polynomial4 a) {
  for (int i = 0; i < a.size; ++i) a.c[i] = -a.c[i];
  return a;
}

Polynomial4 operator-(const Polynomial4& a, const Polynomial4& b) { return a + (-b); }

Polynomial4 operator*(const Polynomial4& a, const Polynomial4& b) {
  Polynomial4 product;
  product.size = a.size + b.size - 1;  // at most 5 where this file multiplies
  for (int i = 0; i < a.size; ++i)
    for (int j = 0; j < b.size; ++j) product.c[i + j] = product.c[i + j] + a.c[i] * b.c[j];
  return product;
}

Polynomial4 derivative(const Polynomial4& p) {
  Polynomial4 slope;
  slope.size = std::max(p.size - 1, 0);
  for (int i = 1; i < p.size; ++i) slope.c[i - 1] = p.c[i] * static_cast<double>(i);
  return slope;
}

// A double evaluation of an expression at the low end of a time interval,
// with a bound of its rounding error, and bounds of the expression's
// magnitude and slope over the interval: a filter that settles most signs
// before any expansion.
struct Estimate {
  double value = 0, error = 0;      // |exact value - value| <= error
  double magnitude = 0, slope = 0;  // |f| and |f'| on the interval are at most these

  static Estimate constant(const Value& exact) {
    const double value = exact.estimate();
    const double error = 0x1p-51 * std::fabs(value);  // a compressed expansion's sum: 2 ulps
    return {value, error, std::fabs(value) + error, 0};
  }
};

constexpr double kRounding = 0x1p-52;  // one rounding, with room for the bound's own

Estimate operator+(const Estimate& a, const Estimate& b) {
  const double value = a.value + b.value;
  return {value, a.error + b.error + kRounding * std::fabs(value), a.magnitude + b.magnitude, a.slope + b.slope};
}

Estimate operator-(Estimate a) {
  a.value = -a.value;
  return a;
}

Estimate operator-(const Estimate& a, const Estimate& b) { return a + (-b); }

Estimate operator*(const Estimate& a, const Estimate& b) {
  const double value = a.value * b.value;
  const double error = std::fabs(a.value) * b.error + std::fabs(b.value) * a.error + a.error * b.error +
                       kRounding * std::fabs(value);
  return {value, error, a.magnitude * b.magnitude, a.slope * b.magnitude + a.magnitude * b.slope};
}

// Vector algebra, the same for exact values, estimates and polynomials.
template <class Number>
using Vector = std::array<Number, 3>;

template <class Number>
Vector<Number> operator-(const Vector<Number>& a, const Vector<Number>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

template <class Number>
Vector<Number> cross(const Vector<Number>& a, const Vector<Number>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <class Number>
Number dot(const Vector<Number>& a, const Vector<Number>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The query's motion as three moving vectors, each the difference of two
// of its points (design numbering 1..4), linear in t:
//   vertex-face: A = x2 - x1, B = x3 - x1, C = x4 - x1 (triangle edges, vertex);
//   edge-edge:   A = x2 - x1, B = x4 - x3, C = x3 - x1 (the edges, between them).
// With n = A x B the coplanarity cubic is C . n, and at its roots, where
// n != 0, the contact is a sign condition on X = (C x B) . n and
// Y = (A x C) . n (vertex-face) or (C x A) . n (edge-edge), which are the
// contact's parameters times N = |n|^2: vertex-face X, Y, N - X - Y >= 0
// (barycentric coordinates), edge-edge X, N - X, Y, N - Y >= 0 (the points
// on the edges). The same mathematics as the exact stage's triangles
// (origin_in_triangle.hpp), in the edges' own parameters, so that no
// diagonal splits the edge-edge square.
template <class Number>
using Motion = std::array<Vector<Number>, 3>;

template <class Number>
Number coplanarity_cubic(const Motion<Number>& v) {
  return dot(v[2], cross(v[0], v[1]));
}

// The numerators of the contact condition at a root (nonnegative at a
// contact): vertex-face X, Y, N - X - Y; edge-edge X, N - X, Y, N - Y.
// Each piece (n, N, X, Y) is formed once, and only when a numerator asked
// for needs it: in expansions every product is costly, and a root usually
// needs one or two of them. The motion must outlive this.
template <class Number>
class LazyNumerators {
 public:
  LazyNumerators(Kind kind, const Motion<Number>& v) : kind_(kind), v_(v) {}

  int count() const { return kind_ == Kind::vertex_face ? 3 : 4; }
  Number operator[](int k) {
    if (kind_ == Kind::vertex_face) return k == 0 ? x() : k == 1 ? y() : squared() - x() - y();
    return k == 0 ? x() : k == 1 ? squared() - x() : k == 2 ? y() : squared() - y();
  }
  const Number& squared() {
    if (!squared_) squared_ = dot(n(), n());
    return *squared_;
  }

 private:
  const Vector<Number>& n() {
    if (!n_) n_ = cross(v_[0], v_[1]);
    return *n_;
  }
  const Number& x() {
    if (!x_) x_ = dot(cross(v_[2], v_[1]), n());
    return *x_;
  }
  const Number& y() {
    if (!y_) y_ = kind_ == Kind::vertex_face ? dot(cross(v_[0], v_[2]), n()) : dot(cross(v_[2], v_[0]), n());
    return *y_;
  }

  Kind kind_;
  const Motion<Number>& v_;
  std::optional<Vector<Number>> n_;
  std::optional<Number> squared_, x_, y_;
};

// P_from - P_to, linear in t.
Vector<Polynomial4> moving_difference(Kind kind, const Query& query, int from, int to) {
  const int a = reference::point_index(kind, from), b = reference::point_index(kind, to);
  Vector<Polynomial4> difference;
  for (int axis = 0; axis < 3; ++axis) {
    const Value start = Value::difference(query.points[a][axis], query.points[b][axis]);
    const Value end = Value::difference(query.points[a + 4][axis], query.points[b + 4][axis]);
    difference[axis].c = {start, end - start};
    difference[axis].size = 2;
  }
  return difference;
}

Motion<Polynomial4> moving_vectors(Kind kind, const Query& query) {
  const auto d = [&](int from, int to) { return moving_difference(kind, query, from, to); };
  if (kind == Kind::vertex_face) return {d(2, 1), d(3, 1), d(4, 1)};
  return {d(2, 1), d(4, 3), d(3, 1)};
}

template <class Time>
Motion<Value> exactly_at(const Motion<Polynomial4>& motion, const Time& t) {
  Motion<Value> at;
  for (int i = 0; i < 3; ++i)
    for (int axis = 0; axis < 3; ++axis) at[i][axis] = motion[i][axis].at(t);
  return at;
}

// The vectors over [low, low + width]: each component s + t b.
Motion<Estimate> estimated_on(const Motion<Polynomial4>& motion, double low, double width) {
  Motion<Estimate> on;
  for (int i = 0; i < 3; ++i)
    for (int axis = 0; axis < 3; ++axis) {
      const Polynomial4& linear = motion[i][axis];
      const Estimate start = Estimate::constant(linear.c[0]), slope = Estimate::constant(linear.c[1]);
      Estimate& component = on[i][axis];
      component = start + slope * Estimate{low, 0, 0, 0};
      component.slope = slope.magnitude;
      component.magnitude = std::fabs(component.value) + component.error + width * component.slope;
    }
  return on;
}

// A root of the cubic in (0, 1): exactly `low` when `exact`, otherwise the
// only one in the open interval (low, high), where the cubic has the sign
// `sign_after_low` just above low.
struct Root {
  double low = 0, high = 0;
  bool exact = false;
  int sign_after_low = 0;
  // Past the doubles' grid (the interval (low, high) 2^-52 wide): the root
  // lies in (low + fine_low, low + fine_low + fine_width), or is exactly
  // low + fine_low when `exact`. fine_width 0: not in use.
  double fine_low = 0, fine_width = 0;

  bool fine() const { return fine_width > 0 || fine_low > 0; }
  Value low_time() const { return Value(low) + Value(fine_low); }
  double width() const { return exact ? 0 : (fine() ? fine_width : high - low); }
};

// Scaled Bernstein coefficients on a dyadic interval (positive multiples of
// the true ones: the same signs, the same subdivision).
using Bernstein = std::array<Value, 4>;

int sign_variations(const Bernstein& b, int n) {
  int variations = 0, previous = 0;
  for (int i = 0; i <= n; ++i) {
    const int sign = b[i].sign();
    if (sign == 0) continue;
    variations += previous != 0 && sign != previous;
    previous = sign;
  }
  return variations;
}

int first_sign(const Bernstein& b, int n) {
  for (int i = 0; i <= n; ++i)
    if (b[i].sign() != 0) return b[i].sign();
  return 0;
}

// The roots of the cubic in (0, 1), in increasing order: Descartes' rule on
// Bernstein coefficients, halving with de Casteljau. nullopt when two roots
// lie closer than 2^-40 (or one is multiple).
std::optional<std::vector<Root>> isolate_cubic_roots(const Polynomial4& cubic) {
  const int n = cubic.degree();
  std::vector<Root> roots;
  if (n < 1) return roots;
  // b_k lcm / binomial(n, k): integer combinations of the coefficients.
  constexpr int kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  const int lcm = n == 3 ? 3 : n;  // of binomial(n, i) for i = 0..n
  Bernstein whole;
  for (int k = 0; k <= n; ++k)
    for (int i = 0; i <= k; ++i)
      whole[k] = whole[k] + cubic.c[i] * static_cast<double>(kBinomial[k][i] * lcm / kBinomial[n][i]);

  struct Interval {
    std::uint64_t numerator;  // [numerator, numerator + 1] 2^-depth
    int depth;
    Bernstein b;
    bool exact_root;  // the single point numerator 2^-depth
  };
  std::vector<Interval> stack{{0, 0, whole, false}};
  while (!stack.empty()) {
    Interval interval = std::move(stack.back());
    stack.pop_back();
    const double low = std::ldexp(static_cast<double>(interval.numerator), -interval.depth);
    if (interval.exact_root) {
      roots.push_back({low, low, true, 0});
      continue;
    }
    const int variations = sign_variations(interval.b, n);
    if (variations == 0) continue;
    if (variations == 1) {
      const double high = std::ldexp(static_cast<double>(interval.numerator + 1), -interval.depth);
      roots.push_back({low, high, false, first_sign(interval.b, n)});
      continue;
    }
    if (interval.depth == kGridBits) return std::nullopt;
    Bernstein left, right, work = interval.b;
    left[0] = work[0];
    right[n] = work[n];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i + r <= n; ++i) work[i] = (work[i] + work[i + 1]) * 0.5;
      left[r] = work[0];
      right[n - r] = work[n - r];
    }
    const std::uint64_t middle = 2 * interval.numerator + 1;
    const int depth = interval.depth + 1;
    const bool middle_is_root = right[0].is_zero();
    // Pushed right to left so that they come off in increasing order.
    stack.push_back({middle, depth, right, false});
    if (middle_is_root) stack.push_back({middle, depth, {}, true});
    stack.push_back({2 * interval.numerator, depth, left, false});
  }
  return roots;
}

// A double near the root in (low, high) (Newton steps kept inside a
// shrinking bracket, on the rounded coefficients): only a first guess.
double approximate_root(const Polynomial4& cubic, const Root& root) {
  const auto value = [&](double t) {
    double sum = 0, slope = 0;
    for (int i = cubic.size - 1; i >= 0; --i) {
      slope = slope * t + sum;
      sum = sum * t + cubic.c[i].estimate();
    }
    return std::pair{sum, slope};
  };
  double low = root.low, high = root.high, t = 0.5 * (low + high);
  for (int step = 0; step < 80 && high - low > std::ldexp(0.25, -kDoubleGridBits); ++step) {
    const auto [f, slope] = value(t);
    if (f == 0) return t;
    if ((f > 0) == (root.sign_after_low > 0)) low = t;
    else high = t;
    const double newton = t - f / slope;
    t = newton > low && newton < high ? newton : 0.5 * (low + high);
  }
  return t;
}

// Narrows the root to a cell [k, k + 1] 2^-bits of a grid (or finds it
// exactly on the grid): exact signs of the cubic at grid points, the first
// two probes next to a Newton estimate, bisection after.
void narrow_to_grid(const Polynomial4& cubic, Root& root, int bits) {
  const double cell = std::ldexp(1.0, -bits);
  if (root.exact || root.high - root.low <= cell) return;
  auto low = static_cast<std::uint64_t>(std::ldexp(root.low, bits));
  auto high = static_cast<std::uint64_t>(std::ldexp(root.high, bits));
  const auto probe = [&](std::uint64_t k) {
    const double t = std::ldexp(static_cast<double>(k), -bits);
    const int sign = cubic.at(t).sign();
    if (sign == 0) root = {t, t, true, 0};
    else if (sign == root.sign_after_low) low = k;
    else high = k;
  };
  const double guess = std::ldexp(approximate_root(cubic, root), bits);
  const auto near = static_cast<std::uint64_t>(std::clamp(std::floor(guess), static_cast<double>(low + 1),
                                                          static_cast<double>(high - 1)));
  probe(near);
  if (!root.exact && low == near && near + 1 < high) probe(near + 1);
  while (!root.exact && high - low > 1) probe(low + (high - low) / 2);
  if (!root.exact) {
    root.low = std::ldexp(static_cast<double>(low), -bits);
    root.high = std::ldexp(static_cast<double>(high), -bits);
  }
}

// Narrows the root, within a cell of the doubles' grid, to a cell of the
// finer grid: exact signs at low + j 2^-76, the first two probes next to
// Newton's step from low (the cubic and its slope there exact, then
// rounded: the step is good to about 2^-100 where the root is simple and
// the cubic's curvature plays no part across 2^-52), bisection after.
void narrow_finer(const Polynomial4& cubic, Root& root) {
  constexpr int bits = kFinerGridBits;
  if (root.exact || root.fine()) return;
  std::uint64_t low = 0;
  std::uint64_t high = static_cast<std::uint64_t>(std::ldexp(root.high - root.low, bits));
  const auto probe = [&](std::uint64_t k) {
    const double offset = std::ldexp(static_cast<double>(k), -bits);  // exact: below 2^53 cells
    const int sign = cubic.at(Value(root.low) + Value(offset)).sign();
    if (sign == 0) {
      root.exact = true;
      root.fine_low = offset;
      root.fine_width = 0;
    } else if (sign == root.sign_after_low) {
      low = k;
    } else {
      high = k;
    }
  };
  if (high - low > 2) {
    const double step = -cubic.at(root.low).estimate() / derivative(cubic).at(root.low).estimate();
    const double guess = std::ldexp(step, bits);
    if (std::isfinite(guess) && guess > static_cast<double>(low) && guess < static_cast<double>(high)) {
      const auto near = static_cast<std::uint64_t>(guess);
      if (near > low) probe(near);
      if (!root.exact && low == near && near + 1 < high) probe(near + 1);
    }
  }
  while (!root.exact && high - low > 1) probe(low + (high - low) / 2);
  if (root.exact) return;
  root.fine_low = std::ldexp(static_cast<double>(low), -bits);
  root.fine_width = std::ldexp(1.0, -bits);
}

// p scaled by a power of two (its roots and signs unchanged) to a largest
// term near 1; false when a nonzero coefficient then has a term below
// `floor` (p is left partly scaled: the caller gives up on it).
bool scaled_to_unit(Polynomial4& p, double floor) {
  double largest = 0;
  for (int i = 0; i < p.size; ++i) largest = std::max(largest, p.c[i].largest_term());
  if (largest == 0) return true;
  const double factor = std::ldexp(1.0, -std::ilogb(largest));
  for (int i = 0; i < p.size; ++i) {
    p.c[i] = p.c[i] * factor;
    if (!p.c[i].is_zero() && p.c[i].smallest_term() < floor) return false;
  }
  return true;
}

// The exponent of a term's last bit: the term is an integer (of 53 bits)
// times 2^lowest_bit.
int lowest_bit(double term) {
  int exponent = 0;
  std::frexp(term, &exponent);
  return exponent - 53;
}

// The sum of an expansion's terms times 2^-lowest (every term's last bit at
// or above 2^lowest): each term's 53-bit integer added into the limbs of
// the positive or the negative part at its offset, in time linear in the
// terms and the result's length (shifting each term into an integer of its
// own and adding costs the length per term).
Integer as_integer(std::span<const double> terms, int lowest) {
  if (terms.empty()) return Integer();
  constexpr int kLimbBits = GMP_NUMB_BITS;
  constexpr int kAddendLimbs = 53 / kLimbBits + 2;  // 53 bits shifted by less than a limb
  const int bits = lowest_bit(terms.back()) + 54 - lowest;  // the largest term, and a carry
  const auto limbs = static_cast<mp_size_t>(bits / kLimbBits + 2);
  Integer positive, negative;
  mp_limb_t* const parts[2] = {mpz_limbs_write(positive.get(), limbs), mpz_limbs_write(negative.get(), limbs)};
  std::fill_n(parts[0], limbs, 0);
  std::fill_n(parts[1], limbs, 0);
  for (const double term : terms) {
    std::array<mp_limb_t, kAddendLimbs> addend{};
    auto digits = static_cast<std::uint64_t>(std::ldexp(std::fabs(term), -lowest_bit(term)));  // below 2^53
    for (mp_limb_t& limb : addend) {
      limb = static_cast<mp_limb_t>(digits) & GMP_NUMB_MASK;
      if constexpr (kLimbBits < 64) digits >>= kLimbBits;
      else digits = 0;
    }
    const int offset = lowest_bit(term) - lowest;
    if (offset % kLimbBits != 0) mpn_lshift(addend.data(), addend.data(), kAddendLimbs, offset % kLimbBits);
    mp_limb_t* const part = parts[term < 0] + offset / kLimbBits;
    const mp_size_t room = limbs - offset / kLimbBits;
    mpn_add(part, part, room, addend.data(), std::min<mp_size_t>(kAddendLimbs, room));
  }
  mpz_limbs_finish(positive.get(), limbs);
  mpz_limbs_finish(negative.get(), limbs);
  return positive - negative;
}

// p times a power of two, with integer coefficients: every term of an
// expansion is a 53-bit integer times a power of two.
Polynomial as_integers(const Polynomial4& p) {
  int lowest = std::numeric_limits<int>::max();
  for (int i = 0; i < p.size; ++i)
    for (const double term : p.c[i].terms()) lowest = std::min(lowest, lowest_bit(term));
  Polynomial result;
  for (int i = 0; i < p.size; ++i) result.coefficients.push_back(as_integer(p.c[i].terms(), lowest));
  result.trim();
  return result;
}

// The sign of p at the root in (low, high) of `defining` (given as
// integers: as_integers), exactly and at once (sign_at_isolated_root),
// where the interval's ends lie on the doubles' grid; nullopt when
// `defining` vanishes at one of them.
//
// In integers, not expansions: the remainder sequence's coefficients grow
// with each step, past the expansions' bounded length where coordinates
// spread over many binades, and even where they fit the integers' few
// products of short polynomials cost less.
std::optional<int> sign_in_integers(const Polynomial& defining, const Polynomial4& p, const Root& root) {
  const auto on_grid = [](double t) {
    Integer numerator;
    mpz_set_d(numerator.get(), std::ldexp(t, kDoubleGridBits));  // an integer below 2^53: exact
    return numerator;
  };
  return sign_at_isolated_root(defining, root.sign_after_low, as_integers(p), on_grid(root.low),
                               on_grid(root.high), kDoubleGridBits);
}

// Whether the primitives touch at a time where n = A x B vanishes (parallel
// edges, a triangle flat on a line or a point: the contact numerators,
// multiples of n, say nothing there), from the vectors at that time,
// exactly. A flat triangle is the segment its corners span, which its two
// sides from x1 cover.
bool touches_where_flat(Kind kind, const Motion<Value>& v) {
  const auto is_zero = [](const Vector<Value>& u) { return u[0].is_zero() && u[1].is_zero() && u[2].is_zero(); };
  const auto on_segment = [&](const Vector<Value>& q, const Vector<Value>& w) {  // q on [0, w]
    if (is_zero(w)) return is_zero(q);
    const Value along = dot(q, w);
    return is_zero(cross(q, w)) && along.sign() >= 0 && (dot(w, w) - along).sign() >= 0;
  };
  const Vector<Value>&a = v[0], &b = v[1], &c = v[2];
  if (kind == Kind::vertex_face) return on_segment(c, a) || on_segment(c, b);
  // Edge-edge: x1 + s a meets x1 + c + u b for s, u in [0, 1].
  if (is_zero(a)) return on_segment(Vector<Value>{} - c, b);
  if (!is_zero(cross(c, a))) return false;  // b, parallel to a, lies off a's line
  // Along a, edge b spans [c.a, c.a + b.a]; edge a spans [0, a.a].
  const Value from = dot(c, a), to = from + dot(b, a), length = dot(a, a);
  return (from.sign() >= 0 || to.sign() >= 0) && ((length - from).sign() >= 0 || (length - to).sign() >= 0);
}

// The sign of p at the root in (low, high) where p's exact value at low
// beats how far p can drift across the interval, bounded by Taylor: its
// exact slope at low and its curvature on [0, 1]; nullopt otherwise.
std::optional<int> sign_by_slope(const Polynomial4& p, const Root& root) {
  constexpr double kMargin = 1 + 0x1p-40;  // covers the estimates' few ulps and the bound's own rounding
  const Polynomial4 slope = derivative(p);
  double curvature = 0;
  for (int i = 2; i < p.size; ++i) curvature += i * (i - 1) * std::fabs(p.c[i].estimate());
  const auto settle = [&](const auto& low) -> std::optional<int> {
    const double width = root.width();
    const double drift = width * (std::fabs(slope.at(low).estimate()) + width * curvature) * kMargin * kMargin;
    const Value value = p.at(low);
    if (std::fabs(value.estimate()) > drift * kMargin) return value.sign();
    return std::nullopt;
  };
  return root.fine() ? settle(root.low_time()) : settle(root.low);
}

// The signs of a root's contact numerators there, each found once, for a
// root narrowed to the doubles' grid: from the numerator's polynomial and
// its slope over the root's interval (sign_by_slope), else over the root
// narrowed to the finer grid, else from the remainder sequence in integers
// (sign_in_integers), which alone tells a zero at the root (a contact on the
// boundary) and costs the most. The answer does not depend on how narrow
// the root's interval is. Numerators as polynomials, formed when first
// asked for.
class SignsAtRoot {
 public:
  SignsAtRoot(Kind kind, const Motion<Polynomial4>& motion, const Polynomial4& cubic)
      : cubic_(cubic), polynomials_(kind, motion) {}

  // The sign of numerator k (or, k = kSquared, of N = |n|^2) at the root;
  // nullopt where the test cannot tell.
  std::optional<int> operator()(int k, const Root& root) {
    if (!known_[k]) {
      try {
        const Polynomial4& p = k == kSquared ? polynomials_.squared() : polynomials_[k];
        known_[k] = sign_by_slope(p, root);
        if (!*known_[k]) {
          const Root& finer = finer_root(root);
          known_[k] = finer.exact ? p.at(finer.low_time()).sign() : sign_by_slope(p, finer);
        }
        if (!*known_[k]) known_[k] = sign_in_integers(cubic_integers(), p, root);
      } catch (const Value::TooLong&) {  // the numerator itself outgrew the expansions
        return std::nullopt;
      }
    }
    return *known_[k];
  }
  static constexpr int kSquared = 4;

 private:
  const Polynomial& cubic_integers() {
    if (!cubic_integers_) cubic_integers_ = as_integers(cubic_);
    return *cubic_integers_;
  }
  const Root& finer_root(const Root& root) {
    if (!finer_root_) narrow_finer(cubic_, finer_root_.emplace(root));
    return *finer_root_;
  }

  const Polynomial4& cubic_;
  std::optional<Polynomial> cubic_integers_;  // these two formed when first needed
  std::optional<Root> finer_root_;
  LazyNumerators<Polynomial4> polynomials_;
  std::array<std::optional<std::optional<int>>, 5> known_;
};

// Whether the primitives touch at the root; nullopt when the signs do not
// settle it at this width. Each numerator's sign comes from its estimate
// against how far it can drift over the interval. Given exact signs (at
// the doubles' grid), a numerator still unsettled is tried with its exact
// value at the interval's low end against the same drift, then takes its
// sign at the root from them (a contact on the boundary, or a numerator
// too small for the interval); on coarser grids an exact value rarely beats
// the drift, and narrowing costs less.
std::optional<bool> touches_at(Kind kind, const Motion<Polynomial4>& motion, const Root& root,
                               SignsAtRoot* exact_signs = nullptr) {
  constexpr double kMargin = 1 + 0x1p-30;  // covers the rounding of the bounds themselves
  const double width = root.width();
  const Motion<Estimate> estimated = estimated_on(motion, root.low, width);
  LazyNumerators<Estimate> estimates(kind, estimated);
  std::optional<Motion<Value>> exact_motion;
  std::optional<LazyNumerators<Value>> exact;
  const auto exact_numerators = [&]() -> LazyNumerators<Value>& {
    if (!exact) exact.emplace(kind, exact_motion.emplace(exactly_at(motion, root.low)));
    return *exact;
  };
  std::array<std::optional<int>, 4> signs;
  for (int k = 0; k < estimates.count(); ++k) {
    const Estimate estimate = estimates[k];
    const double drift = width * estimate.slope;
    if (std::fabs(estimate.value) > (estimate.error + drift) * kMargin + 0x1p-1000) {
      signs[k] = estimate.value > 0 ? 1 : -1;
    } else if (root.exact || (exact_signs && std::fabs(estimate.value) + estimate.error > drift * kMargin)) {
      // The exact value may beat the drift.
      const Value value = exact_numerators()[k];
      if (root.exact || std::fabs(value.estimate()) > drift * kMargin) signs[k] = value.sign();
    }
    // A negative numerator is nonzero, so n != 0 there, where the test
    // applies: outside.
    if (signs[k] && *signs[k] < 0) return false;
  }
  int positive = 0;
  for (int k = 0; k < estimates.count(); ++k) {
    if (!signs[k] && exact_signs) signs[k] = (*exact_signs)(k, root);
    if (!signs[k]) return std::nullopt;  // the next grid may settle it; then the others are tested
    if (*signs[k] < 0) return false;
    positive += *signs[k] > 0;
  }
  if (positive > 0) return true;
  // Every numerator zero: a contact where n != 0; where n = 0, the flat
  // configuration decides at an exact time.
  if (root.exact) return exact_numerators().squared().sign() > 0 || touches_where_flat(kind, *exact_motion);
  if (exact_signs && (*exact_signs)(SignsAtRoot::kSquared, root) > 0) return true;
  return std::nullopt;
}

// Which side of tmax a root of p lies on: true when after it (then every
// later root is too); nullopt when tmax is off the time grid and the root's
// interval straddles it. A root found exactly at tmax becomes exact.
std::optional<bool> after_tmax(const Polynomial4& p, Root& root, double tmax) {
  if (root.low >= tmax && !(root.exact && root.low == tmax)) return true;
  if (root.exact || root.high <= tmax) return false;
  if (!on_time_grid(tmax)) return std::nullopt;
  const int sign = p.at(tmax).sign();
  if (sign == 0) root = {tmax, tmax, true, 0};
  return sign != 0 && sign == root.sign_after_low;
}

// Planar motion: the coplanarity cubic identically zero, and the points in
// a plane the projection along `axis` maps one to one (exact_plane_axis,
// docs/design.md §5a). There the contact is a sign condition on quadratics
// in t, orientations w(U, V) = (U x V)[axis] of the moving vectors; with
// w = w(A, B):
//   vertex-face: w(C, B), w(A, C) and w minus both (w times the vertex's
//     barycentric coordinates), no two of strictly opposite signs;
//   edge-edge: w(C, B) and w - w(C, B), w(C, A) and w - w(C, A) (w times
//     the edges' parameters), neither pair of strictly opposite signs.
// Where w != 0 that is the contact exactly. Where w = 0 (a triangle flat on
// a line, parallel edges) every contact satisfies it but not conversely:
// such a time is left to the integers. Its truth changes only at roots of
// its polynomials, and the contact times form a closed set, so the first
// contact is at 0 or at one of those roots (the candidates).
class PlanarContact {
 public:
  PlanarContact(Kind kind, const Motion<Polynomial4>& v, int axis) : axis_(axis) {
    area_ = orientation(v[0], v[1]);
    const Polynomial4 s = orientation(v[2], v[1]);
    if (kind == Kind::vertex_face) {
      const Polynomial4 u = orientation(v[0], v[2]);
      conditions_ = {s, u, area_ - s - u};
      groups_ = {0, 0, 0};
    } else {
      const Polynomial4 u = orientation(v[2], v[0]);
      conditions_ = {s, area_ - s, u, area_ - u};
      groups_ = {0, 0, 1, 1};
    }
  }

  std::optional<ExactOutcome> solve(bool need_toi, double tmax) {
    if (area_.degree() < 0) return std::nullopt;  // flat or parallel throughout
    std::vector<Candidate> candidates{{Root{0, 0, true, 0}, -1, -1}};
    for (int k = 0; k < static_cast<int>(conditions_.size()); ++k)
      if (!add_roots(k, candidates)) return std::nullopt;
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.root.low < b.root.low; });
    std::optional<double> first;
    for (Candidate& candidate : candidates) {
      if (first && candidate.root.low >= *first) break;  // nothing earlier is left
      const Polynomial4* defining = candidate.defining < 0 ? nullptr : &defining_[candidate.defining];
      if (defining) {
        const std::optional<bool> after = after_tmax(*defining, candidate.root, tmax);
        if (!after) return std::nullopt;
        if (*after) continue;
      } else if (candidate.root.low > tmax) {
        continue;
      }
      // No earlier candidate holds, and none later starts below this one.
      const double lower_bound = candidate.root.low;
      const std::optional<bool> touches = holds(defining, candidate.root, candidate.source);
      if (!touches) return std::nullopt;
      if (!*touches) continue;
      if (!need_toi) return ExactOutcome{true, lower_bound, false};
      if (defining) narrow_to_grid(*defining, candidate.root, kGridBits);
      first = std::min(first.value_or(1.0), candidate.root.low);
    }
    if (first) return ExactOutcome{true, *first, false};
    return ExactOutcome{};
  }

 private:
  // A candidate time: a root of defining_[defining], or exact (-1), where
  // the condition `source` (if any) vanishes.
  struct Candidate {
    Root root;
    int defining;
    int source;
  };

  Polynomial4 orientation(const Vector<Polynomial4>& u, const Vector<Polynomial4>& v) const {
    const int j = (axis_ + 1) % 3, k = (axis_ + 2) % 3;
    return u[j] * v[k] - u[k] * v[j];
  }

  // p's roots in (0, 1], as candidates. A double root (a quadratic touching
  // zero) is its derivative's root; false where roots cluster closer than
  // 2^-40 otherwise.
  bool add_roots(int source, std::vector<Candidate>& candidates) {
    const Polynomial4& p = conditions_[source];
    if (p.degree() < 1) return true;  // no root, or zero throughout: its sign never changes the truth
    if (p.at(1.0).is_zero()) candidates.push_back({Root{1, 1, true, 0}, -1, source});
    const Polynomial4* defining = &p;
    std::optional<std::vector<Root>> roots = isolate_cubic_roots(p);
    Polynomial4 slope;
    if (!roots && p.degree() == 2 && (p.c[1] * p.c[1] - p.c[0] * p.c[2] * 4.0).is_zero()) {
      slope = derivative(p);
      defining = &slope;
      roots = isolate_cubic_roots(slope);
    }
    if (!roots) return false;
    if (roots->empty()) return true;
    defining_.push_back(*defining);
    for (const Root& root : *roots) candidates.push_back({root, static_cast<int>(defining_.size()) - 1, source});
    return true;
  }

  // Whether the condition holds at the candidate (a root of `defining`, or
  // exact, where condition `source` vanishes); nullopt when signs do not
  // settle it, or w vanishes there.
  std::optional<bool> holds(const Polynomial4* defining, Root& root, int source) const {
    std::array<bool, 2> positive{}, negative{};
    for (int k = 0; k < static_cast<int>(conditions_.size()); ++k) {
      const std::optional<int> sign = k == source ? 0 : sign_at(conditions_[k], defining, root);
      if (!sign) return std::nullopt;
      positive[groups_[k]] |= *sign > 0;
      negative[groups_[k]] |= *sign < 0;
      if (positive[groups_[k]] && negative[groups_[k]]) return false;
    }
    const std::optional<int> area = sign_at(area_, defining, root);
    if (!area || *area == 0) return std::nullopt;
    return true;
  }

  // The sign of q at the root of `defining` (or the exact time), narrowing
  // the root as far as the sign needs: q's value and slope against the
  // interval (sign_by_slope), the remainder of two quadratics, then at the
  // doubles' grid the remainder sequence in integers (sign_in_integers); nullopt
  // where `defining` vanishes at an end of the interval.
  static std::optional<int> sign_at(const Polynomial4& q, const Polynomial4* defining, Root& root) {
    if (root.exact || q.degree() < 1) return q.at(root.low).sign();
    if (const auto sign = sign_by_slope(q, root)) return sign;
    if (const auto sign = sign_by_remainder(q, *defining, root)) return sign;
    for (const int bits : {kGridBits, kDoubleGridBits}) {
      narrow_to_grid(*defining, root, bits);
      if (root.exact) return q.at(root.low).sign();
      if (const auto sign = sign_by_slope(q, root)) return sign;
    }
    return sign_in_integers(as_integers(*defining), q, root);
  }

  // The sign of q at the root of p in (root.low, root.high), both of degree
  // at most 2, with no narrowing: with p = a t^2 + b t + c and q = d t^2 +
  // e t + f, a q - d p = alpha t + beta, so at the root r the sign of q is
  // that of a (alpha r + beta), and r lies above rho = -beta / alpha exactly
  // when rho is at or below the interval, or inside it where p has the
  // sign it has below r, sign_after_low (alpha^2 p(rho) = a beta^2 - b alpha beta +
  // c alpha^2; zero there: rho is r, and q vanishes). Linear p: b^2 q(-c/b).
  // The operands are scaled by powers of two to a largest term near 1 and
  // must keep every term above 2^-150 of it: then no product of five of
  // them falls below 2^-1010, and all stay exact. nullopt otherwise.
  static std::optional<int> sign_by_remainder(Polynomial4 q, Polynomial4 p, const Root& root) {
    const int degree = p.degree();
    if (degree < 1 || degree > 2 || q.degree() > 2 || !scaled_to_unit(p, 0x1p-150) || !scaled_to_unit(q, 0x1p-150))
      return std::nullopt;
    const auto coefficient = [](const Polynomial4& polynomial, int i) {
      return i < polynomial.size ? polynomial.c[i] : Value();
    };
    const Value &c = p.c[0], &b = p.c[1], f = coefficient(q, 0), e = coefficient(q, 1), d = coefficient(q, 2);
    if (degree == 1) return (d * c * c - e * b * c + f * b * b).sign();
    const Value& a = p.c[2];
    const Value alpha = a * e - d * b, beta = a * f - d * c;
    if (alpha.is_zero()) return a.sign() * beta.sign();
    // The sign of rho - t: of -(beta + alpha t) / alpha.
    const auto rho_beyond = [&](double t) { return -(beta + alpha * t).sign() * alpha.sign(); };
    int r_above_rho = 0;
    if (rho_beyond(root.low) <= 0) {
      r_above_rho = 1;
    } else if (rho_beyond(root.high) >= 0) {
      r_above_rho = -1;
    } else {
      const int p_at_rho = (a * beta * beta - b * alpha * beta + c * alpha * alpha).sign();
      if (p_at_rho == 0) return 0;
      r_above_rho = p_at_rho == root.sign_after_low ? 1 : -1;  // p's sign below r: rho is below
    }
    return a.sign() * alpha.sign() * r_above_rho;
  }

  int axis_;
  Polynomial4 area_;
  std::vector<Polynomial4> conditions_;
  std::array<int, 4> groups_{};
  std::vector<Polynomial4> defining_;  // the polynomials whose roots are candidates
};

std::optional<ExactOutcome> solve(Kind kind, const Query& query, bool need_toi, double tmax) {
  const Motion<Polynomial4> motion = moving_vectors(kind, query);
  const Polynomial4 cubic = coplanarity_cubic(motion);
  if (cubic.degree() < 0) {  // coplanar motion: decided in its plane where one is certified
    const std::optional<int> axis = exact_plane_axis(query);
    if (!axis) return std::nullopt;
    return PlanarContact(kind, motion, *axis).solve(need_toi, tmax);
  }
  const std::optional<std::vector<Root>> inner = isolate_cubic_roots(cubic);
  if (!inner) return std::nullopt;
  std::vector<Root> candidates;
  if (cubic.c[0].is_zero()) candidates.push_back({0, 0, true, 0});
  candidates.insert(candidates.end(), inner->begin(), inner->end());
  if (cubic.at(1.0).is_zero()) candidates.push_back({1, 1, true, 0});

  for (Root root : candidates) {
    const std::optional<bool> after = after_tmax(cubic, root, tmax);
    if (!after) return std::nullopt;
    if (*after) break;  // and so is every later root
    // Signs too close to call on the isolating interval may settle on a
    // narrower one.
    // From the doubles' grid on, numerators still unsettled are tested for
    // a zero at the root.
    std::optional<bool> touches = touches_at(kind, motion, root);
    SignsAtRoot exact_signs(kind, motion, cubic);
    for (const int bits : {kGridBits, kDoubleGridBits}) {
      if (touches) break;
      narrow_to_grid(cubic, root, bits);
      touches = touches_at(kind, motion, root, bits == kDoubleGridBits ? &exact_signs : nullptr);
    }
    if (!touches) return std::nullopt;
    if (!*touches) continue;
    if (need_toi) narrow_to_grid(cubic, root, kGridBits);
    return ExactOutcome{true, root.low, false};
  }
  return ExactOutcome{};
}

std::optional<double> first_root(Kind kind, const Query& query, double low, double high) {
  const Polynomial4 cubic = coplanarity_cubic(moving_vectors(kind, query));
  const std::optional<std::vector<Root>> roots = isolate_cubic_roots(cubic);
  if (!roots || !on_time_grid(low)) return std::nullopt;
  for (Root root : *roots) {
    if (root.high < low || (!root.exact && root.high == low)) continue;
    if (root.low > high) break;
    if (!root.exact && root.low < low) {  // the root may lie below low
      const int sign = cubic.at(low).sign();
      if (sign == 0) return low;
      if (sign != root.sign_after_low) continue;
    }
    narrow_to_grid(cubic, root, kGridBits);
    if (root.low > high) return std::nullopt;  // [low, high] held no root after all
    return std::max(root.low, low);
  }
  return std::nullopt;
}

// `answer` on the query normalized, or nullopt where the expansions cannot
// hold it (a coordinate spread, a result longer than their capacity).
template <class Answer>
auto on_normalized(const Query& query, Answer answer) -> decltype(answer(query)) {
  const std::optional<Query> scaled = normalized(query, kCoordinateFloor);
  if (!scaled) return std::nullopt;
  try {
    return answer(*scaled);
  } catch (const BoundedExpansion::TooLong&) {
    return std::nullopt;
  }
}

}  // namespace

std::optional<ExactOutcome> solve_with_expansions(Kind kind, const Query& query, bool need_toi, double tmax) {
  return on_normalized(query, [&](const Query& scaled) { return solve(kind, scaled, need_toi, tmax); });
}

std::optional<double> first_root_with_expansions(Kind kind, const Query& query, double low, double high) {
  return on_normalized(query, [&](const Query& scaled) { return first_root(kind, scaled, low, high); });
}

}  // namespace batchccd::exact

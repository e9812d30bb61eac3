// The stiff and extreme suite (extreme_suite.hpp).
//
// Every query is one construction, a "pair": lattice directions e1, e2 with
// normal n = e1 x e2, and the second primitive placed by (i, j, s):
//   vertex-face: triangle a, a + size e1, a + size e2; vertex a + i e1 + j e2 + s n;
//   edge-edge:   edge a, a + size e1; edge b0 = a + i e1 - j e2 + s n, b1 = b0 + size e2.
// (i, j, s) move linearly from `start` to `end` and a common drift moves the
// whole pair, so the second primitive translates relative to the first. As
// e1, e2, n are independent, they touch at t exactly when s(t) = 0 and
// (i(t), j(t)) lies in the first primitive's region: the triangle i, j >= 0,
// i + j <= size (VF), the square [0, size]^2 (EE). With integer parameters
// small enough that every point is an exact double (a lattice pair), that is
// a few linear inequalities in t with integer coefficients: the truth and
// the first contact, exactly. Real pairs draw the same parameters as
// arbitrary doubles: rounded, so their truth is left to exact mode.

#include "extreme_suite.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

namespace batchccd::scenes {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// splitmix64, and only plain arithmetic on its bits: the standard library's
// distributions differ between implementations.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }  // [0, 1)
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  double sign() { return (next() >> 63) != 0 ? 1.0 : -1.0; }
  // 10^x for x uniform in [low, high]: magnitudes spread evenly over decades.
  double decades(double low, double high) { return std::pow(10.0, uniform(low, high)); }
  // Coordinates uniform in [-half_width, half_width], drawn in a fixed order
  // (the order of a constructor's arguments is unspecified).
  Vec3 vector(double half_width) {
    Vec3 v;
    for (int axis = 0; axis < 3; ++axis) v[axis] = uniform(-half_width, half_width);
    return v;
  }

 private:
  std::uint64_t state_;
};

// When s(t) passes zero, for crossing motions.
enum class Timing { random, at_start, at_end };
// crossing: s goes through zero at the event time; hover: s at t0 and t1
// drawn independently (a crossing only when their signs differ).
enum class NormalMotion { crossing, hover };
// Which primitives keep their t0 positions (first: the face or edge a).
enum class Still { none, first, second, all };

// How a category draws its pairs. Lengths of i, j are in units of e1, e2 and
// of s in units of n.
struct Recipe {
  bool lattice = true;  // integer parameters: exact points, constructed truth
  double offset = 0;    // the origin's coordinates within +-offset
  double direction = 4;         // e1's (and e2's) coordinates within +-direction
  double parallel_tilt = 0;     // > 0: e2 = e1 + a vector within +-tilt (nearly parallel edges)
  double parallel_decades = 0;  // the tilt spread over this many decades below parallel_tilt
  double size = 16;
  double in_plane_travel = 16;  // i and j each change by up to this
  double normal_travel = 8;     // crossing: |s1 - s0| up to this; hover: |s0|, |s1| up to this
  double hover_decades = 0;     // hover: |s0|, |s1| spread over this many decades below normal_travel
  // The in-plane miss distance at the event, 10^[low, high] (i, j units),
  // outward or inward with equal odds.
  double margin_low = -1, margin_high = 0.7;
  double drift = 0;   // the common displacement's coordinates within +-drift
  double scale = 1;   // every coordinate's final factor (a power of two for lattice pairs)
  Timing timing = Timing::random;
  NormalMotion normal = NormalMotion::crossing;
  Still still = Still::none;
  bool contacts_only = false;  // lattice: inward margins, redrawn until a contact
};

struct Pair {
  Vec3 origin, e1, e2;
  double size = 1;
  Vec3 start, end;  // (i, j, s) at t0 and t1
  Vec3 drift = Vec3::Zero();
  Vec3 normal() const { return e1.cross(e2); }
};

// The second primitive's anchor (vertex, or b0) relative to the origin.
Vec3 anchor_offset(Kind kind, const Pair& pair, const Vec3& ijs) {
  const double j_sign = kind == Kind::vertex_face ? 1 : -1;
  return pair.e1 * ijs[0] + pair.e2 * (j_sign * ijs[1]) + pair.normal() * ijs[2];
}

// The four points in Query order at one end of the step.
std::array<Vec3, 4> points(Kind kind, const Pair& pair, const Vec3& ijs, const Vec3& shift) {
  const Vec3 a = pair.origin + shift;
  const Vec3 anchor = a + anchor_offset(kind, pair, ijs);
  if (kind == Kind::vertex_face) return {anchor, a, a + pair.size * pair.e1, a + pair.size * pair.e2};
  return {a, a + pair.size * pair.e1, anchor, anchor + pair.size * pair.e2};
}

// ------------------------------------------------------ drawing a pair

class PairDrawer {
 public:
  PairDrawer(Random& random, Kind kind, const Recipe& recipe)
      : random_(random), kind_(kind), recipe_(recipe) {}

  Pair draw() {
    Pair pair;
    pair.origin = quantize(random_.vector(recipe_.offset));
    draw_directions(pair);
    pair.size = quantize(recipe_.size);
    const bool all_still = recipe_.still == Still::all;
    double s0 = 0, s1 = 0;
    if (recipe_.normal == NormalMotion::hover) {
      s0 = quantize(hover_height());
      s1 = all_still ? s0 : quantize(hover_height());
    } else {
      const double travel = random_.sign() * recipe_.normal_travel * random_.uniform(0.5, 1);
      const double crossing = event_time();
      s0 = quantize(travel * crossing);
      s1 = all_still ? s0 : quantize(travel * (crossing - 1));
    }
    // The in-plane path passes near the region's boundary at the event, when
    // s is zero (after quantizing), so that the decision hangs on the margin.
    const double event = s0 * s1 <= 0 && s0 != s1 ? s0 / (s0 - s1) : event_time();
    const Eigen::Vector2d target = near_boundary(pair.size);
    Eigen::Vector2d travel = Eigen::Vector2d::Zero();
    if (!all_still)
      for (int axis = 0; axis < 2; ++axis)
        travel[axis] = quantize(random_.uniform(-recipe_.in_plane_travel, recipe_.in_plane_travel));
    const Eigen::Vector2d start = (target - event * travel).unaryExpr([&](double x) { return quantize(x); });
    const Eigen::Vector2d end = start + travel;
    pair.start = {start.x(), start.y(), s0};
    pair.end = {end.x(), end.y(), s1};
    if (recipe_.still == Still::none) pair.drift = quantize(random_.vector(recipe_.drift));
    // Cancels the second primitive's own motion (exactly on the lattice).
    if (recipe_.still == Still::second)
      pair.drift = anchor_offset(kind_, pair, pair.start) - anchor_offset(kind_, pair, pair.end);
    return pair;
  }

 private:
  double quantize(double x) const { return recipe_.lattice ? std::round(x) : x; }
  Vec3 quantize(const Vec3& v) const { return v.unaryExpr([&](double x) { return quantize(x); }); }

  // Independent directions (well shaped: the normal at least a quarter of
  // the largest possible), or nearly parallel ones when asked.
  void draw_directions(Pair& pair) {
    for (;;) {
      pair.e1 = quantize(random_.vector(recipe_.direction));
      if (recipe_.parallel_tilt > 0) {
        const double tilt = recipe_.parallel_tilt * random_.decades(-recipe_.parallel_decades, 0);
        pair.e2 = pair.e1 + quantize(random_.vector(tilt));
      } else {
        pair.e2 = quantize(random_.vector(recipe_.direction));
      }
      const double area = pair.normal().norm();
      const double shape = recipe_.parallel_tilt > 0 ? 0 : 0.25 * pair.e1.norm() * pair.e2.norm();
      if (area > shape) return;
    }
  }

  double event_time() {
    switch (recipe_.timing) {
      case Timing::at_start: return 0;
      case Timing::at_end: return 1;
      case Timing::random: break;
    }
    return random_.uniform(0.1, 0.9);
  }

  double hover_height() {
    return random_.sign() * recipe_.normal_travel * random_.decades(-recipe_.hover_decades, 0);
  }

  // A point on a random side of the region (a corner one time in eight),
  // moved outward by a signed margin (negative: inward).
  Eigen::Vector2d near_boundary(double size) {
    const double along = random_.uniform() < 0.125 ? 0 : quantize(random_.uniform() * size);
    const double side = random_.uniform();
    Eigen::Vector2d point, outward;
    if (kind_ == Kind::vertex_face) {  // sides i = 0, j = 0, i + j = size
      if (side < 1.0 / 3) {
        point = {0, along};
        outward = {-1, 0};
      } else if (side < 2.0 / 3) {
        point = {along, 0};
        outward = {0, -1};
      } else {
        point = {along, size - along};
        outward = {1, 1};
      }
    } else {  // sides i = 0, i = size, j = 0, j = size
      const bool high = side >= 0.5;
      const bool first_axis = side < 0.25 || (high && side < 0.75);
      const double level = high ? size : 0;
      point = first_axis ? Eigen::Vector2d(level, along) : Eigen::Vector2d(along, level);
      outward = (first_axis ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1)) * (high ? 1 : -1);
    }
    const double sign = recipe_.contacts_only ? -1 : random_.sign();
    const double margin = quantize(sign * random_.decades(recipe_.margin_low, recipe_.margin_high));
    return point + margin * outward;
  }

  Random& random_;
  Kind kind_;
  const Recipe& recipe_;
};

// ------------------------------------------------------ exact truth of a lattice pair

__extension__ using Wide = __int128;  // products of two 64-bit integers

struct Fraction {
  Wide numerator, denominator;  // denominator > 0
  bool operator<(const Fraction& other) const {
    return numerator * other.denominator < other.numerator * denominator;
  }
};

// a + b t >= 0
struct Constraint {
  std::int64_t a, b;
};

// The least t in [0, 1] meeting every constraint, or none.
std::optional<Fraction> first_feasible_time(const std::vector<Constraint>& constraints) {
  Fraction low{0, 1}, high{1, 1};
  for (const auto [a, b] : constraints) {
    if (b == 0) {
      if (a < 0) return std::nullopt;
    } else if (b > 0) {
      low = std::max(low, Fraction{-a, b});
    } else {
      high = std::min(high, Fraction{a, -b});
    }
  }
  if (high < low) return std::nullopt;
  return low;
}

// The largest double not above the fraction (numerator and denominator
// below 2^53, so both convert exactly and the division's remainder is exact).
double round_down(const Fraction& t) {
  const double numerator = static_cast<double>(t.numerator);
  const double denominator = static_cast<double>(t.denominator);
  const double quotient = numerator / denominator;
  return std::fma(quotient, denominator, -numerator) > 0 ? std::nextafter(quotient, -kInfinity)
                                                         : quotient;
}

// The first contact of a lattice pair (none: no contact), from the
// inequalities of the file comment.
std::optional<Fraction> first_contact(Kind kind, const Pair& pair) {
  const auto integer = [](double x) { return static_cast<std::int64_t>(x); };
  // Coefficients of a coordinate's linear path: value at t0, change.
  const auto path = [&](int axis) {
    return Constraint{integer(pair.start[axis]), integer(pair.end[axis] - pair.start[axis])};
  };
  const Constraint i = path(0), j = path(1), s = path(2);
  const std::int64_t size = integer(pair.size);
  std::vector<Constraint> constraints{s, {-s.a, -s.b}, i, j};  // s = 0, i >= 0, j >= 0
  if (kind == Kind::vertex_face) {
    constraints.push_back({size - i.a - j.a, -i.b - j.b});
  } else {
    constraints.push_back({size - i.a, -i.b});
    constraints.push_back({size - j.a, -j.b});
  }
  return first_feasible_time(constraints);
}

// ------------------------------------------------------ queries

// The query of a pair, scaled. On a lattice pair every coordinate must be
// exact, or the constructed truth would not be the inputs' truth: the
// recipes keep every term and partial sum an integer below 2^42, and the
// check below guards the results (integers, scaled by a power of two within
// the normal range).
Query make_query(Kind kind, const Pair& pair, const Recipe& recipe) {
  const std::array<Vec3, 4> at_t0 = points(kind, pair, pair.start, Vec3::Zero());
  const std::array<Vec3, 4> at_t1 = points(kind, pair, pair.end, pair.drift);
  Query query;
  for (int k = 0; k < 4; ++k) {
    query.points[k] = at_t0[k];
    query.points[k + 4] = at_t1[k];
  }
  // The second primitive exactly still, also where rounding moved it.
  if (recipe.still == Still::second)
    for (int k = kind == Kind::vertex_face ? 0 : 2; k < (kind == Kind::vertex_face ? 1 : 4); ++k)
      query.points[k + 4] = query.points[k];
  for (Vec3& point : query.points)
    for (double& x : point) {
      const double scaled = x * recipe.scale;
      if (recipe.lattice &&
          !(std::abs(x) < 0x1p53 && x == std::round(x) && scaled / recipe.scale == x &&
            (x == 0 || std::abs(scaled) >= DBL_MIN)))
        throw std::logic_error("extreme suite: a lattice coordinate is not exact");
      x = scaled;
    }
  return query;
}

// One query of a recipe into the category, with its truth where known.
void add_query(ExtremeCategory& category, Random& random, const Recipe& recipe) {
  PairDrawer drawer(random, category.kind, recipe);
  for (;;) {
    const Pair pair = drawer.draw();
    const Query query = make_query(category.kind, pair, recipe);
    std::optional<Fraction> contact;
    if (recipe.lattice) contact = first_contact(category.kind, pair);
    if (recipe.contacts_only && !contact) continue;  // a corner's inward step left the region
    category.queries.push_back(query);
    category.constructed_truth.push_back(recipe.lattice ? static_cast<signed char>(contact.has_value()) : -1);
    category.constructed_first_contact.push_back(contact ? round_down(*contact) : kInfinity);
    return;
  }
}

struct CategorySpec {
  std::string name, description;
  std::vector<Kind> kinds;
  std::vector<Recipe> recipes;  // used in turn
};

const std::vector<Kind> kBothKinds{Kind::vertex_face, Kind::edge_edge};

std::vector<CategorySpec> category_specs() {
  std::vector<CategorySpec> specs;
  specs.push_back(
      {"stiff 1e-10",
       "primitives 1e-3 of the coordinates moving 1e-10 of them; near misses down to rounding",
       kBothKinds,
       {{.offset = 0x1p40, .size = 0x1p28, .in_plane_travel = 64, .normal_travel = 8, .drift = 64},
        {.lattice = false, .offset = 1e3, .direction = 1, .size = 1, .in_plane_travel = 1e-7,
         .normal_travel = 1e-7, .margin_low = -16, .margin_high = -7, .drift = 1e-7}}});
  specs.push_back(
      {"fast x1e3", "vertices move about 1e3 primitive sizes in the step, crossing near the boundary",
       kBothKinds,
       {{.offset = 0x1p20, .in_plane_travel = 16e3, .normal_travel = 2e3, .drift = 64e3},
        {.lattice = false, .offset = 1, .direction = 1, .size = 1, .in_plane_travel = 1e3,
         .normal_travel = 1e3, .margin_low = -14, .margin_high = -1, .drift = 1e3}}});
  const auto scaled = [](double lattice_scale, double real_scale) {
    return std::vector<Recipe>{
        {.offset = 0x1p24, .size = 0x1p12, .in_plane_travel = 0x1p12, .normal_travel = 0x1p9,
         .scale = lattice_scale},
        {.lattice = false, .offset = 1, .direction = 1, .size = 1, .in_plane_travel = 1,
         .normal_travel = 1, .margin_low = -15, .margin_high = -1, .scale = real_scale}};
  };
  specs.push_back({"tiny 1e-300", "unit-scale crossings scaled to coordinates near 1e-300",
                   kBothKinds, scaled(0x1p-1020, 1e-300)});
  specs.push_back({"huge 1e300", "unit-scale crossings scaled to coordinates near 1e300",
                   kBothKinds, scaled(0x1p973, 1e300)});
  specs.push_back(
      {"near-coplanar",
       "sliding across the boundary at heights 1e-5 to 1e-16 of the size; some exactly coplanar",
       kBothKinds,
       {{.offset = 0x1p30, .size = 0x1p20, .in_plane_travel = 0x1p20, .normal_travel = 2,
         .hover_decades = 1, .normal = NormalMotion::hover},
        {.lattice = false, .offset = 1, .direction = 1, .size = 1, .in_plane_travel = 1,
         .normal_travel = 1e-6, .hover_decades = 10, .margin_low = -15, .margin_high = -1,
         .normal = NormalMotion::hover}}});
  specs.push_back(
      {"near-parallel EE", "edges 1e-3 to 1e-12 radians from parallel, crossing near an end",
       {Kind::edge_edge},
       {{.offset = 0x1p30, .direction = 0x1p12, .parallel_tilt = 1, .size = 0x1p10,
         .in_plane_travel = 0x1p10, .normal_travel = 16},
        {.lattice = false, .offset = 1, .direction = 1, .parallel_tilt = 1e-3,
         .parallel_decades = 9, .size = 1, .in_plane_travel = 1, .normal_travel = 1,
         .margin_low = -15, .margin_high = -1}}});
  const auto touching = [](Timing timing) {
    return std::vector<Recipe>{
        {.offset = 0x1p30, .direction = 8, .size = 0x1p10, .in_plane_travel = 0x1p10,
         .normal_travel = 0x1p6, .drift = 0x1p10, .timing = timing, .contacts_only = true},
        {.offset = 0x1p30, .direction = 8, .size = 0x1p10, .in_plane_travel = 0x1p10,
         .normal_travel = 0x1p6, .scale = 0x1p-60, .timing = timing, .still = Still::first,
         .contacts_only = true}};
  };
  specs.push_back({"contact t=0", "touching at exactly t = 0 (inside, on a side or a corner), exact coordinates",
                   kBothKinds, touching(Timing::at_start)});
  specs.push_back({"contact t=1", "first touching at exactly t = 1 (inside, on a side or a corner), exact coordinates",
                   kBothKinds, touching(Timing::at_end)});
  specs.push_back(
      {"static vertices",
       "all still (touching, near or far apart), or one primitive still while the other crosses",
       kBothKinds,
       {{.normal_travel = 0, .still = Still::all},
        {.normal_travel = 64, .normal = NormalMotion::hover, .still = Still::all},
        {.still = Still::first},
        {.still = Still::second},
        {.lattice = false, .offset = 1, .direction = 1, .size = 1, .in_plane_travel = 1,
         .normal_travel = 1e-8, .hover_decades = 8, .margin_low = -15, .margin_high = -1,
         .normal = NormalMotion::hover, .still = Still::all},
        {.lattice = false, .offset = 1, .direction = 1, .size = 1, .in_plane_travel = 1,
         .normal_travel = 1, .margin_low = -15, .margin_high = -1, .still = Still::first},
        {.lattice = false, .offset = 1, .direction = 1, .size = 1, .in_plane_travel = 1,
         .normal_travel = 1, .margin_low = -15, .margin_high = -1, .still = Still::second}}});
  return specs;
}

// ------------------------------------------------------ evaluation

bool well_formed(const QueryResult& result) {
  return result.hit ? result.toi >= 0 && result.toi <= 1 : result.toi == kInfinity;
}

ExtremeRow row_against_exact(const ExtremeCategory& category, const lab::Method& method, BatchResult batch,
                             const BatchResult& exact) {
  ExtremeRow row;
  row.category = category.name;
  row.kind = category.kind;
  row.method = method;
  row.queries = static_cast<std::int64_t>(category.queries.size());
  for (std::size_t q = 0; q < category.queries.size(); ++q) {
    const QueryResult& result = batch.results[q];
    const bool truth = exact.results[q].hit;
    row.agree += result.hit == truth;
    row.false_negatives += truth && !result.hit;
    row.false_positives += !truth && result.hit;
    row.nan_tois += std::isnan(result.toi);
    row.malformed_tois += !std::isnan(result.toi) && !well_formed(result);
    if (category.constructed_truth[q] >= 0) {
      ++row.truth_known;
      row.truth_disagreements += result.hit != (category.constructed_truth[q] == 1);
      row.late_tois += result.hit && result.toi > category.constructed_first_contact[q];
    }
  }
  row.batch = std::move(batch);
  return row;
}

}  // namespace

std::vector<ExtremeCategory> extreme_categories(int queries_per_category) {
  std::vector<ExtremeCategory> categories;
  std::uint64_t seed = 0x5eedULL << 32;
  for (const CategorySpec& spec : category_specs())
    for (const Kind kind : spec.kinds) {
      ExtremeCategory category{spec.name, spec.description, kind, {}, {}, {}};
      Random random(++seed);
      for (int q = 0; q < queries_per_category; ++q)
        add_query(category, random, spec.recipes[static_cast<std::size_t>(q) % spec.recipes.size()]);
      categories.push_back(std::move(category));
    }
  return categories;
}

std::vector<ExtremeRow> evaluate_extreme(const std::vector<ExtremeCategory>& categories,
                                         const Options& options) {
  const auto run = [&](const ExtremeCategory& category, const lab::Method& method) {
    Options with_method = method.applied_to(options);
    with_method.time_queries = true;
    with_method.per_candidate_results = true;
    return lab::batch_ccd(category.kind, category.queries, with_method, method.settings());
  };
  std::vector<ExtremeRow> rows;
  for (const ExtremeCategory& category : categories) {
    const BatchResult exact = run(category, lab::kExact);
    rows.push_back(row_against_exact(category, lab::kExact, exact, exact));
    for (const lab::Method& method : {lab::kConservative, lab::kFast, lab::kCubic})
      rows.push_back(row_against_exact(category, method, run(category, method), exact));
  }
  return rows;
}

void write_extreme_table(std::ostream& out, const std::vector<ExtremeRow>& rows) {
  struct Column {
    const char* title;
    int width;
  };
  const std::array<Column, 15> columns{{{"category", 17}, {"kind", 4}, {"mode", 12},
                                        {"queries", 7}, {"hits", 5}, {"agree", 5},
                                        {"false-", 6}, {"false+", 6}, {"NaN", 3},
                                        {"bad toi", 7}, {"late toi", 8}, {"truth wrong", 11},
                                        {"escalated", 9}, {"undecided", 9}, {"max ms", 8}}};
  const auto line = [&](const std::array<std::string, 15>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (c == 0) {
        out << std::left << std::setw(columns[c].width) << cells[c] << std::right;
      } else {
        out << "  " << std::setw(columns[c].width) << cells[c];
      }
    }
    out << '\n';
  };
  std::array<std::string, 15> titles;
  for (std::size_t c = 0; c < columns.size(); ++c) titles[c] = columns[c].title;
  line(titles);
  for (const ExtremeRow& row : rows) {
    const Counters& counters = row.batch.counters;
    std::ostringstream milliseconds;
    milliseconds << std::fixed << std::setprecision(3) << counters.max_query_seconds * 1e3;
    const auto text = [](std::int64_t n) { return std::to_string(n); };
    line({row.category, to_string(row.kind), lab::to_string(row.method), text(row.queries),
          text(counters.hits), text(row.agree), text(row.false_negatives),
          text(row.false_positives), text(row.nan_tois), text(row.malformed_tois),
          text(row.late_tois), text(row.truth_disagreements) + "/" + text(row.truth_known),
          text(counters.exact_escalations), text(counters.undecided), milliseconds.str()});
  }
}

}  // namespace batchccd::scenes

#include "exact/plane_axis.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "exact/exact_motion.hpp"
#include "exact/expansion.hpp"

namespace batchccd::exact {
namespace {

// Whether d may lie in the plane of a, b, c: orient3d(a, b, c, d) in
// double is within its error bound of 0 (generous: a difference's rounding,
// two products and two sums on each term's path, well under 32 u of the
// permanent). Inputs normalized: nothing overflows or underflows.
bool may_be_in_plane(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = a - d, v = b - d, w = c - d;
  const double determinant = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                             u[2] * (v[0] * w[1] - v[1] * w[0]);
  const Vec3 au = u.cwiseAbs(), av = v.cwiseAbs(), aw = w.cwiseAbs();
  const double permanent = au[0] * (av[1] * aw[2] + av[2] * aw[1]) + au[1] * (av[2] * aw[0] + av[0] * aw[2]) +
                           au[2] * (av[0] * aw[1] + av[1] * aw[0]);
  return std::fabs(determinant) <= 0x1p-48 * permanent;
}

// The plane through a, b, c in exact arithmetic: a point d lies in it when
// (d - a) . n = 0 with n = (b - a) x (c - a), the normal formed once.
class ExactPlane {
 public:
  ExactPlane(const Vec3& a, const Vec3& b, const Vec3& c) : a_(a) {
    std::array<Expansion<2>, 3> ab, ac;
    for (int i = 0; i < 3; ++i) {
      ab[i] = difference(b[i], a[i]);
      ac[i] = difference(c[i], a[i]);
    }
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      normal_[i] = ab[j] * ac[k] - ab[k] * ac[j];
    }
  }

  // The sign of the normal's component along `axis`: 0 when the triangle
  // a, b, c projects onto a line there.
  int normal_sign(int axis) const { return normal_[axis].sign(); }

  bool contains(const Vec3& d) const {
    const auto term = [&](int i) { return difference(d[i], a_[i]) * normal_[i]; };
    return (term(0) + term(1) + term(2)).sign() == 0;
  }

 private:
  Vec3 a_;
  std::array<Expansion<16>, 3> normal_;
};

double largest_component(const Vec3& v) { return v.cwiseAbs().maxCoeff(); }

#ifdef __SIZEOF_INT128__
__extension__ using Int128 = __int128;

// Coordinates below 2 in magnitude (normalized) on a common grid of 2^-39
// or coarser, as exact integers: then an orientation fits in 128 bits
// (differences below 2^41, normal components below 2^83, a dot below
// 2^126), far cheaper than expansions. Synthetic and quantized data
// usually are; nullopt when the grid is finer.
using GridPoints = std::array<std::array<std::int64_t, 3>, 8>;
std::optional<GridPoints> on_integer_grid(const Query& normalized) {
  int lowest = 1;  // the exponent of the lowest set bit of any coordinate
  for (const Vec3& point : normalized.points)
    for (int axis = 0; axis < 3; ++axis) {
      if (point[axis] == 0) continue;
      // A normal double is (2^52 + fraction) 2^(biased exponent - 1075).
      const auto bits = std::bit_cast<std::uint64_t>(point[axis]);
      const int biased = static_cast<int>((bits >> 52) & 0x7ff);
      const std::uint64_t significand = (bits & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
      lowest = std::min(lowest, biased - 1075 + std::countr_zero(significand));
    }
  if (lowest < -39) return std::nullopt;
  const double factor = std::ldexp(1.0, -lowest);
  GridPoints grid;
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis)
      grid[i][axis] = static_cast<std::int64_t>(normalized.points[i][axis] * factor);
  return grid;
}

// The plane test of exact_plane_axis on grid integers: false when a point
// is off the plane of the references or the projection along `axis` folds it.
bool integer_plane(const GridPoints& p, int origin, int far, int third, int axis) {
  std::array<std::int64_t, 3> ab, ac;
  for (int i = 0; i < 3; ++i) {
    ab[i] = p[far][i] - p[origin][i];
    ac[i] = p[third][i] - p[origin][i];
  }
  std::array<Int128, 3> normal;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    normal[i] = Int128{ab[j]} * ac[k] - Int128{ab[k]} * ac[j];
  }
  if (normal[axis] == 0) return false;  // the references fold onto a line there
  for (int d = 0; d < 8; ++d) {
    Int128 dot = 0;
    for (int i = 0; i < 3; ++i) dot += normal[i] * (p[d][i] - p[origin][i]);
    if (dot != 0) return false;
  }
  return true;
}
#endif

}  // namespace

bool shares_coordinate(const Query& query, int axis) {
  const auto shared_at = [&](int first) {
    const double value = query.points[first][axis];
    for (int i = first; i < first + 4; ++i)
      if (query.points[i][axis] != value) return false;
    return true;
  };
  return shared_at(0) && shared_at(4);
}

std::optional<int> shared_axis(const Query& query) {
  for (int axis = 0; axis < 3; ++axis)
    if (shares_coordinate(query, axis)) return axis;
  return std::nullopt;
}

std::optional<int> exact_plane_axis(const Query& query) {
  if (const auto axis = shared_axis(query)) return axis;
  const std::optional<Query> scaled = normalized(query, -200);
  if (!scaled) return std::nullopt;
  // Three reference points spanning the plane: the first, the farthest from
  // it, and the one making the largest normal with those two.
  const auto& points = scaled->points;
  const Vec3& origin = points[0];
  int far = 0;
  for (int i = 1; i < 8; ++i)
    if (largest_component(points[i] - origin) > largest_component(points[far] - origin)) far = i;
  if (far == 0) return std::nullopt;  // one point: the coincident case
  int third = 0;
  Vec3 normal = Vec3::Zero();
  for (int i = 1; i < 8; ++i) {
    const Vec3 candidate = (points[far] - origin).cross(points[i] - origin);
    if (largest_component(candidate) > largest_component(normal)) {
      normal = candidate;
      third = i;
    }
  }
  if (third == 0) return std::nullopt;  // collinear throughout (as far as double tells)
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  const Vec3 &a = origin, &b = points[far], &c = points[third];
  // Whether `test` holds for every point but the references.
  const auto others = [&](auto&& test) {
    for (int i = 1; i < 8; ++i)
      if (i != far && i != third && !test(points[i])) return false;
    return true;
  };
#ifdef __SIZEOF_INT128__
  // Exact and cheap on a grid: no filter needed first.
  if (const std::optional<GridPoints> grid = on_integer_grid(*scaled))
    return integer_plane(*grid, 0, far, third, axis) ? std::optional<int>(axis) : std::nullopt;
#endif
  // A generic query leaves at the filter.
  if (!others([&](const Vec3& d) { return may_be_in_plane(a, b, c, d); })) return std::nullopt;
  const ExactPlane plane(a, b, c);
  // The projection maps the plane one to one when the references stay a
  // proper triangle in it.
  if (plane.normal_sign(axis) == 0) return std::nullopt;
  if (!others([&](const Vec3& d) { return plane.contains(d); })) return std::nullopt;
  return axis;
}

}  // namespace batchccd::exact

#include "exact/exact_motion.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include "reference/scaled_query.hpp"

namespace batchccd::exact {
namespace {

// value = mantissa * 2^exponent with an odd mantissa (or zero).
struct DyadicDouble {
  std::int64_t mantissa = 0;
  int exponent = 0;
};

DyadicDouble decompose(double value) {
  if (value == 0) return {};
  int exponent = 0;
  const double fraction = std::frexp(value, &exponent);  // in [0.5, 1)
  auto mantissa = static_cast<std::int64_t>(std::ldexp(fraction, 53));  // exact
  exponent -= 53;
  const int trailing = __builtin_ctzll(static_cast<unsigned long long>(mantissa < 0 ? -mantissa : mantissa));
  return {mantissa >> trailing, exponent + trailing};
}

}  // namespace

RelativeMotion exact_relative_motion(Kind kind, const Query& query) {
  std::array<std::array<DyadicDouble, 3>, 8> parts;
  int smallest_exponent = INT_MAX;
  for (int point = 0; point < 8; ++point)
    for (int axis = 0; axis < 3; ++axis) {
      parts[point][axis] = decompose(query.points[point][axis]);
      if (parts[point][axis].mantissa != 0)
        smallest_exponent = std::min(smallest_exponent, parts[point][axis].exponent);
    }
  auto integer = [&](int point, int axis) {
    const DyadicDouble& part = parts[point][axis];
    Integer value(static_cast<long>(part.mantissa));
    if (part.mantissa != 0)
      value.shift_left(static_cast<unsigned long>(part.exponent - smallest_exponent));
    return value;
  };

  RelativeMotion motion;
  Integer common;  // gcd of every coefficient
  for (int i = 0; i < 3; ++i) {
    const int origin = reference::point_index(kind, 1);
    const int point = reference::point_index(kind, i + 2);
    for (int axis = 0; axis < 3; ++axis) {
      const Integer start = integer(point, axis) - integer(origin, axis);
      const Integer end = integer(point + 4, axis) - integer(origin + 4, axis);
      common = greatest_common_divisor(common, start);
      common = greatest_common_divisor(common, end);
      motion[i][axis] = linear_polynomial(start, end - start);
    }
  }
  if (common.sign() > 0 && !(common == Integer(1)))
    for (PolynomialVector& vector : motion)
      for (Polynomial& component : vector)
        for (Integer& c : component.coefficients) c = exact_quotient(c, common);
  return motion;
}

std::optional<Query> normalized(const Query& query, int floor_exponent) {
  double largest = 0;
  for (const Vec3& point : query.points) largest = std::max(largest, point.cwiseAbs().maxCoeff());
  if (largest == 0) return std::nullopt;
  const int exponent = -std::ilogb(largest);
  if (exponent < -1000 || exponent > 1000) return std::nullopt;  // 2^exponent is one double
  const double factor = std::ldexp(1.0, exponent);
  const double floor = std::ldexp(largest, floor_exponent);
  Query result;
  for (int i = 0; i < 8; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double coordinate = query.points[i][axis];
      if (coordinate != 0 && std::fabs(coordinate) < floor) return std::nullopt;
      result.points[i][axis] = coordinate * factor;  // exact: the result stays a normal double
    }
  }
  return result;
}

}  // namespace batchccd::exact

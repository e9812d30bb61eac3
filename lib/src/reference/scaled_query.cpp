#include "reference/scaled_query.hpp"

#include <cmath>

namespace batchccd::reference {
namespace {

constexpr double kSmallestSubnormal = 0x1p-1074;

// x * 2^exponent, correctly rounded, for any exponent (no overflowing factor).
Vec3 scale_by_power_of_two(const Vec3& x, int exponent) {
  return {std::ldexp(x[0], exponent), std::ldexp(x[1], exponent), std::ldexp(x[2], exponent)};
}

double largest_magnitude(const Query& query) {
  double largest = 0;
  for (const Vec3& point : query.points) largest = std::fmax(largest, point.cwiseAbs().maxCoeff());
  return largest;
}

}  // namespace

ScaledQuery scale_query(Kind kind, const Query& query) {
  ScaledQuery scaled;
  for (const Vec3& point : query.points)
    if (!point.allFinite()) {
      scaled.finite = false;
      return scaled;
    }
  const double input_magnitude = largest_magnitude(query);
  if (input_magnitude == 0) {
    scaled.coincident = true;
    return scaled;
  }
  // First normalisation (largest input in [1, 2)) so the differences below
  // cannot overflow. Scaling down may round tiny coordinates to subnormals.
  const int input_exponent = -std::ilogb(input_magnitude);
  const double input_floor = input_exponent < 0 ? kSmallestSubnormal : 0.0;

  double largest = 0;
  for (int tau = 0; tau < 2; ++tau) {
    const Vec3 origin =
        scale_by_power_of_two(query.points[point_index(kind, 1) + 4 * tau], input_exponent);
    for (int i = 0; i < 3; ++i) {
      const Vec3 point =
          scale_by_power_of_two(query.points[point_index(kind, i + 2) + 4 * tau], input_exponent);
      scaled.relative[i][tau] = point - origin;
      largest = std::fmax(largest, scaled.relative[i][tau].cwiseAbs().maxCoeff());
    }
  }
  if (largest == 0) {
    scaled.coincident = true;
    return scaled;
  }
  // Second normalisation: the largest difference in [1, 2).
  const int exponent = -std::ilogb(largest);
  for (auto& point_pair : scaled.relative)
    for (Vec3& value : point_pair) value = scale_by_power_of_two(value, exponent);
  // Both inputs of a difference may carry input_floor; scaling down by at
  // most 4 may round a subnormal once more.
  scaled.absolute_error = std::ldexp(2 * input_floor, exponent) + kSmallestSubnormal;
  return scaled;
}

}  // namespace batchccd::reference

#include "reference/scaled_query.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace batchccd::reference {
namespace {

constexpr double kSmallestSubnormal = 0x1p-1074;

// 2^exponent for -1074 <= exponent <= 1023 (subnormal below -1022).
double power_of_two(int exponent) {
  return exponent >= -1022 ? std::bit_cast<double>(static_cast<std::uint64_t>(exponent + 1023) << 52)
                           : std::bit_cast<double>(std::uint64_t{1} << (exponent + 1074));
}

// floor(log2(x)) for finite x > 0, subnormals included (std::ilogb without
// the library call).
int binary_exponent(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const int biased = static_cast<int>(bits >> 52);
  return biased > 0 ? biased - 1023 : -1011 - std::countl_zero(bits);
}

// x * 2^exponent, one correctly rounded product: the same as std::ldexp
// (a library call, several times the cost of the arithmetic) for exponent
// >= -1074. Past 2^1023 two factors, of which the first is exact: callers
// scale up by that much only values below 2^-1022.
double times_power_of_two(double x, int exponent) {
  if (exponent > 1023) return x * 0x1p1023 * power_of_two(exponent - 1023);
  return x * power_of_two(exponent);
}

// The largest magnitude of v's coordinates, and of `largest`.
double largest_of(const Vec3& v, double largest) {
  return std::max({largest, std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
}

}  // namespace

bool all_finite(const Query& query) {
  for (const Vec3& point : query.points)
    if (!point.allFinite()) return false;
  return true;
}

ScaledQuery scale_query(Kind kind, const Query& query) {
  ScaledQuery scaled;
  // One pass for both: the largest magnitude is finite when every
  // coordinate is (std::max passes over a NaN, hence the sum).
  double input_magnitude = 0, sum = 0;
  for (const Vec3& point : query.points) {
    input_magnitude = largest_of(point, input_magnitude);
    sum += point[0] + point[1] + point[2];
  }
  if (!std::isfinite(sum) && !all_finite(query)) {
    scaled.finite = false;
    return scaled;
  }
  if (input_magnitude == 0) {
    scaled.coincident = true;
    return scaled;
  }
  // Differences in the input's own units: subtraction commutes exactly with
  // power-of-two scaling (a subnormal difference of doubles is exact), so
  // the frame below does not depend on units. Only inputs within a factor 4
  // of overflow are first quartered so that no difference overflows; that
  // may round tiny coordinates to subnormals (input_floor).
  const bool huge = input_magnitude >= kHugeInput;
  const double input_factor = huge ? 0.25 : 1.0;
  const double input_floor = huge ? kSmallestSubnormal : 0.0;

  double largest = 0;
  for (int tau = 0; tau < 2; ++tau) {
    const Vec3 origin = query.points[point_index(kind, 1) + 4 * tau] * input_factor;
    for (int i = 0; i < 3; ++i) {
      const Vec3 point = query.points[point_index(kind, i + 2) + 4 * tau] * input_factor;
      scaled.relative[i][tau] = point - origin;
      largest = largest_of(scaled.relative[i][tau], largest);
    }
  }
  if (largest == 0) {
    scaled.coincident = true;
    return scaled;
  }
  // Normalisation: the largest difference in [1, 2).
  const int exponent = -binary_exponent(largest);
  if (exponent <= 1023) {  // one factor for all (times_power_of_two's product)
    const double factor = power_of_two(exponent);
    for (auto& point_pair : scaled.relative)
      for (Vec3& value : point_pair) value *= factor;
  } else {
    for (auto& point_pair : scaled.relative)
      for (Vec3& value : point_pair)
        value = {times_power_of_two(value[0], exponent), times_power_of_two(value[1], exponent),
                 times_power_of_two(value[2], exponent)};
  }
  scaled.input_factor = input_factor;
  scaled.exponent = exponent;
  // Both inputs of a difference may carry input_floor, magnified with it;
  // scaling down may round a subnormal once more.
  scaled.absolute_error = times_power_of_two(2 * input_floor, exponent) + kSmallestSubnormal;
  return scaled;
}

double to_scaled_length(const ScaledQuery& query, double length) {
  return std::max(times_power_of_two(length * query.input_factor, query.exponent), 0x1p-1022);
}

}  // namespace batchccd::reference

#pragma once

#include <cmath>

#include "reference/error_bounds.hpp"

// Midpoint-radius ("ball") arithmetic: a value known to lie within `radius`
// of `middle`, kept certified through rounding by growing the radius with
// each operation's own rounding error (u |result|) and a margin for the
// rounding of the radius itself.
namespace batchccd::reference {

struct Ball {
  double middle = 0;
  double radius = 0;

  bool certainly_positive() const { return middle > radius; }
  bool certainly_negative() const { return middle < -radius; }
};

namespace ball_detail {
inline double grown(double radius, double result) {
  return (radius + kUnitRoundoff * std::fabs(result)) * (1 + 8 * kUnitRoundoff) + kUnderflowFloor;
}
}  // namespace ball_detail

inline Ball operator+(const Ball& a, const Ball& b) {
  const double middle = a.middle + b.middle;
  return {middle, ball_detail::grown(a.radius + b.radius, middle)};
}

inline Ball operator-(const Ball& a, const Ball& b) {
  const double middle = a.middle - b.middle;
  return {middle, ball_detail::grown(a.radius + b.radius, middle)};
}

inline Ball operator*(const Ball& a, const Ball& b) {
  const double middle = a.middle * b.middle;
  const double radius =
      std::fabs(a.middle) * b.radius + std::fabs(b.middle) * a.radius + a.radius * b.radius;
  return {middle, ball_detail::grown(radius, middle)};
}

}  // namespace batchccd::reference

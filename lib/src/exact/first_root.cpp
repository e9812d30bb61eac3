#include "exact/first_root.hpp"

#include <cmath>

#include "exact/exact_motion.hpp"
#include "exact/exact_solver.hpp"
#include "exact/expansion_stage.hpp"
#include "exact/root_isolation.hpp"

namespace batchccd::exact {

std::optional<double> first_root_lower_bound(Kind kind, const Query& query, double low,
                                             double high) {
  if (const std::optional<double> toi = first_root_with_expansions(kind, query, low, high)) return toi;
  return first_root_with_integers(kind, query, low, high);
}

std::optional<double> first_root_with_integers(Kind kind, const Query& query, double low, double high) {
  // [low, high] = [k / 2^j, (k + 1) / 2^j], as bisection from [0, 1] makes it.
  int width_exponent = 0;
  if (!(high > low) || std::frexp(high - low, &width_exponent) != 0.5) return std::nullopt;
  const unsigned long exponent = static_cast<unsigned long>(1 - width_exponent);
  const double scaled_low = std::ldexp(low, 1 - width_exponent);
  if (scaled_low != std::floor(scaled_low) || scaled_low < 0 || scaled_low > 0x1p53)
    return std::nullopt;
  const Integer numerator(static_cast<long>(scaled_low));

  const RelativeMotion motion = exact_relative_motion(kind, query);
  const Polynomial cubic = square_free_part(dot(cross(motion[0], motion[1]), motion[2]));
  std::optional<std::vector<IsolatedRoot>> roots = isolate_roots(cubic, numerator, exponent);
  if (!roots || roots->empty()) return std::nullopt;
  IsolatedRoot& first = roots->front();
  while (!first.exact && first.exponent < kToiBits) halve(first, cubic);
  return lower_bound(first);
}

}  // namespace batchccd::exact

#include "fronts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace batchccd::fronts {

void require(bool holds, const char* call, const char* name, const char* expected, double value) {
  if (holds) return;
  std::ostringstream message;
  message.precision(17);
  message << call << ": " << name << " must be " << expected << ", got " << value;
  throw std::invalid_argument(message.str());
}

namespace {

double coordinate_extent(const Query& query) {
  double extent = 0;
  for (int time = 0; time < 2; ++time)
    for (int axis = 0; axis < 3; ++axis) {
      double low = query.points[4 * time][axis], high = low;
      for (int k = 1; k < 4; ++k) {
        low = std::min(low, query.points[4 * time + k][axis]);
        high = std::max(high, query.points[4 * time + k][axis]);
      }
      extent = std::max(extent, high - low);
    }
  return extent;
}

}  // namespace

Options conservative_options(const Query& query, double tolerance, long max_iterations) {
  Options options;  // conservative, TOI wanted
  const double extent = coordinate_extent(query);
  if (extent > 0 && std::isfinite(extent))  // otherwise the query needs no tolerance
    options.tolerance = std::nextafter(tolerance / extent, 0.0);
  options.max_iterations = max_iterations < 0 ? std::numeric_limits<std::int64_t>::max() : max_iterations;
  return options;
}

}  // namespace batchccd::fronts

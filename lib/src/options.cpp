#include "batchccd/options.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace batchccd {
namespace {

[[noreturn]] void refuse(const char* field, double value, const char* expected) {
  std::ostringstream message;
  message.precision(17);
  message << "batchccd: Options::" << field << " must be " << expected << ", got " << value;
  throw std::invalid_argument(message.str());
}

}  // namespace

void validate(const Options& options) {
  if (!(options.min_distance >= 0 && std::isfinite(options.min_distance)))  // NaN fails too
    refuse("min_distance", options.min_distance, ">= 0 and finite");
  if (!(options.tmax > 0 && options.tmax <= 1)) refuse("tmax", options.tmax, "in (0, 1]");
  if (options.mode == Mode::cubic && options.min_distance > 0)
    refuse("min_distance", options.min_distance, "0 in mode cubic (the cubic finds roots, not distances)");
}

}  // namespace batchccd

#include "batchccd/options.hpp"

#include <sstream>
#include <stdexcept>
#include <string>

#include "batchccd/lab.hpp"
#include "separation_check.hpp"

namespace batchccd {
namespace {

[[noreturn]] void refuse(const char* field, double value, const char* expected) {
  std::ostringstream message;
  message.precision(17);
  message << "batchccd: Options::" << field << " must be " << expected << ", got " << value;
  throw std::invalid_argument(message.str());
}

}  // namespace

void validate(const Options& options) { lab::validate(options, {}); }

void lab::validate(const Options& options, const Settings& settings) {
  if (const char* expected = separation_problem(options.min_distance, decider_of(options, settings)))
    refuse("min_distance", options.min_distance, expected);
  if (!(options.tmax > 0 && options.tmax <= 1)) refuse("tmax", options.tmax, "in (0, 1]");
}

}  // namespace batchccd

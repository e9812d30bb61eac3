#include "comparison_format.hpp"

#include <algorithm>
#include <ostream>

#include "text_output.hpp"

namespace batchccd::bench {
namespace {

using cli::fixed;
using cli::general;
using cli::print_aligned;
using cli::round_trip_decimal;
using cli::TableColumn;

constexpr TableColumn kColumns[] = {
    {"method", false},   {"seconds", true},   {"candidates/s", true}, {"vs cubic", true},
    {"culled", true},    {"false_neg", true}, {"false_pos", true},    {"toi_err_max", true},
    {"toi_err_mean", true},
};

const MethodTally* cubic_row(const std::vector<MethodTally>& tallies) {
  const auto found = std::find_if(tallies.begin(), tallies.end(),
                                  [](const MethodTally& t) { return t.method == Method::cubic; });
  return found == tallies.end() ? nullptr : &*found;
}

std::string speed_up(const MethodTally& tally, const MethodTally* cubic) {
  if (!cubic || tally.seconds <= 0 || cubic->seconds <= 0) return "-";
  return fixed(cubic->seconds / tally.seconds, 1) + "x";
}

}  // namespace

void print_comparison(std::ostream& out, const std::vector<MethodTally>& tallies) {
  const MethodTally* cubic = cubic_row(tallies);
  std::vector<std::vector<std::string>> rows;
  for (const MethodTally& t : tallies) {
    rows.push_back({std::string(name_of(t.method)), fixed(t.seconds, 3),
                    general(t.candidates_per_second(), 3), speed_up(t, cubic),
                    fixed(100 * t.cull_ratio(), 2) + " %", std::to_string(t.false_negatives),
                    std::to_string(t.false_positives), general(t.toi_error_max, 2),
                    general(t.toi_error_mean(), 2)});
  }
  print_aligned(out, kColumns, rows);
}

void write_comparison_csv(std::ostream& out,
                          const std::vector<std::pair<std::string, MethodTally>>& rows) {
  out << "input,method,seconds,candidates,candidates_per_second,culled,cull_ratio,"
         "false_negatives,false_positives,toi_compared,toi_error_max,toi_error_mean\n";
  for (const auto& [label, t] : rows) {
    // Quotes only where a path needs them.
    const bool quote = label.find_first_of(",\"\n") != std::string::npos;
    std::string field = label;
    if (quote) {
      field.clear();
      for (const char c : label) field += c == '"' ? std::string("\"\"") : std::string(1, c);
      field = '"' + field + '"';
    }
    out << field << ',' << name_of(t.method) << ',' << round_trip_decimal(t.seconds) << ','
        << t.candidates << ',' << round_trip_decimal(t.candidates_per_second()) << ',' << t.culled
        << ',' << round_trip_decimal(t.cull_ratio()) << ',' << t.false_negatives << ','
        << t.false_positives << ',' << t.toi_compared << ',' << round_trip_decimal(t.toi_error_max)
        << ',' << round_trip_decimal(t.toi_error_mean()) << '\n';
  }
}

}  // namespace batchccd::bench

#include "report_format.hpp"

#include <algorithm>
#include <optional>
#include <ostream>

#include "text_output.hpp"

namespace batchccd::cli {

namespace {

nlohmann::ordered_json count_or_null(const std::optional<std::int64_t>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

nlohmann::ordered_json json_object(const InputReport& report) {
  nlohmann::ordered_json object;
  object["input"] = report.input;
  object["kind"] = to_string(report.kind);
  object["mode"] = to_string(report.mode);
  object["min_distance"] = report.min_distance;
  object["tmax"] = report.tmax;
  object["isa"] = to_string(report.isa);
  object["threads"] = report.threads;
  object["queries"] = report.queries;
  object["hits"] = report.hits;
  object["positives"] = count_or_null(report.positives);
  object["false_positives"] = count_or_null(report.false_positives);
  object["false_negatives"] = count_or_null(report.false_negatives);
  object["truth_min_distance"] =
      report.truth_labels ? nlohmann::ordered_json(report.truth_labels->min_distance) : nlohmann::ordered_json();
  object["truth_tmax"] =
      report.truth_labels ? nlohmann::ordered_json(report.truth_labels->tmax) : nlohmann::ordered_json();
  object["culled"] = report.culled;
  object["seconds"] = report.seconds;
  object["queries_per_second"] = report.queries_per_second();
  object["exact_escalations"] = report.exact_escalations;
  object["max_query_seconds"] =
      report.max_query_seconds ? nlohmann::ordered_json(*report.max_query_seconds) : nlohmann::ordered_json();
  return object;
}

std::string json_line(const InputReport& report) {
  return json_object(report).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

// ---- table ----------------------------------------------------------------

namespace {

using Row = std::vector<std::string>;

// min_distance only when it differs between rows (inputs that state their
// own separation); the settings line says it otherwise.
constexpr TableColumn min_distance_column{"min_distance", true};
constexpr TableColumn table_columns[] = {
    {"input", false},     {"kind", false},      {"queries", true},
    {"hits", true},       {"positives", true},  {"false_pos", true},
    {"false_neg", true},  {"culled", true},     {"seconds", true},
    {"queries/s", true},  {"exact", true},      {"max_query_s", true},
};

std::string cell(const std::optional<std::int64_t>& value) {
  return value ? std::to_string(*value) : "-";
}

Row table_row(const InputReport& report) {
  return {report.input,
          to_string(report.kind),
          std::to_string(report.queries),
          std::to_string(report.hits),
          cell(report.positives),
          cell(report.false_positives),
          cell(report.false_negatives),
          std::to_string(report.culled),
          fixed(report.seconds, 6),
          fixed(report.queries_per_second(), 0),
          std::to_string(report.exact_escalations),
          report.max_query_seconds ? fixed(*report.max_query_seconds, 6) : "-"};
}

// A truth column's total is shown only when every row has it.
std::optional<std::int64_t> total_of(const std::vector<InputReport>& reports,
                                     std::optional<std::int64_t> InputReport::*field) {
  std::int64_t total = 0;
  for (const InputReport& report : reports) {
    if (!(report.*field)) return std::nullopt;
    total += *(report.*field);
  }
  return total;
}

Row totals_row(const std::vector<InputReport>& reports) {
  InputReport total;
  for (const InputReport& report : reports) {
    total.queries += report.queries;
    total.hits += report.hits;
    total.culled += report.culled;
    total.seconds += report.seconds;
    total.exact_escalations += report.exact_escalations;
    if (report.max_query_seconds)
      total.max_query_seconds = std::max(total.max_query_seconds.value_or(0), *report.max_query_seconds);
  }
  total.positives = total_of(reports, &InputReport::positives);
  total.false_positives = total_of(reports, &InputReport::false_positives);
  total.false_negatives = total_of(reports, &InputReport::false_negatives);
  Row row = table_row(total);
  row[0] = "total";
  row[1] = "";
  return row;
}

// Why an input's truth columns are blank: its truth is labelled for
// another separation or time window than the call's.
std::string unscored_truth_note(const InputReport& report) {
  const TruthLabels& labels = *report.truth_labels;
  return "note: " + report.input + " (" + to_string(report.kind) + "): truth labelled for min_distance " +
         round_trip_decimal(labels.min_distance) + ", tmax " + round_trip_decimal(labels.tmax) +
         "; this run asked min_distance " + round_trip_decimal(report.min_distance) + ", tmax " +
         round_trip_decimal(report.tmax) + ": not scored";
}

}  // namespace

void print_table(std::ostream& out, const std::vector<InputReport>& reports) {
  if (reports.empty()) return;
  // Mode, time window, instruction set and threads are the same for every
  // row of a run; the separation too unless inputs state their own.
  const InputReport& first = reports.front();
  const bool one_min_distance = std::all_of(reports.begin(), reports.end(), [&](const InputReport& report) {
    return report.min_distance == first.min_distance;
  });
  out << "mode " << to_string(first.mode) << ", min_distance "
      << (one_min_distance ? round_trip_decimal(first.min_distance) : "per input (column min_distance)")
      << ", tmax " << round_trip_decimal(first.tmax) << ", isa " << to_string(first.isa) << ", threads "
      << first.threads << '\n';
  std::vector<TableColumn> columns(std::begin(table_columns), std::end(table_columns));
  std::vector<Row> rows;
  for (const InputReport& report : reports) rows.push_back(table_row(report));
  rows.push_back(totals_row(reports));
  if (!one_min_distance) {
    columns.insert(columns.begin() + 2, min_distance_column);
    for (std::size_t i = 0; i < reports.size(); ++i)
      rows[i].insert(rows[i].begin() + 2, round_trip_decimal(reports[i].min_distance));
    rows.back().insert(rows.back().begin() + 2, "");
  }
  print_aligned(out, columns, rows);
  bool any_unscored = false;
  for (const InputReport& report : reports)
    if (report.truth_not_scored()) {
      out << unscored_truth_note(report) << '\n';
      any_unscored = true;
    }
  if (any_unscored)
    out << "(positives, false_pos and false_neg are blank there: truth labelled for another separation or "
           "time window would count right answers as wrong)\n";
}

// ---- results file ---------------------------------------------------------

std::string result_line(const QueryResult& result) {
  return std::string(result.hit ? "1," : "0,") + round_trip_decimal(result.toi);
}

void write_results_file(const std::filesystem::path& file,
                        const std::vector<InputReport>& reports) {
  write_file_atomically(file, [&](std::ostream& out) {
    for (const InputReport& report : reports)
      for (const QueryResult& result : report.results) out << result_line(result) << '\n';
  });
}

}  // namespace batchccd::cli

#include "report_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <utility>

#include "names.hpp"
#include "text_output.hpp"

namespace batchccd::cli {

namespace {

// Length of the well-formed UTF-8 sequence starting at `at`, 0 when the bytes
// there are not one (overlong forms, surrogates and values past U+10FFFF
// included).
std::size_t utf8_sequence_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t index) { return static_cast<unsigned char>(text[index]); };
  const unsigned lead = byte(at);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned second_low = 0x80, second_high = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) second_low = 0xA0;   // overlong
    if (lead == 0xED) second_high = 0x9F;  // surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) second_low = 0x90;   // overlong
    if (lead == 0xF4) second_high = 0x8F;  // past U+10FFFF
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  if (byte(at + 1) < second_low || byte(at + 1) > second_high) return 0;
  for (std::size_t index = at + 2; index < at + length; ++index) {
    if ((byte(index) & 0xC0) != 0x80) return 0;
  }
  return length;
}

void append_escaped_ascii(std::string& out, char character) {
  switch (character) {
    case '"': out += "\\\""; return;
    case '\\': out += "\\\\"; return;
    case '\b': out += "\\b"; return;
    case '\f': out += "\\f"; return;
    case '\n': out += "\\n"; return;
    case '\r': out += "\\r"; return;
    case '\t': out += "\\t"; return;
    default: break;
  }
  if (static_cast<unsigned char>(character) < 0x20) {
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(character));
    out += escaped;
  } else {
    out += character;
  }
}

std::string json_number(double value) {
  return std::isfinite(value) ? round_trip_decimal(value) : "null";  // JSON has no inf
}

std::string json_count(const std::optional<std::int64_t>& value) {
  return value ? std::to_string(*value) : "null";
}

std::string json_name(std::string_view name) { return json_string(name); }

}  // namespace

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = utf8_sequence_length(text, at);
    if (length == 0) {
      out += "\\ufffd";
      at += 1;
    } else if (length == 1) {
      append_escaped_ascii(out, text[at]);
      at += 1;
    } else {
      out.append(text.substr(at, length));
      at += length;
    }
  }
  return out + "\"";
}

std::string round_trip_decimal(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (error != std::errc()) return "nan";  // cannot happen with 64 chars
  return std::string(buffer, end);
}

std::string json_line(const InputReport& report) {
  const std::pair<std::string_view, std::string> fields[] = {
      {"input", json_string(report.input)},
      {"kind", json_name(name_of(report.kind))},
      {"mode", json_name(name_of(report.mode))},
      {"isa", json_name(name_of(report.isa))},
      {"threads", std::to_string(report.threads)},
      {"queries", std::to_string(report.queries)},
      {"hits", std::to_string(report.hits)},
      {"positives", json_count(report.positives)},
      {"false_positives", json_count(report.false_positives)},
      {"false_negatives", json_count(report.false_negatives)},
      {"culled", std::to_string(report.culled)},
      {"seconds", json_number(report.seconds)},
      {"queries_per_second", json_number(report.queries_per_second())},
      {"exact_escalations", std::to_string(report.exact_escalations)},
      {"max_query_seconds", json_number(report.max_query_seconds)},
  };
  std::string line = "{";
  for (const auto& [name, value] : fields) {
    if (line.size() > 1) line += ", ";
    line += json_string(name) + ": " + value;
  }
  return line + "}";
}

// ---- table ----------------------------------------------------------------

namespace {

using Row = std::vector<std::string>;

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
          std::string(name_of(report.kind)),
          std::to_string(report.queries),
          std::to_string(report.hits),
          cell(report.positives),
          cell(report.false_positives),
          cell(report.false_negatives),
          std::to_string(report.culled),
          fixed(report.seconds, 6),
          fixed(report.queries_per_second(), 0),
          std::to_string(report.exact_escalations),
          fixed(report.max_query_seconds, 6)};
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
    total.max_query_seconds = std::max(total.max_query_seconds, report.max_query_seconds);
  }
  total.positives = total_of(reports, &InputReport::positives);
  total.false_positives = total_of(reports, &InputReport::false_positives);
  total.false_negatives = total_of(reports, &InputReport::false_negatives);
  Row row = table_row(total);
  row[0] = "total";
  row[1] = "";
  return row;
}

}  // namespace

void print_table(std::ostream& out, const std::vector<InputReport>& reports) {
  if (reports.empty()) return;
  // Mode, instruction set and threads are the same for every row of a run.
  const InputReport& first = reports.front();
  out << "mode " << name_of(first.mode) << ", isa " << name_of(first.isa) << ", threads "
      << first.threads << '\n';
  std::vector<Row> rows;
  for (const InputReport& report : reports) rows.push_back(table_row(report));
  rows.push_back(totals_row(reports));
  print_aligned(out, table_columns, rows);
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

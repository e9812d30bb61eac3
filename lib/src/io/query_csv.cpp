// Query CSV files (docs/design.md §9) and the kind a path names.

#include <cctype>
#include <stdexcept>
#include <string>
#include <span>
#include <utility>
#include <vector>

#include "batchccd/io.hpp"
#include "io/text_input.hpp"

namespace batchccd {

namespace {

using io_detail::in_quotes;
using io_detail::NumberedLine;

struct Word {
  std::string text;  // lower case
  std::size_t begin;
  std::size_t end;
};

std::vector<Word> alphanumeric_words(std::string_view text) {
  std::vector<Word> words;
  std::size_t i = 0;
  while (i < text.size()) {
    if (!std::isalnum(static_cast<unsigned char>(text[i]))) {
      ++i;
      continue;
    }
    Word word{{}, i, i};
    while (i < text.size() && std::isalnum(static_cast<unsigned char>(text[i]))) {
      word.text += static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
      ++i;
    }
    word.end = i;
    words.push_back(std::move(word));
  }
  return words;
}

// "vertex-face" (or "vertex_face"): two words one separator apart.
bool is_pair(const std::vector<Word>& words, std::size_t i, std::string_view first, std::string_view second) {
  return i + 1 < words.size() && words[i].text == first && words[i + 1].text == second &&
         words[i + 1].begin == words[i].end + 1;
}

// The words that name each kind: a short name alone, or a pair.
struct KindWords {
  Kind kind;
  std::string_view short_name;
  std::string_view pairs[2][2];
};
constexpr KindWords kind_words[] = {
    {Kind::vertex_face, "vf", {{"vertex", "face"}, {"vertex", "face"}}},
    {Kind::edge_edge, "ee", {{"edge", "edge"}, {"edge", "edge"}}},
    {Kind::vertex_edge, "ve", {{"vertex", "edge"}, {"point", "edge"}}},
    {Kind::vertex_vertex, "vv", {{"vertex", "vertex"}, {"point", "point"}}},
};

// The kind a single path component names; its last mention wins.
std::optional<Kind> kind_named_by_component(std::string_view component) {
  const std::vector<Word> words = alphanumeric_words(component);
  std::optional<Kind> kind;
  for (std::size_t i = 0; i < words.size(); ++i)
    for (const KindWords& named : kind_words)
      if (words[i].text == named.short_name || is_pair(words, i, named.pairs[0][0], named.pairs[0][1]) ||
          is_pair(words, i, named.pairs[1][0], named.pairs[1][1]))
        kind = named.kind;
  return kind;
}

// Column layout of a query row (docs/design.md §9).
constexpr std::size_t columns_without_truth = 6;
constexpr std::size_t columns_with_truth = 7;

class QueryCsvParser {
 public:
  explicit QueryCsvParser(const std::filesystem::path& path) : file_(path.string()) {}

  QueryFile parse(std::string_view text, Kind kind) {
    QueryFile result;
    result.path = file_;
    result.kind = kind;
    // A query's points at t0, then at t1, each written once (vf/ee 8 rows, ve 6, vv 4).
    const std::size_t points_each_time = static_cast<std::size_t>(points_per_time(kind));
    const std::size_t rows_per_query = 2 * points_each_time;
    const std::vector<NumberedLine> lines = io_detail::numbered_lines(text);
    check_row_count(lines, kind, rows_per_query);
    if (!lines.empty()) column_count_ = first_row_column_count(lines.front());
    if (column_count_ == columns_with_truth) result.truth.emplace();
    result.queries.reserve(lines.size() / rows_per_query);
    std::vector<Vec3> points(rows_per_query);
    const std::span<const Vec3> all(points);
    for (std::size_t first = 0; first < lines.size(); first += rows_per_query) {
      std::optional<bool> truth;
      for (std::size_t row = 0; row < rows_per_query; ++row) read_row(lines[first + row], points[row], truth);
      result.queries.push_back(
          make_query(kind, all.first(points_each_time), all.subspan(points_each_time)));
      if (result.truth) result.truth->push_back(*truth);
    }
    return result;
  }

 private:
  void check_row_count(const std::vector<NumberedLine>& lines, Kind kind, std::size_t rows_per_query) const {
    const std::size_t leftover = lines.size() % rows_per_query;
    if (leftover == 0) return;
    const std::string rows = std::to_string(rows_per_query);
    throw InputError(file_, lines.back().number,
                     "row count " + std::to_string(lines.size()) + " is not a multiple of " + rows + " (" +
                         to_string(kind) + " queries have " + rows + " rows; the last query has " +
                         std::to_string(leftover) + " of its " + rows + " rows)");
  }

  // The first row fixes the layout of the whole file.
  std::size_t first_row_column_count(const NumberedLine& line) const {
    const std::size_t count = io_detail::split_fields(line.text).size();
    if (count != columns_without_truth && count != columns_with_truth)
      throw InputError(file_, line.number, "expected 6 or 7 columns, found " + std::to_string(count));
    return count;
  }

  void read_row(const NumberedLine& line, Vec3& point, std::optional<bool>& query_truth) const {
    if (io_detail::trim(line.text).empty()) throw InputError(file_, line.number, "empty line");
    const std::vector<std::string_view> fields = io_detail::split_fields(line.text);
    if (fields.size() != column_count_) {
      throw InputError(file_, line.number,
                       "expected " + std::to_string(column_count_) + " columns (as on the first row), found " +
                           std::to_string(fields.size()));
    }
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t column = 2 * static_cast<std::size_t>(axis);
      try {
        point[axis] = exact_double_from_rational(fields[column], fields[column + 1]);
      } catch (const std::invalid_argument& error) {
        throw InputError(file_, line.number, "column " + std::to_string(column + 1) + ": " + error.what());
      }
    }
    if (column_count_ == columns_with_truth) read_truth(line, fields.back(), query_truth);
  }

  // The truth is repeated on every row of a query; they must agree.
  void read_truth(const NumberedLine& line, std::string_view field, std::optional<bool>& query_truth) const {
    const std::optional<bool> truth = io_detail::parse_bit(field);
    if (!truth) throw InputError(file_, line.number, "column 7: truth must be 0 or 1, found " + in_quotes(field));
    if (query_truth && *query_truth != *truth) {
      throw InputError(file_, line.number,
                       "column 7: truth " + std::to_string(*truth) + " differs from the truth " +
                           std::to_string(*query_truth) + " of the earlier rows of this query");
    }
    query_truth = truth;
  }

  std::string file_;
  std::size_t column_count_ = 0;
};

}  // namespace

std::optional<Kind> kind_from_path(const std::filesystem::path& path) {
  std::vector<std::string> components;
  for (const auto& component : path) components.push_back(component.string());
  for (auto it = components.rbegin(); it != components.rend(); ++it)
    if (const auto kind = kind_named_by_component(*it)) return kind;
  return std::nullopt;
}

QueryFile read_query_csv(const std::filesystem::path& path, Kind kind) {
  const std::string text = io_detail::read_input_file(path);
  QueryCsvParser parser(path);
  return parser.parse(text, kind);
}

}  // namespace batchccd

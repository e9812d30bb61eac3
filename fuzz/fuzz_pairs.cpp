// libFuzzer target: the candidate-list readers ("vertex,face",
// "a0,a1,b0,b1", "vertex,e0,e1" and "p,q" a line, io.hpp). Every reader
// sees every input, and each answer is held to a reading of the bytes
// written here from io.hpp's rules alone: the ids it returns are the ids
// the text holds, and a refusal is an InputError naming the file, the line
// of the first bad row and, for a bad field, its column and text.

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "batchccd/io.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input_file.hpp"

namespace {

using batchccd::fuzz::require;

// What a list of `columns` ids a line must read as: its rows, or where the
// first bad row is (column 0 for the row as a whole: an empty line, a wrong
// field count).
struct ExpectedList {
  std::vector<std::vector<int>> rows;
  long bad_line = 0;  // 0: the list reads
  std::size_t bad_column = 0;
  std::string bad_field;
};

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

// A field as an id: decimal digits alone, at most INT_MAX.
std::optional<int> as_id(std::string_view field) {
  if (field.empty() || !std::all_of(field.begin(), field.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  const std::size_t first = std::min(field.find_first_not_of('0'), field.size() - 1);
  const std::string_view digits = field.substr(first);
  if (digits.size() > 10) return std::nullopt;
  const long long value = std::stoll(std::string(digits));
  if (value > INT_MAX) return std::nullopt;
  return static_cast<int>(value);
}

ExpectedList expected_list(std::string_view text, std::size_t columns) {
  // Lines split at '\n', each without one trailing '\r'; trailing lines of
  // spaces, tabs and '\r' alone are not rows.
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  while (!lines.empty() && lines.back().find_first_not_of(" \t\r") == std::string_view::npos) lines.pop_back();

  ExpectedList expected;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const long number = static_cast<long>(i) + 1;
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
      const std::size_t comma = lines[i].find(',', start);
      fields.push_back(trimmed(lines[i].substr(start, comma == std::string_view::npos ? comma : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (trimmed(lines[i]).empty() || fields.size() != columns) {
      expected.bad_line = number;
      return expected;
    }
    std::vector<int> row;
    for (std::size_t k = 0; k < columns; ++k) {
      const std::optional<int> id = as_id(fields[k]);
      if (!id) {
        expected.bad_line = number;
        expected.bad_column = k + 1;
        // Messages cut user text at 60 bytes and write a control byte or
        // DEL as \xHH.
        for (const char c : fields[k].substr(0, 60)) {
          const auto byte = static_cast<unsigned char>(c);
          if (byte >= 0x20 && byte != 0x7f) {
            expected.bad_field.push_back(c);
          } else {
            char escaped[5];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
            expected.bad_field += escaped;
          }
        }
        return expected;
      }
      row.push_back(*id);
    }
    expected.rows.push_back(std::move(row));
  }
  return expected;
}

template <std::size_t N, class Reader>
void check_reader(Reader read, const std::filesystem::path& path, const ExpectedList& expected, const char* name) {
  try {
    const std::vector<std::array<int, N>> rows = read(path);
    require(expected.bad_line == 0, "a bad list is refused", name);
    require(rows.size() == expected.rows.size(), "one row a line", name);
    for (std::size_t i = 0; i < rows.size(); ++i)
      require(std::equal(rows[i].begin(), rows[i].end(), expected.rows[i].begin()), "the ids the text holds", name);
  } catch (const batchccd::InputError& error) {
    require(expected.bad_line != 0, "a good list is read", name);
    require(error.file() == path.string(), "the error names the file", name);
    require(error.line() == expected.bad_line, "the error names the first bad line", name);
    const std::string message = error.what();
    require(std::none_of(message.begin(), message.end(),
                         [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }),
            "the error holds no control byte", name);
    if (expected.bad_column != 0) {
      require(message.find("column " + std::to_string(expected.bad_column) + ": ") != std::string::npos,
              "the error names the bad field's column", name);
      require(message.find("'" + expected.bad_field) != std::string::npos, "the error quotes the bad field", name);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& path = batchccd::fuzz::as_input_file(data, size);
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const ExpectedList two = expected_list(text, 2), three = expected_list(text, 3), four = expected_list(text, 4);
  check_reader<2>(batchccd::read_vertex_face_pairs, path, two, "vertex-face");
  check_reader<4>(batchccd::read_edge_edge_pairs, path, four, "edge-edge");
  check_reader<3>(batchccd::read_vertex_edge_triples, path, three, "vertex-edge");
  check_reader<2>(batchccd::read_vertex_vertex_pairs, path, two, "vertex-vertex");
  return 0;
}

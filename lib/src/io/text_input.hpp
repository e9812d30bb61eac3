#pragma once

// Private helpers shared by the text readers of lib/src/io: reading a whole
// file, cutting it into numbered lines and comma-separated fields, and
// quoting user text in messages.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace batchccd::io_detail {

// The bytes of a file; InputError(path, 0, ...) when it cannot be read.
std::string read_input_file(const std::filesystem::path& path);

struct NumberedLine {
  long number;            // 1-based
  std::string_view text;  // without '\n' and a trailing '\r'
};

// Every line of text; trailing blank lines (the usual final newline, an
// editor's extra empty line) are dropped, blank lines in between are kept so
// that readers can reject them with their line number.
std::vector<NumberedLine> numbered_lines(std::string_view text);

std::string_view trim(std::string_view text);

// Fields separated by ',' with the spaces or tabs around each removed.
std::vector<std::string_view> split_fields(std::string_view line);

// User text for a message with every control byte and DEL as \xHH: a NUL
// would end what() there, the others would reach a terminal.
std::string printable(std::string_view text);

// User text for a message: printable, in quotes and cut short, since a
// malformed number may be arbitrarily long.
std::string in_quotes(std::string_view text, std::size_t max_length = 60);

// True for one or more of 0-9 and nothing else.
bool all_digits(std::string_view text);

// "0" -> false, "1" -> true, anything else -> nullopt.
std::optional<bool> parse_bit(std::string_view text);

}  // namespace batchccd::io_detail

#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <span>
#include <string>
#include <string_view>
#include <vector>

// Plain-text building blocks of the command-line reports: aligned tables,
// numbers, and files that are either complete or not there.
namespace batchccd::cli {

struct TableColumn {
  std::string_view header;
  bool right_aligned;
};

// The header and the rows, each cell padded to its column's widest, two
// spaces between columns, no trailing spaces. Every row has one cell per column.
void print_aligned(std::ostream& out, std::span<const TableColumn> columns,
                   const std::vector<std::vector<std::string>>& rows);

// The shortest decimal that reads back as the same double; "inf" / "-inf" /
// "nan" for the non-finite values.
std::string round_trip_decimal(double value);

// "%.*f" and "%.*g" without the locale.
std::string fixed(double value, int decimals);
std::string general(double value, int digits);

// Writes what `write` puts out to FILE.tmp-<pid>, then renames it over FILE,
// so FILE is either the old file or complete. Throws std::runtime_error
// when it cannot (no temporary file is left).
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<void(std::ostream&)>& write);

}  // namespace batchccd::cli

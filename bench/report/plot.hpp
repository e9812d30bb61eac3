#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

// The comparison's picture, drawn by gnuplot from the CSV the report writes
// (comparison_format.hpp): three panels, false negatives, false positives and
// the largest TOI error, each against run time, log axes, one point per
// method of the CSV's "total" rows, each point named beside its marker, and
// a legend row under the panels pairing every marker with its method.
namespace batchccd::bench {

// The gnuplot executable on PATH; std::nullopt when there is none.
std::optional<std::filesystem::path> find_gnuplot();

// A gnuplot script reading `csv` and writing `png`, a point for each of
// `methods` (names without spaces). Zeros, which log axes cannot show, sit
// on a row of their own ticked 0.
std::string plot_script(std::string_view title, const std::filesystem::path& csv,
                        const std::filesystem::path& png, const std::vector<std::string>& methods);

// Runs `gnuplot SCRIPT` in `directory` (the script's paths are relative to
// it). Throws std::runtime_error with gnuplot's own messages when it fails.
void run_gnuplot(const std::filesystem::path& gnuplot, const std::filesystem::path& directory,
                 const std::string& script);

}  // namespace batchccd::bench

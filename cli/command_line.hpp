#pragma once

#include <charconv>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "batchccd/names.hpp"

// Pieces of the command lines (CLI11) that batchccd and the bench's
// batchccd_report share.
namespace batchccd::cli {

// A positive int, said plainly when it is not one.
inline const CLI::Validator positive_integer(
    [](std::string& text) -> std::string {
      int value = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (error == std::errc() && end == text.data() + text.size() && value > 0) return {};
      return "needs a positive integer, not '" + text + "'";
    },
    "N>0");

// The names of an enum's table (names.hpp), for CLI::IsMember.
template <class Enum>
std::vector<std::string> names_of(std::span<const EnumName<Enum>> table) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.emplace_back(entry.name);
  return names;
}

// Parses; returns the exit status when the command should not run: 0 after
// --help or --version, 2 after a bad command line (said on stderr).
inline std::optional<int> parse_or_exit(CLI::App& app, int argc, char** argv) {
  if (argc <= 1) {
    std::cerr << app.help();
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& done) {  // --help, --version
    return app.exit(done);
  } catch (const CLI::ParseError& error) {
    std::string command = app.get_name();
    for (const CLI::App* sub : app.get_subcommands()) command += " " + sub->get_name();
    std::cerr << command << ": " << error.what() << "\nRun '" << command << " --help' for usage.\n";
    return 2;
  }
  return std::nullopt;
}

}  // namespace batchccd::cli

// The `batchccd` executable: command-line parsing only. The work is done by
// run_inputs (run.hpp) and shown by report_format.hpp.

#include <charconv>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "batchccd/version.hpp"
#include "demo.hpp"
#include "names.hpp"
#include "report_format.hpp"
#include "run.hpp"

namespace {

using batchccd::cli::RunSettings;
using Arguments = std::span<const std::string_view>;

constexpr int exit_success = 0;
constexpr int exit_input_error = 1;
constexpr int exit_usage_error = 2;

constexpr std::string_view general_usage =
    "usage: batchccd COMMAND [options] ...\n"
    "\n"
    "Continuous collision detection over batches of vertex-face (vf) and\n"
    "edge-edge (ee) queries.\n"
    "\n"
    "Commands:\n"
    "  demo      every mode and baseline on a built-in scene: speed, errors, plot\n"
    "  report    the same comparison on query files and scenes\n"
    "  run       evaluate query files and scenes, report counts and timing\n"
    "\n"
    "  batchccd --help          this text and every command's options\n"
    "  batchccd COMMAND --help  one command's options\n"
    "  batchccd --version       the version\n";

constexpr std::string_view run_usage =
    "usage: batchccd run [options] INPUT...\n"
    "\n"
    "Runs the narrow phase on every INPUT and prints one result per input and\n"
    "kind: an aligned table with a totals row, or JSON lines with --json.\n"
    "\n"
    "INPUT is one of\n"
    "  a query CSV    8 rows a query; columns x_num,x_den,y_num,y_den,z_num,z_den\n"
    "                 and optionally truth (0/1)\n"
    "  a scene        a directory holding t0.ply and t1.ply, with vf.csv, ee.csv\n"
    "                 and optionally vf_truth.txt, ee_truth.txt; gives a vf and an\n"
    "                 ee result\n"
    "  a directory    searched recursively for scenes and for *.csv query files\n"
    "                 whose path names their kind (or any *.csv with --kind);\n"
    "                 run in sorted path order\n"
    "\n"
    "Options:\n"
    "  --kind vf|ee       kind of a query file whose path does not say: a path\n"
    "                     with \"vertex-face\" or \"vf\" is vf, with \"edge-edge\" or\n"
    "                     \"ee\" is ee\n"
    "  --truth FILE       ground truth for query files without a truth column (or\n"
    "                     replacing it): a JSON array of booleans or one 0/1 a\n"
    "                     line; needs a single INPUT\n"
    "  --mode MODE        conservative (default): certified, never misses a\n"
    "                     contact, false positives only within tolerance (GMP\n"
    "                     settles what floating point cannot); fast: the same\n"
    "                     search in plain double arithmetic;\n"
    "                     cubic: the unfiltered cubic solver (the baseline);\n"
    "                     exact: decisions equal to exact arithmetic (certified\n"
    "                     path, uncertain queries settled with GMP), TOI within\n"
    "                     1e-12 before the first contact\n"
    "  --threads N        worker threads, a positive integer (default: all)\n"
    "  --isa ISA          auto (default), scalar (the reference path), sse4,\n"
    "                     avx2, avx512\n"
    "  --json             one JSON object per input and kind on stdout, fields\n"
    "                     input, kind, mode, isa (the one used), threads,\n"
    "                     queries, hits, positives, false_positives,\n"
    "                     false_negatives (null without truth), culled, seconds\n"
    "                     (narrow phase alone, reading excluded),\n"
    "                     queries_per_second, exact_escalations (queries whose\n"
    "                     decision or TOI needed exact arithmetic; 0 in fast\n"
    "                     and cubic mode), max_query_seconds (wall-clock time of\n"
    "                     the slowest single query)\n"
    "  --out FILE         per-query results, one \"hit,toi\" line a query (hit 0/1,\n"
    "                     toi \"inf\" without a hit) in input order, all inputs in\n"
    "                     the order run; a scene's vf candidates come before its\n"
    "                     ee ones; replaced atomically\n"
    "  -h, --help         this text\n"
    "\n"
    "Exit status: 0 success; 1 an input could not be read (reported on stderr,\n"
    "the other inputs still run); 2 a bad command line.\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RunCommandLine {
  RunSettings settings;
  bool json = false;
  bool help = false;
  std::optional<std::filesystem::path> out;
};

template <class Enum, std::size_t Count>
Enum parse_enum(std::string_view option, std::string_view value,
                const batchccd::cli::NameTable<Enum, Count>& names) {
  if (auto parsed = batchccd::cli::from_name(names, value)) return *parsed;
  std::string accepted;
  for (const auto& entry : names) {
    if (!accepted.empty()) accepted += '|';
    accepted += entry.first;
  }
  throw UsageError("bad " + std::string(option) + " value '" + std::string(value) +
                   "' (expected " + accepted + ")");
}

int parse_positive(std::string_view option, std::string_view value) {
  int number = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
  if (error != std::errc() || end != value.data() + value.size() || number <= 0) {
    throw UsageError(std::string(option) + " needs a positive integer, not '" + std::string(value) + "'");
  }
  return number;
}
// Reads the arguments of `--name value` and `--name=value` one at a time.
class ArgumentCursor {
 public:
  explicit ArgumentCursor(Arguments arguments) : arguments_(arguments) {}

  bool done() const { return next_ >= arguments_.size(); }

  // The next argument; an option's inline "=value" is kept for value().
  std::string_view take() {
    std::string_view argument = arguments_[next_++];
    inline_value_.reset();
    if (argument.starts_with("--")) {
      if (const auto equals = argument.find('='); equals != std::string_view::npos) {
        inline_value_ = argument.substr(equals + 1);
        argument = argument.substr(0, equals);
      }
    }
    return argument;
  }

  std::string_view value(std::string_view option) {
    if (inline_value_) return *std::exchange(inline_value_, std::nullopt);
    if (done()) throw UsageError(std::string(option) + " needs a value");
    return arguments_[next_++];
  }

  // An option that takes no value must not have been given one.
  void expect_no_value(std::string_view option) const {
    if (inline_value_) throw UsageError(std::string(option) + " takes no value");
  }

 private:
  Arguments arguments_;
  std::size_t next_ = 0;
  std::optional<std::string_view> inline_value_;
};

void parse_run_option(std::string_view option, ArgumentCursor& cursor, RunCommandLine& line) {
  using namespace batchccd::cli;
  RunSettings& settings = line.settings;
  if (option == "--help" || option == "-h") {
    cursor.expect_no_value(option);
    line.help = true;
  } else if (option == "--json") {
    cursor.expect_no_value(option);
    line.json = true;
  } else if (option == "--kind") {
    settings.kind = parse_enum(option, cursor.value(option), kind_names);
  } else if (option == "--mode") {
    settings.options.mode = parse_enum(option, cursor.value(option), mode_names);
  } else if (option == "--isa") {
    settings.options.isa = parse_enum(option, cursor.value(option), isa_names);
  } else if (option == "--threads") {
    settings.options.threads = parse_positive(option, cursor.value(option));
  } else if (option == "--truth") {
    settings.truth = std::filesystem::path(cursor.value(option));
  } else if (option == "--out") {
    line.out = std::filesystem::path(cursor.value(option));
  } else {
    throw UsageError("unknown option '" + std::string(option) + "'");
  }
}

RunCommandLine parse_run_arguments(Arguments arguments) {
  RunCommandLine line;
  ArgumentCursor cursor(arguments);
  bool options_ended = false;  // after "--" everything is an INPUT
  while (!cursor.done()) {
    const std::string_view argument = cursor.take();
    if (!options_ended && argument == "--") {
      options_ended = true;
    } else if (!options_ended && argument.size() > 1 && argument.starts_with('-')) {
      parse_run_option(argument, cursor, line);
    } else {
      line.settings.inputs.emplace_back(argument);
    }
  }
  if (line.help) return line;
  if (line.settings.inputs.empty()) throw UsageError("missing INPUT");
  if (line.settings.truth && line.settings.inputs.size() > 1) {
    throw UsageError("--truth needs a single INPUT");
  }
  line.settings.keep_results = line.out.has_value();
  return line;
}

void print_reports(const RunCommandLine& line, const batchccd::cli::RunOutcome& outcome) {
  if (line.json) {
    for (const auto& report : outcome.reports) std::cout << batchccd::cli::json_line(report) << '\n';
  } else {
    batchccd::cli::print_table(std::cout, outcome.reports);
  }
  std::cout.flush();
}

int run_command(Arguments arguments) {
  RunCommandLine line;
  try {
    line = parse_run_arguments(arguments);
  } catch (const UsageError& error) {
    std::cerr << "batchccd run: " << error.what() << "\n\n" << run_usage;
    return exit_usage_error;
  }
  if (line.help) {
    std::cout << run_usage;
    return exit_success;
  }
  batchccd::cli::RunOutcome outcome = batchccd::cli::run_inputs(line.settings, std::cerr);
  print_reports(line, outcome);
  if (line.out) {
    try {
      batchccd::cli::write_results_file(*line.out, outcome.reports);
    } catch (const std::exception& error) {
      std::cerr << "batchccd: error: " << error.what() << '\n';
      outcome.any_error = true;
    }
  }
  return outcome.any_error ? exit_input_error : exit_success;
}

// ---- demo and report ---------------------------------------------------------

constexpr std::string_view demo_usage =
    "usage: batchccd demo [options]\n"
    "\n"
    "Generates a built-in scene, runs a swept-box broad phase on it, and runs\n"
    "every method on the candidates: exact, conservative, fast and cubic modes,\n"
    "the DNF-style filter variant and FCL (when built with it). Prints, per\n"
    "method, run time, candidates per second, speed-up against cubic, cull\n"
    "ratio, false negatives and positives, and TOI error (max and mean), all\n"
    "against exact mode; then what each part of a call costs, and each mode on\n"
    "the stiff and extreme suite. Writes report.txt, methods.csv and plot.svg\n"
    "(error against run time). The default takes about 35 s on 2 cores.\n"
    "\n"
    "Options:\n"
    "  --scene cloth|rigid  cloth (default): a sheet draping, folding and twisting\n"
    "                       onto itself, 12 steps; rigid: thin bodies moving far\n"
    "                       within one step\n"
    "  --resolution N       scene size: cloth vertices per side (default 128,\n"
    "                       about 4 M candidates a step), rigid cells per body\n"
    "                       length (default 12)\n"
    "  --threads N          worker threads, a positive integer (default: all)\n"
    "  --out DIR            where the files go (default batchccd-demo)\n"
    "  --methods-only       skip the costs and the stiff and extreme suite\n"
    "  -h, --help           this text\n";

constexpr std::string_view report_usage =
    "usage: batchccd report [options] INPUT...\n"
    "\n"
    "The demo's comparison on query files and scenes (INPUT as for run): every\n"
    "method, ground truth from the files (exact mode's decisions where an input\n"
    "has none), TOI error against exact mode. Totals on stdout; with --out,\n"
    "methods.csv (a row per input and method, and totals) and plot.svg.\n"
    "\n"
    "Options:\n"
    "  --kind vf|ee       kind of a query file whose path does not say\n"
    "  --threads N        worker threads, a positive integer (default: all)\n"
    "  --out DIR          write methods.csv and plot.svg there\n"
    "  -h, --help         this text\n"
    "\n"
    "Exit status: 0 success; 1 an input could not be read (reported on stderr,\n"
    "the other inputs still run); 2 a bad command line.\n";

// Progress lines go to a terminal only.
std::ostream* progress_stream() { return ::isatty(STDERR_FILENO) ? &std::cerr : nullptr; }

// Parses with `option` for each option; returns the exit status of a
// usage error or help, nothing when the command should run.
std::optional<int> parse_command(std::string_view command, std::string_view usage, Arguments arguments,
                                 const std::function<void(std::string_view, ArgumentCursor&)>& option,
                                 const std::function<void(std::string_view)>& operand) {
  try {
    ArgumentCursor cursor(arguments);
    while (!cursor.done()) {
      const std::string_view argument = cursor.take();
      if (argument == "--help" || argument == "-h") {
        cursor.expect_no_value(argument);
        std::cout << usage;
        return exit_success;
      }
      if (argument.size() > 1 && argument.starts_with('-')) {
        option(argument, cursor);
      } else {
        operand(argument);
      }
    }
  } catch (const UsageError& error) {
    std::cerr << "batchccd " << command << ": " << error.what() << "\n\n" << usage;
    return exit_usage_error;
  }
  return std::nullopt;
}

int demo_command(Arguments arguments) {
  batchccd::cli::DemoSettings settings;
  const auto status = parse_command(
      "demo", demo_usage, arguments,
      [&](std::string_view option, ArgumentCursor& cursor) {
        if (option == "--scene") {
          const std::string_view value = cursor.value(option);
          if (value == "cloth") {
            settings.scene = batchccd::cli::BuiltinScene::cloth;
          } else if (value == "rigid") {
            settings.scene = batchccd::cli::BuiltinScene::rigid;
          } else {
            throw UsageError("bad --scene value '" + std::string(value) + "' (expected cloth|rigid)");
          }
        } else if (option == "--resolution") {
          settings.resolution = parse_positive(option, cursor.value(option));
        } else if (option == "--threads") {
          settings.threads = parse_positive(option, cursor.value(option));
        } else if (option == "--out") {
          settings.out = std::filesystem::path(cursor.value(option));
        } else if (option == "--methods-only") {
          cursor.expect_no_value(option);
          settings.sections = false;
        } else {
          throw UsageError("unknown option '" + std::string(option) + "'");
        }
      },
      [](std::string_view operand) {
        throw UsageError("unexpected argument '" + std::string(operand) + "'");
      });
  if (status) return *status;
  try {
    batchccd::cli::run_demo(settings, std::cout, progress_stream());
  } catch (const std::runtime_error& error) {
    std::cerr << "batchccd: error: " << error.what() << '\n';
    return exit_input_error;
  }
  return exit_success;
}

int report_command(Arguments arguments) {
  batchccd::cli::ReportSettings settings;
  const auto status = parse_command(
      "report", report_usage, arguments,
      [&](std::string_view option, ArgumentCursor& cursor) {
        if (option == "--kind") {
          settings.kind = parse_enum(option, cursor.value(option), batchccd::cli::kind_names);
        } else if (option == "--threads") {
          settings.threads = parse_positive(option, cursor.value(option));
        } else if (option == "--out") {
          settings.out = std::filesystem::path(cursor.value(option));
        } else {
          throw UsageError("unknown option '" + std::string(option) + "'");
        }
      },
      [&](std::string_view operand) { settings.inputs.emplace_back(operand); });
  if (status) return *status;
  if (settings.inputs.empty()) {
    std::cerr << "batchccd report: missing INPUT\n\n" << report_usage;
    return exit_usage_error;
  }
  bool ok = false;
  try {
    ok = batchccd::cli::run_report(settings, std::cout, std::cerr, progress_stream());
  } catch (const std::runtime_error& error) {
    std::cerr << "batchccd: error: " << error.what() << '\n';
  }
  return ok ? exit_success : exit_input_error;
}

// Every command of the tool.
struct Command {
  std::string_view name;
  std::string_view usage;
  int (*entry)(Arguments arguments);
};

constexpr Command commands[] = {
    {"demo", demo_usage, demo_command},
    {"report", report_usage, report_command},
    {"run", run_usage, run_command},
};

void print_full_help() {
  std::cout << general_usage;
  for (const Command& command : commands) std::cout << "\n" << command.usage;
}

int dispatch(Arguments arguments) {
  if (arguments.empty()) {
    std::cerr << general_usage;
    return exit_usage_error;
  }
  const std::string_view first = arguments.front();
  if (first == "--help" || first == "-h" || first == "help") {
    print_full_help();
    return exit_success;
  }
  if (first == "--version") {
    std::cout << "batchccd " << BATCHCCD_VERSION << '\n';
    return exit_success;
  }
  for (const Command& command : commands) {
    if (command.name == first) return command.entry(arguments.subspan(1));
  }
  std::cerr << "batchccd: unknown command '" << first << "'\n\n" << general_usage;
  return exit_usage_error;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string_view> arguments(argv + 1, argv + argc);
  try {
    return dispatch(arguments);
  } catch (const std::exception& error) {
    // Unexpected failures (out of memory, a library bug) still end cleanly.
    std::cerr << "batchccd: internal error: " << error.what() << '\n';
    return exit_input_error;
  }
}

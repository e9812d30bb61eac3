// The installed `batchccd` executable: its command line (CLI11). The work is
// done by run_inputs (run.hpp) and shown by report_format.hpp.

#include <charconv>
#include <exception>
#include <iostream>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "batchccd/batchccd.hpp"
#include "command_line.hpp"
#include "report_format.hpp"
#include "run.hpp"
#include "text_output.hpp"

namespace {

using batchccd::cli::names_of;
using batchccd::cli::positive_integer;

constexpr int exit_success = 0;
constexpr int exit_input_error = 1;
constexpr int exit_usage_error = 2;

constexpr const char* run_footer = R"(INPUT is one of
  a query CSV   a query's points at t0, then its points at t1, one a row:
                  vf (vertex-face)    8 rows  p a b c, then p a b c
                  ee (edge-edge)      8 rows  ea0 ea1 eb0 eb1, then the same
                  ve (vertex-edge)    6 rows  p e0 e1, then p e0 e1
                  vv (vertex-vertex)  4 rows  p q, then p q
                columns x_num,x_den,y_num,y_den,z_num,z_den (exact rationals)
                and optionally truth (0/1, the same on all of a query's rows)
  a scene       a directory holding t0.ply and t1.ply, with candidate lists
                vf.csv ("vertex,face" a line), ee.csv ("a0,a1,b0,b1"), ve.csv
                ("vertex,e0,e1"), vv.csv ("p,q") and optionally vf_truth.txt,
                ee_truth.txt, ve_truth.txt, vv_truth.txt; gives a vf and an ee
                result, and a ve and a vv result when it has ve.csv, vv.csv
  a directory   searched recursively for scenes and for *.csv query files whose
                path names their kind (or any *.csv with --kind); run in sorted
                path order
A query file's kind comes from its path (the last component naming one):
"vertex-face" or a "vf" word is vf, "edge-edge" or an "ee" word is ee,
"vertex-edge", "point-edge" or a "ve" word is ve, "vertex-vertex",
"point-point" or a "vv" word is vv; --kind gives it otherwise.

--min-distance D, --tmax T: a contact is the primitives coming within distance
D of each other (in the data's length units) at some t in [0, T] (T in (0, 1],
default 1; a contact after T is not a hit). D >= 0 and finite; without
--min-distance, the separation an input's data states (the one number of
ms.txt beside a query file or in a scene directory), else 0 (touching).

Truth (a truth column, *_truth.txt) is labelled for the separation its data
states (ms.txt; 0 without) and T = 1; --truth FILE for the run's own D and T.
Truth labelled for another D or T is not scored: positives, false positives
and false negatives stay blank (null in JSON), and a note under the table says
which inputs and why. The JSON fields truth_min_distance and truth_tmax say what
an input's truth is labelled for (null without truth).

--truth FILE: ground truth for a single query file, replacing its truth
column: a JSON array of booleans, or one 0/1 a line.

Modes:
  conservative  certified: never misses a contact, false positives only within
                tolerance (GMP settles what floating point cannot); the default
  exact         decisions equal to exact arithmetic, TOI within 1e-12 before
                the first contact

JSON fields (--json, one object per input and kind): input, kind, mode,
min_distance, tmax, isa (the one used), threads, queries, hits, positives,
false_positives, false_negatives (null without truth or with truth labelled
for another separation or tmax), truth_min_distance, truth_tmax, culled,
seconds (narrow phase alone, reading excluded), queries_per_second,
exact_escalations (queries whose decision or TOI needed exact arithmetic),
max_query_seconds (wall-clock time of the slowest single query, with
--time-queries; null without).

--repeat N: each input's narrow phase N times into one result, as a frame loop
runs it; seconds is the best of the N (reading, first touch and allocation
out).

--out FILE: one "hit,toi" line a query (hit 0/1, toi "inf" without a hit) in
input order, all inputs in the order run, a scene's vf candidates, then its ee,
ve and vv ones; replaced atomically.

Exit status: 0 success; 1 an input could not be read (reported on stderr, the
other inputs still run) or the instruction set is not available; 2 a bad
command line (a bad --min-distance or --tmax too).)";

struct RunCommand {
  std::vector<std::string> inputs;
  std::string kind, truth, mode = "conservative", isa = "auto", out;
  int threads = 0;
  int repeat = 1;
  bool json = false;
  bool time_queries = false;
  std::optional<double> min_distance;  // without it, each input's stated separation (run.hpp)
  double tmax = 1;
};

// The library names options as C++ does; the command line names its flags.
// Every library message about the options passes through here.
constexpr std::pair<std::string_view, std::string_view> command_line_names[] = {
    {"batchccd: ", ""},  // the tool prefixes its own
    {"Options::min_distance", "--min-distance"},
    {"Options::tmax", "--tmax"},
};

std::string in_command_line_names(std::string message) {
  for (const auto& [library_name, flag] : command_line_names)
    for (std::size_t at = message.find(library_name); at != std::string::npos;
         at = message.find(library_name, at + flag.size()))
      message.replace(at, library_name.size(), flag);
  return message;
}

// A number, said plainly when it is not one; its range is validate()'s to
// judge (run_command), so that the tool and the library agree.
CLI::Validator number(const char* description) {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        const char* const end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error == std::errc::result_out_of_range) return "'" + text + "' is out of the range of a double";
        if (error != std::errc() || stop != end) return "needs a number, not '" + text + "'";
        return {};
      },
      description);
}

// --mode: one of the modes. fast and cubic were modes until 0.3; an old
// command line that names one is told where they went.
const CLI::Validator mode_name(
    [](std::string& text) -> std::string {
      if (batchccd::mode_from_string(text)) return {};
      std::string modes;
      for (const auto& entry : batchccd::mode_names()) modes += (modes.empty() ? "" : ", ") + std::string(entry.name);
      std::string message = "'" + text + "' is not a mode (" + modes + ")";
      if (text == "fast" || text == "cubic")
        message += "; fast and cubic, modes until 0.3, may miss contacts: they are baselines of "
                   "the benchmark report (batchccd_report) now";
      return message;
    },
    "MODE");

void add_run_command(CLI::App& app, RunCommand& command) {
  CLI::App* run = app.add_subcommand("run", "evaluate query files and scenes, report counts and timing");
  run->footer(run_footer);
  run->add_option("INPUT", command.inputs, "query CSV files, scene directories, directories")
      ->required();
  run->add_option("--kind", command.kind, "kind of a query file whose path names none")
      ->check(CLI::IsMember(names_of(batchccd::kind_names())));
  run->add_option("--truth", command.truth, "ground truth for a single query file (below)");
  run->add_option("--mode", command.mode, "how decisions are made (below)")
      ->check(mode_name);
  run->add_option("--min-distance", command.min_distance,
                  "separation that counts as a contact (below; default: the data's, else 0)")
      ->check(number("D>=0"));
  run->add_option("--tmax", command.tmax, "end of the time window (below; default 1)")
      ->check(number("T in (0,1]"));
  run->add_option("--threads", command.threads, "worker threads (default: all)")
      ->check(positive_integer);
  run->add_option("--isa", command.isa, "instruction set (auto: the best available)")
      ->check(CLI::IsMember(names_of(batchccd::isa_names())));
  run->add_option("--repeat", command.repeat, "calls per input into one result; the best time (default 1)")
      ->check(positive_integer);
  run->add_flag("--time-queries", command.time_queries, "time every query for max_query_seconds")
      ->disable_flag_override();
  run->add_flag("--json", command.json, "one JSON object per input and kind on stdout")
      ->disable_flag_override();
  run->add_option("--out", command.out, "per-query results file (below)");
}

void print_reports(const RunCommand& command, const batchccd::cli::RunOutcome& outcome) {
  if (command.json) {
    for (const auto& report : outcome.reports) std::cout << batchccd::cli::json_line(report) << '\n';
  } else {
    batchccd::cli::print_table(std::cout, outcome.reports);
  }
  std::cout.flush();
}

int run_command(const RunCommand& command) {
  if (!command.truth.empty() && command.inputs.size() > 1) {
    std::cerr << "batchccd run: --truth needs a single INPUT\n";
    return exit_usage_error;
  }
  batchccd::cli::RunSettings settings;
  settings.inputs.assign(command.inputs.begin(), command.inputs.end());
  if (!command.kind.empty()) settings.kind = batchccd::kind_from_string(command.kind);
  if (!command.truth.empty()) settings.truth = command.truth;
  settings.options.mode = *batchccd::mode_from_string(command.mode);
  settings.options.isa = *batchccd::isa_from_string(command.isa);
  settings.options.threads = command.threads;
  settings.options.min_distance = command.min_distance.value_or(0);
  settings.min_distance_from_data = !command.min_distance;
  settings.options.tmax = command.tmax;
  try {
    batchccd::validate(settings.options);
  } catch (const std::invalid_argument& error) {
    std::cerr << "batchccd run: " << in_command_line_names(error.what())
              << "\nRun 'batchccd run --help' for usage.\n";
    return exit_usage_error;
  }
  settings.keep_results = !command.out.empty();
  settings.repeat = command.repeat;
  settings.time_queries = command.time_queries;
  try {
    // Refused once here rather than once per input.
    batchccd::resolve_isa(settings.options.isa);
  } catch (const std::invalid_argument& error) {
    std::cerr << "batchccd: error: " << error.what() << '\n';
    return exit_input_error;
  }
  batchccd::cli::RunOutcome outcome = batchccd::cli::run_inputs(settings, std::cerr);
  print_reports(command, outcome);
  if (!command.out.empty()) {
    try {
      batchccd::cli::write_results_file(command.out, outcome.reports);
    } catch (const std::exception& error) {
      std::cerr << "batchccd: error: " << error.what() << '\n';
      outcome.any_error = true;
    }
  }
  return outcome.any_error ? exit_input_error : exit_success;
}

// What this build and processor offer: the version, the instruction sets a
// batch call can be forced to and the one `auto` picks, the modes.
int info_command(bool json) {
  nlohmann::ordered_json info;
  info["version"] = BATCHCCD_VERSION;
  info["isas"] = nlohmann::ordered_json::array();
  for (const batchccd::Isa isa : batchccd::available_isas()) info["isas"].push_back(to_string(isa));
  info["auto_isa"] = to_string(batchccd::resolve_isa(batchccd::Isa::automatic));
  info["modes"] = names_of(batchccd::mode_names());
  if (json) {
    std::cout << info.dump() << '\n';
    return exit_success;
  }
  const auto joined = [](const nlohmann::ordered_json& list) {
    std::string text;
    for (const auto& item : list) text += (text.empty() ? "" : " ") + item.get<std::string>();
    return text;
  };
  std::cout << "batchccd " << BATCHCCD_VERSION << '\n'
            << "instruction sets: " << joined(info["isas"]) << " (auto: "
            << info["auto_isa"].get<std::string>() << ")\n"
            << "modes: " << joined(info["modes"]) << '\n';
  return exit_success;
}

int main_of(int argc, char** argv) {
  CLI::App app("Continuous collision detection over batches of vertex-face (vf), edge-edge (ee), "
               "point-edge (ve) and point-point (vv) queries.",
               "batchccd");
  app.set_version_flag("--version", std::string("batchccd ") + BATCHCCD_VERSION);
  app.require_subcommand(1);
  RunCommand run;
  add_run_command(app, run);
  bool info_json = false;
  CLI::App* info = app.add_subcommand("info", "version, instruction sets and modes of this build");
  info->add_flag("--json", info_json, "as one JSON object")->disable_flag_override();
  if (const auto status = batchccd::cli::parse_or_exit(app, argc, argv)) return *status;
  if (app.got_subcommand("info")) return info_command(info_json);
  return run_command(run);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return main_of(argc, argv);
  } catch (const std::exception& error) {
    // Unexpected failures (out of memory, a library bug) still end cleanly.
    std::cerr << "batchccd: internal error: " << error.what() << '\n';
    return exit_input_error;
  }
}

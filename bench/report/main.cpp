// batchccd_report: the benchmark report, not installed. `demo` runs every
// mode and baseline on a built-in scene, `report` on query files and scenes.

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "batchccd/batchccd.hpp"
#include "command_line.hpp"
#include "demo.hpp"

namespace {

constexpr int exit_success = 0;
constexpr int exit_error = 1;

// Progress lines go to a terminal only.
std::ostream* progress_stream() { return ::isatty(STDERR_FILENO) ? &std::cerr : nullptr; }

int main_of(int argc, char** argv) {
  CLI::App app("The benchmark report of batchccd: every mode and baseline side by side.",
               "batchccd_report");
  app.require_subcommand(1);

  batchccd::bench::DemoSettings demo;
  std::string out = demo.out.string();
  std::string scene = "cloth";
  bool methods_only = false;
  CLI::App* demo_command = app.add_subcommand(
      "demo",
      "Generates a built-in scene, runs a swept-box broad phase on it, and runs every method on "
      "the candidates: exact and conservative mode, the fast and cubic baselines, the DNF-style filter "
      "and FCL (when built with it). Prints, per method, run time, candidates per second, "
      "speed-up against cubic, cull ratio, false negatives and positives, and TOI error, all "
      "against exact mode; then what each part of a call costs, and each mode and baseline on the "
      "stiff and extreme suite. Writes report.txt, methods.csv, plot.gp and plot.png (gnuplot). About 55 "
      "CPU seconds.");
  demo_command->add_option("--scene", scene,
                           "cloth: a sheet draping, folding and twisting onto itself, 12 steps; "
                           "rigid: thin bodies moving far within one step")
      ->check(CLI::IsMember({"cloth", "rigid"}));
  demo_command->add_option("--resolution", demo.resolution,
                           "scene size: cloth vertices per side (default 128, about 4 M "
                           "candidates a step), rigid cells per body length (default 12)")
      ->check(batchccd::cli::positive_integer);
  demo_command->add_option("--threads", demo.threads, "worker threads (default: all)")
      ->check(batchccd::cli::positive_integer);
  demo_command->add_option("--out", out, "where the files go")->capture_default_str();
  demo_command->add_flag("--methods-only", methods_only, "skip the costs and the stiff and extreme suite")
      ->disable_flag_override();

  batchccd::bench::ReportSettings report;
  std::vector<std::string> inputs;
  std::string kind, report_out;
  CLI::App* report_command = app.add_subcommand(
      "report",
      "The demo's comparison on query files and scenes (INPUT as for `batchccd run`): every "
      "method, ground truth from the files (exact mode's decisions where an input has none), "
      "TOI error against exact mode. Totals on stdout; with --out, methods.csv (a row per input "
      "and method, and totals), plot.gp and plot.png.");
  report_command->add_option("INPUT", inputs, "query CSV files, scene directories, directories")
      ->required();
  report_command->add_option("--kind", kind, "kind of a query file whose path does not say")
      ->check(CLI::IsMember(batchccd::cli::names_of(batchccd::kind_names())));
  report_command->add_option("--threads", report.threads, "worker threads (default: all)")
      ->check(batchccd::cli::positive_integer);
  report_command->add_option("--out", report_out, "write methods.csv, plot.gp and plot.png there");

  if (const auto status = batchccd::cli::parse_or_exit(app, argc, argv)) return *status;

  try {
    if (app.got_subcommand(demo_command)) {
      demo.scene = scene == "rigid" ? batchccd::bench::BuiltinScene::rigid
                                    : batchccd::bench::BuiltinScene::cloth;
      demo.out = out;
      demo.sections = !methods_only;
      batchccd::bench::run_demo(demo, std::cout, progress_stream());
      return exit_success;
    }
    report.inputs.assign(inputs.begin(), inputs.end());
    if (!kind.empty()) report.kind = batchccd::kind_from_string(kind);
    if (!report_out.empty()) report.out = report_out;
    return batchccd::bench::run_report(report, std::cout, std::cerr, progress_stream())
               ? exit_success
               : exit_error;
  } catch (const std::runtime_error& error) {
    std::cerr << "batchccd_report: error: " << error.what() << '\n';
    return exit_error;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return main_of(argc, argv);
  } catch (const std::exception& error) {
    std::cerr << "batchccd_report: internal error: " << error.what() << '\n';
    return exit_error;
  }
}

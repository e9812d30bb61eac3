#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"

// `batchccd_report demo` and `batchccd_report report` without their command lines: run
// every method (compare.hpp) on a built-in scene or on input files, print
// the comparison, and write it as CSV and a gnuplot picture.
namespace batchccd::bench {

enum class BuiltinScene { cloth, rigid };

struct DemoSettings {
  BuiltinScene scene = BuiltinScene::cloth;
  int resolution = 0;  // 0: the scene's demo size (about 35 s on 2 cores)
  int threads = 0;     // 0: all
  std::filesystem::path out = "batchccd-demo";  // report.txt, methods.csv, plot.gp, plot.png
  bool sections = true;  // also the costs and the stiff and extreme suite
};

// Runs the demo. Prints the report on `out`, progress on `progress` (when
// not null: a terminal), writes the files. Throws std::runtime_error when a
// file cannot be written (the printed report is complete by then).
void run_demo(const DemoSettings& settings, std::ostream& out, std::ostream* progress);

struct ReportSettings {
  std::vector<std::filesystem::path> inputs;  // as `batchccd run` takes them
  std::optional<Kind> kind;                   // of query files whose path names none
  int threads = 0;
  std::optional<std::filesystem::path> out;   // methods.csv, plot.gp, plot.png there
};

// `batchccd report`: the comparison over input files, ground truth from the
// files (exact mode's decisions where a file has none, said in the output).
// An input that fails is reported on `errors` and the rest still run;
// returns false when one did.
bool run_report(const ReportSettings& settings, std::ostream& out, std::ostream& errors,
                std::ostream* progress);

}  // namespace batchccd::bench

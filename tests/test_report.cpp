// The benchmark report (bench/report): the comparison's tallies, and
// `batchccd_report demo` and `report` through the built executable: tables,
// methods.csv, and the plot gnuplot draws from it (or the note when there is
// no gnuplot).

#include <gtest/gtest.h>

#include "program_test.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "compare.hpp"
#include "peers/fcl_peer.hpp"
#include "plot.hpp"

namespace {

namespace fs = std::filesystem;
using program_test::edge_edge_hit_and_miss;
using program_test::lines_of;
using program_test::read_file;
using program_test::vertex_face_hit_and_miss;
using program_test::write_file;

using ReportRun = program_test::ProgramRun;

class ReportTest : public program_test::ProgramTest {
 protected:
  ReportRun run_report(const std::vector<std::string>& arguments,
             const std::vector<std::string>& environment = {}) const {
    return run(BATCHCCD_REPORT_PATH, arguments, environment);
  }

};

bool is_png(const fs::path& file) { return read_file(file).rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

// methods.csv as rows of named fields.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file) {
  const std::vector<std::string> lines = lines_of(read_file(file));
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty()) return rows;
  const auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (const char c : line) {
      if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> header = split(lines.front());
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> cells = split(lines[i]);
    EXPECT_EQ(cells.size(), header.size()) << lines[i];
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < std::min(cells.size(), header.size()); ++c) row[header[c]] = cells[c];
    rows.push_back(row);
  }
  return rows;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const auto method : batchccd::bench::compared_methods())
    names.emplace_back(batchccd::bench::name_of(method));
  return names;
}

TEST(ReportCompare, TallyCountsErrorsAgainstTruthAndToiAgainstTheReference) {
  using batchccd::QueryResult;
  batchccd::bench::MethodRun run;
  run.results = {{true, 0.5}, {false}, {true, 0.25}, {true, 0.0}};
  run.seconds = 2;
  run.culled = 1;
  const std::vector<bool> truth = {true, true, true, false};
  const std::vector<QueryResult> reference = {{true, 0.5}, {true, 0.1}, {true, 0.3}, {false}};
  batchccd::bench::MethodTally tally;
  tally.add(run, truth, reference);
  EXPECT_EQ(tally.candidates, 4);
  EXPECT_EQ(tally.false_negatives, 1);
  EXPECT_EQ(tally.false_positives, 1);
  EXPECT_EQ(tally.toi_compared, 2);
  EXPECT_DOUBLE_EQ(tally.toi_error_max, 0.05);
  EXPECT_DOUBLE_EQ(tally.toi_error_mean(), 0.025);
  EXPECT_DOUBLE_EQ(tally.candidates_per_second(), 2);
  EXPECT_DOUBLE_EQ(tally.cull_ratio(), 0.25);
  batchccd::bench::MethodTally twice = tally;
  twice += tally;
  EXPECT_EQ(twice.false_negatives, 2);
  EXPECT_DOUBLE_EQ(twice.toi_error_max, 0.05);
  EXPECT_DOUBLE_EQ(twice.toi_error_mean(), 0.025);
  EXPECT_THROW(tally.add(run, {true}, reference), std::logic_error);
}

TEST_F(ReportTest, ReportComparesEveryMethodAgainstTheFilesTruth) {
  program_test::write_small_scene(path("data/scene"));
  write_file(path("data/vf/q.csv"), vertex_face_hit_and_miss);
  write_file(path("data/ee/q.csv"), edge_edge_hit_and_miss);
  const ReportRun result = run_report({"report", "--threads", "2", "--out", "out", "data"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const std::string& method : method_names())
    EXPECT_NE(result.out.find("\n" + method + " "), std::string::npos) << method << "\n" << result.out;
  const auto rows = read_csv(path("out/methods.csv"));
  ASSERT_EQ(rows.size(), 4 * method_names().size());  // 3 inputs and the totals, per method
  for (const auto& row : rows) {
    // The inputs hold clean hits and clear misses: the certified modes get all right.
    if (row.at("method") == "exact" || row.at("method") == "conservative") {
      EXPECT_EQ(row.at("false_negatives"), "0") << row.at("input");
      EXPECT_EQ(row.at("false_positives"), "0") << row.at("input");
    }
    if (row.at("input") == "total") {
      EXPECT_EQ(row.at("candidates"), "8");
    }
  }
  const std::string script = read_file(path("out/plot.gp"));
  EXPECT_NE(script.find("'methods.csv'"), std::string::npos) << script;
  EXPECT_NE(script.find("set logscale xy"), std::string::npos) << script;
  if (batchccd::bench::find_gnuplot()) {
    EXPECT_TRUE(is_png(path("out/plot.png")));
  } else {
    EXPECT_NE(result.out.find("gnuplot not found"), std::string::npos) << result.out;
  }
  if (!batchccd::peers::fcl_available()) {
    EXPECT_NE(result.out.find("not available: built without FCL"), std::string::npos) << result.out;
  }
}

TEST_F(ReportTest, ReportGoesOnPastABadInputAndSaysSo) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  write_file(path("vf/bad.csv"), "1,1,2\n");
  const ReportRun result = run_report({"report", "vf/bad.csv", "missing", "vf/q.csv"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("bad.csv:1"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("missing"), std::string::npos) << result.err;
  EXPECT_NE(result.out.find("1 inputs, 2 candidates"), std::string::npos) << result.out;
}

TEST_F(ReportTest, DemoAndReportCommandLines) {
  for (const auto& arguments : std::vector<std::vector<std::string>>{
           {"demo", "--scene", "sphere"}, {"demo", "--resolution", "0"}, {"demo", "extra"},
           {"demo", "--methods-only=yes"}, {"report"}, {"report", "--threads", "x", "a"},
           {"report", "--bogus", "a"}, {"report", "--kind", "xy", "a"}}) {
    const ReportRun result = run_report(arguments);
    EXPECT_EQ(result.exit_code, 2) << arguments[1];
    EXPECT_NE(result.err.find("batchccd_report " + arguments[0]), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
  }
  for (const std::string command : {"demo", "report"}) {
    const ReportRun help = run_report({command, "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("batchccd_report " + command), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("--threads"), std::string::npos);
  }
}

// A small cloth: every method runs, exact mode is the truth, and the
// certified mode misses nothing. (Exact mode scored against itself proves
// nothing; ReportComparesEveryMethodAgainstTheFilesTruth scores it against
// a file's own truth.)
TEST_F(ReportTest, DemoPrintsTheTableAndWritesReportCsvAndPlot) {
  const ReportRun result = run_report({"demo", "--resolution", "24", "--threads", "2", "--out", "out"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << "progress must stay off a non-terminal: " << result.err;
  for (const char* section : {"candidates/s", "What a call pays for", "Stiff and extreme"})
    EXPECT_NE(result.out.find(section), std::string::npos) << section;
  // The tables say what they count: the cost table's need_toi row and the
  // stiff and extreme suite's columns.
  for (const char* note : {"need_toi = false changes only", "truth wrong a/b", "undecided: queries"})
    EXPECT_NE(result.out.find(note), std::string::npos) << note;
  const bool gnuplot = batchccd::bench::find_gnuplot().has_value();
  EXPECT_EQ(read_file(path("out/report.txt")) + "wrote out/report.txt, out/methods.csv, " +
                (gnuplot ? "out/plot.png, " : "") + "out/plot.gp\n" +
                (gnuplot ? "" : "plot.png not drawn: gnuplot not found (apt-get install gnuplot-nox); "
                                "plot.gp draws it from methods.csv\n"),
            result.out);
  const auto rows = read_csv(path("out/methods.csv"));
  ASSERT_EQ(rows.size(), method_names().size());
  std::map<std::string, std::map<std::string, std::string>> by_method;
  for (const auto& row : rows) by_method[row.at("method")] = row;
  EXPECT_EQ(by_method.at("conservative").at("false_negatives"), "0");
  EXPECT_GT(std::stod(by_method.at("conservative").at("cull_ratio")), 0.9);
  EXPECT_EQ(by_method.at("cubic").at("culled"), "0");
  // The scene has contacts: TOIs were compared.
  EXPECT_GT(std::stol(by_method.at("conservative").at("toi_compared")), 0);
  if (gnuplot) {
    EXPECT_TRUE(is_png(path("out/plot.png")));
  }
}

TEST_F(ReportTest, DemoIntoAnUnwritableDirectoryIsAnErrorAfterTheReport) {
  write_file(path("blocker"), "a file where the directory should go");
  const ReportRun result =
      run_report({"demo", "--scene", "rigid", "--resolution", "2", "--methods-only", "--out", "blocker/out"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.out.find("candidates/s"), std::string::npos);  // the report came first
  EXPECT_NE(result.err.find("blocker"), std::string::npos) << result.err;
}

// Without gnuplot the report says so and still writes the CSV and the script.
TEST_F(ReportTest, WithoutGnuplotTheCsvAndTheScriptAreStillWritten) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const ReportRun result = run_report({"report", "--out", "out", "vf/q.csv"}, {"PATH=/nonexistent"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("plot.png not drawn: gnuplot not found"), std::string::npos) << result.out;
  EXPECT_FALSE(fs::exists(path("out/plot.png")));
  EXPECT_FALSE(read_file(path("out/methods.csv")).empty());
  EXPECT_FALSE(read_file(path("out/plot.gp")).empty());
}

// The script as gnuplot runs it: a PNG from a CSV with every kind of row,
// zeros on the log axes included.
using ReportPlot = test_support::TemporaryDirectoryTest;

TEST_F(ReportPlot, GnuplotDrawsTheCsv) {
  const auto gnuplot = batchccd::bench::find_gnuplot();
  if (!gnuplot) GTEST_SKIP() << "no gnuplot on PATH";
  const fs::path& directory = this->directory();
  write_file(directory / "methods.csv",
             "input,method,seconds,candidates,candidates_per_second,culled,cull_ratio,false_negatives,"
             "false_positives,toi_compared,toi_error_max,toi_error_mean\n"
             "a.csv,exact,0.5,10,20,9,0.9,0,0,1,0,0\n"
             "total,exact,0.5,10,20,9,0.9,0,0,1,0,0\n"
             "total,cubic,0.05,10,200,0,0,2,1,1,0.001,0.001\n"
             "\"dir, with a comma/q.csv\",fast,0.1,10,100,0,0,0,3,1,1e-9,1e-9\n"
             "total,fast,0.1,10,100,0,0,0,3,1,1e-9,1e-9\n");
  write_file(directory / "plot.gp", batchccd::bench::plot_script("a 'title'", "methods.csv", "plot.png",
                                                                     {"exact", "cubic", "fast"}));
  EXPECT_NO_THROW(batchccd::bench::run_gnuplot(*gnuplot, directory, "plot.gp"));
  EXPECT_TRUE(is_png(directory / "plot.png"));
  // Nothing wrong and no TOI error anywhere: every axis still has a range.
  fs::remove(directory / "plot.png");
  write_file(directory / "methods.csv",
             "input,method,seconds,candidates,candidates_per_second,culled,cull_ratio,false_negatives,"
             "false_positives,toi_compared,toi_error_max,toi_error_mean\n"
             "total,exact,0.5,10,20,9,0.9,0,0,1,0,0\n");
  EXPECT_NO_THROW(batchccd::bench::run_gnuplot(*gnuplot, directory, "plot.gp"));
  EXPECT_TRUE(is_png(directory / "plot.png"));
  write_file(directory / "broken.gp", "plot nonsense(\n");
  EXPECT_THROW(batchccd::bench::run_gnuplot(*gnuplot, directory, "broken.gp"), std::runtime_error);
}

}  // namespace

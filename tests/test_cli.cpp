// The command-line tool: argument handling and exit codes through the built
// executable, the rest in process through run_inputs (the same code path).

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "program_test.hpp"

#include <nlohmann/json.hpp>

#include "batchccd/batchccd.hpp"
#include "report_format.hpp"
#include "run.hpp"
#include "shared_data.hpp"

namespace {

namespace fs = std::filesystem;
using program_test::edge_edge_hit;
using program_test::edge_edge_hit_and_miss;
using program_test::edge_edge_miss;
using program_test::lines_of;
using program_test::query_csv;
using program_test::QuarterPoint;
using program_test::QueryPoints;
using program_test::read_file;
using program_test::TestQuery;
using program_test::vertex_face_hit;
using program_test::vertex_face_hit_and_miss;
using program_test::vertex_face_miss;
using program_test::write_file;
using batchccd::Kind;
using batchccd::cli::InputReport;
using batchccd::cli::RunOutcome;
using batchccd::cli::RunSettings;

// ---- query files ----------------------------------------------------------

// A query of a point kind: its points at t0, then at t1, each once (ve 6
// rows, vv 4), with its truth.
struct PointQuery {
  std::vector<QuarterPoint> points;
  bool truth;
};

std::string point_query_csv(const std::vector<PointQuery>& queries) {
  std::ostringstream text;
  for (const PointQuery& query : queries)
    for (const QuarterPoint& point : query.points)
      text << point.x << ",4," << point.y << ",4," << point.z << ",4," << (query.truth ? 1 : 0) << '\n';
  return text.str();
}

// p falls through the static edge (0,0,0)-(1,0,0) at t = 1/2.
const PointQuery vertex_edge_hit{{{2, 0, 4}, {0, 0, 0}, {4, 0, 0}, {2, 0, -4}, {0, 0, 0}, {4, 0, 0}}, true};
// p stays far from the edge.
const PointQuery vertex_edge_miss{{{2, 40, 4}, {0, 0, 0}, {4, 0, 0}, {2, 40, -4}, {0, 0, 0}, {4, 0, 0}}, false};
// p falls through the still point q at the origin at t = 1/2.
const PointQuery vertex_vertex_hit{{{0, 0, 4}, {0, 0, 0}, {0, 0, -4}, {0, 0, 0}}, true};
// p passes the still point q at the origin 1/4 away at t = 1/2: a contact
// exactly when the minimum distance is at least 1/4.
PointQuery vertex_vertex_pass(bool truth) { return {{{-4, 1, 0}, {0, 0, 0}, {4, 1, 0}, {0, 0, 0}}, truth}; }

// The small scene of program_test.hpp, with a query file of its own.
void write_scene(const fs::path& directory) {
  program_test::write_small_scene(directory);
  // A scene's own query file belongs to the scene, not to a directory search.
  write_file(directory / "queries_vf.csv", vertex_face_hit_and_miss);
}

// ---- JSON -------------------------------------------------------------------

// One JSON object's fields: strings as they are, other values as JSON text
// ("3", "null", "true"). Empty, with a test failure, when the line is not one.
std::map<std::string, std::string> parse_json_line(const std::string& line) {
  std::map<std::string, std::string> fields;
  const nlohmann::json object = nlohmann::json::parse(line, nullptr, false);
  EXPECT_TRUE(object.is_object()) << "not a JSON object: " << line;
  if (!object.is_object()) return fields;
  for (const auto& [name, value] : object.items())
    fields[name] = value.is_string() ? value.get<std::string>() : value.dump();
  return fields;
}

const std::vector<std::string> json_field_names = {
    "input",     "kind",           "mode",           "min_distance", "tmax", "isa",
    "threads",   "queries",        "hits",           "positives",
    "false_positives", "false_negatives", "truth_min_distance", "truth_tmax", "culled", "seconds",
    "queries_per_second", "exact_escalations", "max_query_seconds"};

// ---- running the executable -------------------------------------------------

using CliRun = program_test::ProgramRun;

class CliTest : public program_test::ProgramTest {
 protected:
  CliRun run_cli(const std::vector<std::string>& arguments,
             const std::vector<std::string>& environment = {}) const {
    return run(BATCHCCD_CLI_PATH, arguments, environment);
  }

  // The JSON objects printed by `batchccd run --json ARGUMENTS`.
  std::vector<std::map<std::string, std::string>> run_json(std::vector<std::string> arguments,
                                                           int expected_exit = 0) const {
    arguments.insert(arguments.begin(), {"run", "--json"});
    const CliRun result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, expected_exit) << result.err;
    std::vector<std::map<std::string, std::string>> objects;
    for (const std::string& line : lines_of(result.out)) objects.push_back(parse_json_line(line));
    return objects;
  }

  std::vector<fs::path> files_containing(const std::string& fragment) const {
    std::vector<fs::path> found;
    for (const auto& entry : fs::recursive_directory_iterator(directory())) {
      if (entry.path().filename().string().find(fragment) != std::string::npos)
        found.push_back(entry.path());
    }
    return found;
  }

};

// ---- command line -----------------------------------------------------------

TEST_F(CliTest, NoArgumentsPrintsUsageAndExitsTwo) {
  const CliRun result = run_cli({});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("run"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("info"), std::string::npos) << result.err;
  EXPECT_TRUE(result.out.empty());
}

TEST_F(CliTest, HelpDocumentsEveryOption) {
  const CliRun general = run_cli({"--help"});
  EXPECT_EQ(general.exit_code, 0);
  for (const char* command : {"run", "info"})
    EXPECT_NE(general.out.find(command), std::string::npos) << command;
  const CliRun run = run_cli({"run", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  for (const char* option : {"--kind", "--truth", "--mode", "--threads", "--isa", "--json", "--repeat", "--time-queries",
                             "--out", "conservative", "exact", "avx512",
                             "INPUT", "exact_escalations", "max_query_seconds", "Exit status",
                             "--min-distance", "--tmax", "min_distance", "tmax", "point-edge",
                             "point-point", "vertex-vertex", "8 rows", "6 rows", "4 rows",
                             "ve.csv", "vv.csv", "vv_truth.txt"}) {
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  }
}

TEST_F(CliTest, VersionIsTheLibrarysVersion) {
  const CliRun result = run_cli({"--version"});
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.out, std::string("batchccd ") + BATCHCCD_VERSION + "\n");
}

TEST_F(CliTest, BadCommandLinesExitTwoPointingToHelp) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const std::vector<std::vector<std::string>> bad_command_lines = {
      {"frobnicate"},
      {"run"},
      {"run", "--json"},
      {"run", "--bogus", "vf/q.csv"},
      {"run", "--mode", "exactly", "vf/q.csv"},
      {"run", "--mode=sloppy", "vf/q.csv"},
      {"run", "--mode", "1", "vf/q.csv"},
      {"run", "vf/q.csv", "--mode"},
      {"run", "--threads", "0", "vf/q.csv"},
      {"run", "--threads", "-2", "vf/q.csv"},
      {"run", "--threads", "two", "vf/q.csv"},
      {"run", "--threads", "3x", "vf/q.csv"},
      {"run", "--isa", "sve", "vf/q.csv"},
      {"run", "--kind", "xy", "vf/q.csv"},
      {"run", "--json=yes", "vf/q.csv"},
      {"run", "--truth", "t.txt", "vf/q.csv", "vf/q.csv"},
      {"info", "extra"},
  };
  for (const auto& arguments : bad_command_lines) {
    const CliRun result = run_cli(arguments);
    std::string shown;
    for (const auto& argument : arguments) shown += argument + " ";
    EXPECT_EQ(result.exit_code, 2) << shown << "\n" << result.err;
    EXPECT_NE(result.err.find("batchccd"), std::string::npos) << shown << "\n" << result.err;
    EXPECT_TRUE(result.out.empty()) << shown;
  }
}

// fast and cubic, modes until 0.3, are benchmark baselines: an old command
// line is refused with the value named and told where they went.
TEST_F(CliTest, FormerModesAreRefusedNamingTheValue) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  for (const char* former : {"fast", "cubic"}) {
    const CliRun result = run_cli({"run", "--mode", former, "vf/q.csv"});
    EXPECT_EQ(result.exit_code, 2) << former << "\n" << result.err;
    EXPECT_TRUE(result.out.empty()) << former;
    EXPECT_NE(result.err.find(std::string("'") + former + "' is not a mode (conservative, exact)"),
              std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("baselines"), std::string::npos) << result.err;
  }
  // Any other unknown name: the modes, without the note.
  const CliRun typo = run_cli({"run", "--mode", "exactly", "vf/q.csv"});
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("'exactly' is not a mode (conservative, exact)"), std::string::npos) << typo.err;
  EXPECT_EQ(typo.err.find("baselines"), std::string::npos) << typo.err;
}

TEST_F(CliTest, AcceptsEveryDocumentedOptionForm) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"run", "--mode", "conservative", "--threads", "2", "vf/q.csv"},
        std::vector<std::string>{"run", "--mode=exact", "--isa=scalar", "vf/q.csv"},
        std::vector<std::string>{"run", "--mode", "exact", "vf/q.csv"},
        std::vector<std::string>{"run", "--isa", "auto", "--kind", "vf", "--", "vf/q.csv"}}) {
    const CliRun result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, 0) << result.err;
  }
}

// After "--" an argument that looks like an option is an input.
TEST_F(CliTest, DoubleDashEndsTheOptions) {
  write_file(path("-vf.csv"), vertex_face_hit_and_miss);
  const auto objects = run_json({"--kind", "vf", "--", "-vf.csv"});
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].at("input"), "-vf.csv");
}

TEST_F(CliTest, BadMinDistanceOrTmaxExitsTwoNamingOptionAndValue) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  struct Case {
    std::vector<std::string> arguments;
    std::string option;
    std::string problem;  // besides the option
  };
  // The library's words (options.hpp, validate) after the flag's name.
  const std::vector<Case> cases = {
      {{"--min-distance", "-1"}, "--min-distance", "--min-distance must be >= 0 and finite, got -1"},
      {{"--min-distance=-0.5"}, "--min-distance", "--min-distance must be >= 0 and finite, got -0.5"},
      {{"--min-distance", "nan"}, "--min-distance", "--min-distance must be >= 0 and finite, got nan"},
      {{"--min-distance", "inf"}, "--min-distance", "--min-distance must be >= 0 and finite, got inf"},
      {{"--min-distance", "1e999"}, "--min-distance", "'1e999' is out of the range of a double"},
      {{"--min-distance", "tiny"}, "--min-distance", "needs a number, not 'tiny'"},
      {{"--min-distance", "1e-3x"}, "--min-distance", "needs a number, not '1e-3x'"},
      {{"--tmax", "0"}, "--tmax", "--tmax must be in (0, 1], got 0"},
      {{"--tmax", "1.5"}, "--tmax", "--tmax must be in (0, 1], got 1.5"},
      {{"--tmax=-0.25"}, "--tmax", "--tmax must be in (0, 1], got -0.25"},
      {{"--tmax", ""}, "--tmax", "needs a number, not ''"},
  };
  for (const Case& bad : cases) {
    std::vector<std::string> arguments = {"run"};
    arguments.insert(arguments.end(), bad.arguments.begin(), bad.arguments.end());
    arguments.push_back("vf/q.csv");
    const CliRun result = run_cli(arguments);
    std::string shown;
    for (const auto& argument : arguments) shown += argument + " ";
    EXPECT_EQ(result.exit_code, 2) << shown << "\n" << result.err;
    EXPECT_NE(result.err.find("batchccd run: " + bad.option), std::string::npos) << shown << "\n" << result.err;
    EXPECT_NE(result.err.find(bad.problem), std::string::npos) << shown << "\n" << result.err;
    EXPECT_TRUE(result.out.empty()) << shown;
  }
  // The ends of the ranges are values like any other.
  for (const std::vector<std::string>& good :
       {std::vector<std::string>{"--min-distance", "0", "--tmax", "1"},
        std::vector<std::string>{"--min-distance=1e300", "--tmax=4.9e-324"}}) {
    std::vector<std::string> arguments = {"run"};
    arguments.insert(arguments.end(), good.begin(), good.end());
    arguments.push_back("vf/q.csv");
    EXPECT_EQ(run_cli(arguments).exit_code, 0) << good[0];
  }
}

// The separation and the time window reach the call: the same queries
// change their answers where the geometry says they must.
TEST_F(CliTest, MinDistanceAndTmaxDecide) {
  write_file(path("vv/pass.csv"), point_query_csv({vertex_vertex_pass(true)}));  // truth for 0.3
  write_file(path("vv/ms.txt"), "0.3\n");
  const auto within = run_json({"--min-distance", "0.3", "vv/pass.csv"});
  ASSERT_EQ(within.size(), 1u);
  EXPECT_EQ(within[0].at("min_distance"), "0.3");
  EXPECT_EQ(within[0].at("hits"), "1");
  EXPECT_EQ(within[0].at("false_negatives"), "0");
  const auto exact = run_json({"--mode", "exact", "--min-distance", "0.3", "vv/pass.csv"});
  ASSERT_EQ(exact.size(), 1u);
  EXPECT_EQ(exact[0].at("hits"), "1");
  const auto beyond = run_json({"--min-distance", "0.2", "vv/pass.csv"});
  ASSERT_EQ(beyond.size(), 1u);
  EXPECT_EQ(beyond[0].at("hits"), "0");
  EXPECT_EQ(beyond[0].at("false_negatives"), "null");  // labelled for 0.3: not scored
  EXPECT_EQ(run_json({"--min-distance", "0", "vv/pass.csv"}).at(0).at("hits"), "0");

  // The vertex-face hit is at t = 1/2.
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const auto cut_off = run_json({"--tmax", "0.25", "vf/q.csv"});
  ASSERT_EQ(cut_off.size(), 1u);
  EXPECT_EQ(cut_off[0].at("tmax"), "0.25");
  EXPECT_EQ(cut_off[0].at("hits"), "0");
  const auto kept = run_json({"--tmax=0.75", "--out", "results.txt", "vf/q.csv"});
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].at("hits"), "1");
  const auto lines = lines_of(read_file(path("results.txt")));
  ASSERT_EQ(lines.size(), 2u);
  ASSERT_EQ(lines[0].rfind("1,", 0), 0u) << lines[0];
  const double toi = std::stod(lines[0].substr(2));
  EXPECT_LE(toi, 0.5);
  EXPECT_GE(toi, 0.5 - 1e-6);

  // The table's first line says both.
  const CliRun table = run_cli({"run", "--min-distance", "0.3", "--tmax", "0.5", "vv/pass.csv"});
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("min_distance 0.3, tmax 0.5"), std::string::npos) << table.out;
}

TEST_F(CliTest, PointEdgeAndPointPointQueryFiles) {
  write_file(path("data/point-edge/q.csv"), point_query_csv({vertex_edge_hit, vertex_edge_miss}));
  write_file(path("data/vv/q.csv"), point_query_csv({vertex_vertex_pass(false), vertex_vertex_hit}));
  const auto objects = run_json({"--out", "results.txt", "data"});
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].at("input"), "data/point-edge/q.csv");
  EXPECT_EQ(objects[0].at("kind"), "ve");
  EXPECT_EQ(objects[1].at("kind"), "vv");
  for (const auto& object : objects) {
    EXPECT_EQ(object.size(), json_field_names.size());
    EXPECT_EQ(object.at("queries"), "2");
    EXPECT_EQ(object.at("hits"), "1");
    EXPECT_EQ(object.at("false_positives"), "0");
    EXPECT_EQ(object.at("false_negatives"), "0");
  }
  const auto lines = lines_of(read_file(path("results.txt")));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("1,", 0), 0u);
  EXPECT_EQ(lines[1], "0,inf");
  EXPECT_EQ(lines[2], "0,inf");
  EXPECT_EQ(lines[3].rfind("1,", 0), 0u);

  // A file that names no kind takes --kind; read as another kind, its rows
  // do not divide into queries.
  write_file(path("plain.csv"), point_query_csv({vertex_edge_hit}));
  EXPECT_EQ(run_json({"--kind", "ve", "plain.csv"}).at(0).at("hits"), "1");
  const CliRun as_vv = run_cli({"run", "--kind", "vv", "plain.csv"});
  EXPECT_EQ(as_vv.exit_code, 1);
  EXPECT_NE(as_vv.err.find("plain.csv:6: row count 6 is not a multiple of 4"), std::string::npos) << as_vv.err;
}

// write_scene plus point-edge and point-point candidates, labelled for a
// minimum distance of 0.4 (the vf and ee labels hold there too): vertex 3
// passes edge 0-1 0.25 away and vertex 0 0.354 away; 6 and 7 stay far.
void write_point_scene(const fs::path& directory) {
  write_scene(directory);
  write_file(directory / "ve.csv", "3,0,1\n3,6,7\n");
  write_file(directory / "ve_truth.txt", "1\n0\n");
  write_file(directory / "vv.csv", "6,7\n3,0\n");
  write_file(directory / "vv_truth.txt", "0\n1\n");
  write_file(directory / "ms.txt", "0.4\n");
}

TEST_F(CliTest, SceneWithPointCandidatesGivesFourReports) {
  write_point_scene(path("scene"));
  const auto objects = run_json({"--min-distance", "0.4", "--out", "results.txt", "scene"});
  ASSERT_EQ(objects.size(), 4u);
  const std::vector<std::string> kinds = {"vf", "ee", "ve", "vv"};
  for (std::size_t i = 0; i < objects.size(); ++i) {
    EXPECT_EQ(objects[i].at("kind"), kinds[i]);
    EXPECT_EQ(objects[i].at("input"), "scene");
    EXPECT_EQ(objects[i].at("queries"), "2") << kinds[i];
    EXPECT_EQ(objects[i].at("hits"), "1") << kinds[i];
    EXPECT_EQ(objects[i].at("false_negatives"), "0") << kinds[i];
    EXPECT_EQ(objects[i].at("false_positives"), "0") << kinds[i];
  }
  const auto lines = lines_of(read_file(path("results.txt")));
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[4].rfind("1,", 0), 0u);  // ve 3 against edge 0-1
  EXPECT_EQ(lines[5], "0,inf");
  EXPECT_EQ(lines[6], "0,inf");  // vv 6, 7
  EXPECT_EQ(lines[7].rfind("1,", 0), 0u);

  // Touching, neither point candidate collides.
  const auto touching = run_json({"--min-distance", "0", "scene"});
  ASSERT_EQ(touching.size(), 4u);
  EXPECT_EQ(touching[2].at("hits"), "0");
  EXPECT_EQ(touching[3].at("hits"), "0");

  // An empty ve.csv still gives its (empty) report; a bad id is named with its line.
  write_file(path("scene/ve.csv"), "");
  fs::remove(path("scene/ve_truth.txt"));
  EXPECT_EQ(run_json({"scene"}).at(2).at("queries"), "0");
  write_file(path("scene/vv.csv"), "6,7\n3,8\n");
  const CliRun bad = run_cli({"run", "scene"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("vv.csv:2: vertex id 8 is out of range"), std::string::npos) << bad.err;
}

// ---- output -----------------------------------------------------------------

TEST_F(CliTest, JsonHasEveryFieldAndCountsAgainstTruth) {
  write_file(path("vertex-face/q.csv"), vertex_face_hit_and_miss);
  const auto objects = run_json({"--threads", "3", "vertex-face/q.csv"});
  ASSERT_EQ(objects.size(), 1u);
  const auto& object = objects.front();
  for (const std::string& name : json_field_names) {
    EXPECT_EQ(object.count(name), 1u) << name;
  }
  EXPECT_EQ(object.size(), json_field_names.size());
  EXPECT_EQ(object.at("input"), "vertex-face/q.csv");
  EXPECT_EQ(object.at("kind"), "vf");
  EXPECT_EQ(object.at("mode"), "conservative");
  EXPECT_EQ(object.at("min_distance"), "0.0");
  EXPECT_EQ(object.at("tmax"), "1.0");
  EXPECT_EQ(object.at("isa"), batchccd::to_string(batchccd::resolve_isa(batchccd::Isa::automatic)));
  EXPECT_EQ(object.at("threads"), "3");
  EXPECT_EQ(object.at("queries"), "2");
  EXPECT_EQ(object.at("hits"), "1");
  EXPECT_EQ(object.at("positives"), "1");
  EXPECT_EQ(object.at("false_positives"), "0");
  EXPECT_EQ(object.at("false_negatives"), "0");
  EXPECT_GE(std::stod(object.at("seconds")), 0.0);
}

TEST_F(CliTest, JsonCountsExactEscalationsAndTheSlowestQueryInEveryMode) {
  write_file(path("vertex-face/q.csv"), vertex_face_hit_and_miss);
  for (const char* mode : {"conservative", "exact"}) {
    // Untimed queries: no slowest one.
    EXPECT_EQ(run_json({"--mode", mode, "vertex-face/q.csv"}).front().at("max_query_seconds"), "null");
    const auto objects = run_json({"--mode", mode, "--time-queries", "vertex-face/q.csv"});
    ASSERT_EQ(objects.size(), 1u) << mode;
    const auto& object = objects.front();
    EXPECT_EQ(object.at("mode"), mode);
    EXPECT_EQ(object.at("false_positives"), "0") << mode;
    EXPECT_EQ(object.at("false_negatives"), "0") << mode;
    // Timed: a number, not null (what it measures is the benchmarks' business).
    EXPECT_NE(object.at("max_query_seconds"), "null") << mode;
    // Exact arithmetic here at most for the hit's TOI.
    EXPECT_LE(std::stoi(object.at("exact_escalations")), 1) << mode;
  }
}

// --repeat runs the same call into one result: the same answers and
// counts as one call, the best time of the repeats.
TEST_F(CliTest, RepeatGivesTheSameAnswersAndItsBestTime) {
  write_file(path("vertex-face/q.csv"), vertex_face_hit_and_miss);
  const auto once = run_json({"vertex-face/q.csv"});
  const auto repeated = run_json({"--repeat", "5", "vertex-face/q.csv"});
  ASSERT_EQ(once.size(), 1u);
  ASSERT_EQ(repeated.size(), 1u);
  for (const char* field : {"queries", "hits", "false_positives", "false_negatives", "culled", "exact_escalations"})
    EXPECT_EQ(repeated[0].at(field), once[0].at(field)) << field;
  EXPECT_GE(std::stod(repeated[0].at("seconds")), 0.0);
  EXPECT_EQ(run_cli({"run", "--repeat", "3", "--out", "results.csv", "vertex-face/q.csv"}).exit_code, 0);
  EXPECT_EQ(lines_of(read_file(path("results.csv"))).size(), 2u);
  const CliRun zero = run_cli({"run", "--repeat", "0", "vertex-face/q.csv"});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--repeat"), std::string::npos) << zero.err;
}

TEST_F(CliTest, TruthFieldsAreNullWithoutTruthAndFilledByTruthFile) {
  write_file(path("queries.csv"),
             query_csv({{vertex_face_hit, true}, {vertex_face_miss, false}}, false));
  write_file(path("truth.txt"), "1\n0\n");
  const auto without_truth = run_json({"--kind", "vf", "queries.csv"});
  ASSERT_EQ(without_truth.size(), 1u);
  for (const char* name : {"positives", "false_positives", "false_negatives"}) {
    EXPECT_EQ(without_truth[0].at(name), "null") << name;
  }
  const auto with_truth = run_json({"--kind", "vf", "--truth", "truth.txt", "queries.csv"});
  ASSERT_EQ(with_truth.size(), 1u);
  EXPECT_EQ(with_truth[0].at("positives"), "1");
  EXPECT_EQ(with_truth[0].at("false_negatives"), "0");
}

TEST_F(CliTest, TruthFileOfTheWrongLengthIsAnInputError) {
  write_file(path("vf/queries.csv"), query_csv({{vertex_face_hit, true}}, false));
  write_file(path("truth.txt"), "1\n0\n");
  const CliRun result = run_cli({"run", "--truth", "truth.txt", "vf/queries.csv"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("truth.txt"), std::string::npos) << result.err;
}

TEST_F(CliTest, TableHasOneRowPerInputAndATotalsRow) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  write_file(path("ee/q.csv"), edge_edge_hit_and_miss);
  const CliRun result = run_cli({"run", "vf/q.csv", "ee/q.csv"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  const auto lines = lines_of(result.out);
  ASSERT_EQ(lines.size(), 5u) << result.out;  // settings, header, two rows, totals
  EXPECT_NE(lines[0].find("conservative"), std::string::npos);
  EXPECT_EQ(lines[1].rfind("input", 0), 0u);
  EXPECT_EQ(lines[2].rfind("vf/q.csv", 0), 0u);
  EXPECT_EQ(lines[3].rfind("ee/q.csv", 0), 0u);
  EXPECT_EQ(lines[4].rfind("total", 0), 0u);
  // Right-aligned numbers: every row ends where the header ends.
  for (std::size_t row = 2; row < lines.size(); ++row) EXPECT_EQ(lines[row].size(), lines[1].size());
}

TEST_F(CliTest, OutWritesOneLinePerQueryInOrderAtomically) {
  write_file(path("vertex-face/q.csv"),
             query_csv({{vertex_face_hit, true}, {vertex_face_miss, false}, {vertex_face_hit, true}}));
  write_file(path("edge-edge/q.csv"), query_csv({{edge_edge_miss, false}, {edge_edge_hit, true}}));
  write_file(path("results.txt"), "old content\n");
  const CliRun result =
      run_cli({"run", "--out", "results.txt", "vertex-face/q.csv", "edge-edge/q.csv"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  const auto lines = lines_of(read_file(path("results.txt")));
  ASSERT_EQ(lines.size(), 5u);
  const std::vector<bool> expected_hits = {true, false, true, false, true};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (expected_hits[i]) {
      ASSERT_EQ(lines[i].rfind("1,", 0), 0u) << lines[i];
      const double toi = std::stod(lines[i].substr(2));
      EXPECT_LE(toi, 0.5);
      EXPECT_GT(toi, 0.5 - 1e-6);
    } else {
      EXPECT_EQ(lines[i], "0,inf");
    }
  }
  EXPECT_TRUE(files_containing(".tmp-").empty());
}

TEST_F(CliTest, OutIntoAMissingDirectoryFailsWithoutLeavingFiles) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const CliRun result = run_cli({"run", "--out", "no/such/dir/results.txt", "vf/q.csv"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("results.txt"), std::string::npos) << result.err;
  EXPECT_TRUE(files_containing(".tmp-").empty());
}

TEST_F(CliTest, InputErrorAmongSeveralStillReportsTheOthers) {
  write_file(path("vf/good.csv"), vertex_face_hit_and_miss);
  write_file(path("vf/bad.csv"), "1,1,2,1\n");
  write_file(path("ee/good.csv"), edge_edge_hit_and_miss);
  const CliRun result = run_cli({"run", "--json", "--out", "results.txt", "vf/good.csv",
                                 "vf/bad.csv", "missing/vf.csv", "ee/good.csv"});
  EXPECT_EQ(result.exit_code, 1);
  const auto lines = lines_of(result.out);
  ASSERT_EQ(lines.size(), 2u) << result.out;
  EXPECT_EQ(parse_json_line(lines[0]).at("input"), "vf/good.csv");
  EXPECT_EQ(parse_json_line(lines[1]).at("input"), "ee/good.csv");
  EXPECT_NE(result.err.find("vf/bad.csv"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("missing/vf.csv"), std::string::npos) << result.err;
  EXPECT_EQ(lines_of(read_file(path("results.txt"))).size(), 4u);
}

// ---- finding inputs ------------------------------------------------------------

// `run data/*` also names a folder's LICENSE: noted and passed over.
TEST_F(CliTest, PlainFileThatIsNoCsvIsPassedOverWithANote) {
  write_file(path("vf/good.csv"), vertex_face_hit_and_miss);
  write_file(path("LICENSE"), "not a query file\n");
  const CliRun result = run_cli({"run", "--json", "vf/good.csv", "LICENSE"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(lines_of(result.out).size(), 1u);
  EXPECT_NE(result.err.find("LICENSE: skipped"), std::string::npos) << result.err;
}

// A path the system cannot stat (a component over 255 characters) is an
// input error like any other: the good inputs' results are kept.
TEST_F(CliTest, UnstatablePathLosesNothing) {
  write_file(path("vf/good.csv"), vertex_face_hit_and_miss);
  const CliRun result =
      run_cli({"run", "--json", "--out", "results.txt", "vf/good.csv", std::string(300, 'a')});
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_EQ(lines_of(result.out).size(), 1u) << result.out;
  EXPECT_EQ(lines_of(read_file(path("results.txt"))).size(), 2u);
}

// An instruction set this processor lacks is refused, never silently
// replaced; BATCHCCD_HIDE_ISA makes one unavailable on any machine.
TEST_F(CliTest, UnavailableInstructionSetIsAnError) {
  write_file(path("vf/good.csv"), vertex_face_hit_and_miss);
  const CliRun result = run_cli({"run", "--isa", "avx2", "vf/good.csv"}, {"BATCHCCD_HIDE_ISA=avx2"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("avx2"), std::string::npos) << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
  // Hidden sets are also left out of what auto picks and of what info lists.
  const CliRun info = run_cli({"info", "--json"}, {"BATCHCCD_HIDE_ISA=sse4,avx2,avx512,neon"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json object = nlohmann::json::parse(info.out);
  EXPECT_EQ(object.at("isas"), nlohmann::json::array({"scalar"}));
  EXPECT_EQ(object.at("auto_isa"), "scalar");
  const auto objects = run_json({"vf/good.csv"});
  ASSERT_EQ(objects.size(), 1u);
}

TEST_F(CliTest, InfoListsWhatThisBuildOffers) {
  const CliRun result = run_cli({"info", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json object = nlohmann::json::parse(result.out);
  EXPECT_EQ(object.at("version"), BATCHCCD_VERSION);
  std::vector<std::string> isas;
  for (const batchccd::Isa isa : batchccd::available_isas()) isas.emplace_back(batchccd::to_string(isa));
  EXPECT_EQ(object.at("isas"), nlohmann::json(isas));
  EXPECT_EQ(object.at("auto_isa"), batchccd::to_string(batchccd::resolve_isa(batchccd::Isa::automatic)));
  EXPECT_EQ(object.at("modes").size(), batchccd::mode_names().size());
  const CliRun text = run_cli({"info"});
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("instruction sets: scalar"), std::string::npos) << text.out;
}

TEST_F(CliTest, KindComesFromThePathOrFromKindOption) {
  write_file(path("edge-edge/a.csv"), edge_edge_hit_and_miss);
  write_file(path("plain/queries_vf.csv"), vertex_face_hit_and_miss);
  write_file(path("plain/unnamed.csv"), edge_edge_hit_and_miss);

  const auto named = run_json({"edge-edge/a.csv", "plain/queries_vf.csv"});
  ASSERT_EQ(named.size(), 2u);
  EXPECT_EQ(named[0].at("kind"), "ee");
  EXPECT_EQ(named[1].at("kind"), "vf");

  const CliRun unnamed = run_cli({"run", "plain/unnamed.csv"});
  EXPECT_EQ(unnamed.exit_code, 1);
  EXPECT_NE(unnamed.err.find("--kind"), std::string::npos) << unnamed.err;

  const auto given = run_json({"--kind", "ee", "plain/unnamed.csv"});
  ASSERT_EQ(given.size(), 1u);
  EXPECT_EQ(given[0].at("kind"), "ee");
  EXPECT_EQ(given[0].at("hits"), "1");
}

TEST_F(CliTest, DirectoriesAreSearchedRecursivelyInSortedOrder) {
  write_file(path("data/b/vertex-face/q.csv"), vertex_face_hit_and_miss);
  write_file(path("data/a/edge-edge/q2.csv"), edge_edge_hit_and_miss);
  write_file(path("data/a/edge-edge/q1.csv"), edge_edge_hit_and_miss);
  write_file(path("data/unnamed.csv"), vertex_face_hit_and_miss);  // no kind: skipped
  write_file(path("data/notes.txt"), "not a query file\n");
  const auto objects = run_json({"data"});
  ASSERT_EQ(objects.size(), 3u);
  EXPECT_EQ(objects[0].at("input"), "data/a/edge-edge/q1.csv");
  EXPECT_EQ(objects[1].at("input"), "data/a/edge-edge/q2.csv");
  EXPECT_EQ(objects[2].at("input"), "data/b/vertex-face/q.csv");
  EXPECT_EQ(objects[2].at("kind"), "vf");
}

TEST_F(CliTest, DirectoryWithoutInputsIsAnError) {
  write_file(path("empty/notes.txt"), "nothing here\n");
  const CliRun result = run_cli({"run", "empty"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("empty"), std::string::npos);
}

TEST_F(CliTest, SceneGivesOneReportPerKindVertexFaceFirst) {
  write_scene(path("data/scene"));
  write_file(path("data/vf/q.csv"), vertex_face_hit_and_miss);
  RunSettings settings;
  settings.inputs = {path("data")};
  settings.keep_results = true;
  std::ostringstream errors;
  const RunOutcome outcome = batchccd::cli::run_inputs(settings, errors);
  EXPECT_FALSE(outcome.any_error) << errors.str();
  ASSERT_EQ(outcome.reports.size(), 3u);  // the scene's queries_vf.csv is not an input
  const InputReport& vertex_face = outcome.reports[0];
  const InputReport& edge_edge = outcome.reports[1];
  EXPECT_EQ(vertex_face.input, path("data/scene").string());
  EXPECT_EQ(vertex_face.kind, Kind::vertex_face);
  EXPECT_EQ(edge_edge.input, path("data/scene").string());
  EXPECT_EQ(edge_edge.kind, Kind::edge_edge);
  for (const InputReport* report : {&vertex_face, &edge_edge}) {
    EXPECT_EQ(report->queries, 2);
    EXPECT_EQ(report->hits, 1);
    EXPECT_EQ(report->positives, 1);
    EXPECT_EQ(report->false_negatives, 0);
    ASSERT_EQ(report->results.size(), 2u);
    EXPECT_TRUE(report->results[0].hit);
    EXPECT_FALSE(report->results[1].hit);
  }
  EXPECT_EQ(outcome.reports[2].input, path("data/vf/q.csv").string());
}

TEST_F(CliTest, SceneOnTheCommandLine) {
  write_scene(path("scene"));
  const auto objects = run_json({"--out", "results.txt", "scene"});
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].at("kind"), "vf");
  EXPECT_EQ(objects[1].at("kind"), "ee");
  const auto lines = lines_of(read_file(path("results.txt")));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("1,", 0), 0u);
  EXPECT_EQ(lines[1], "0,inf");
  EXPECT_EQ(lines[2].rfind("1,", 0), 0u);
  EXPECT_EQ(lines[3], "0,inf");
}

// ---- the user's words and the truth's labels ---------------------------------------

// A refused --min-distance or --tmax names the flag, never the library's field.
TEST_F(CliTest, RefusedOptionsNameTheFlagNotTheLibrarysField) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const CliRun negative = run_cli({"run", "--min-distance", "-1", "vf/q.csv"});
  EXPECT_EQ(negative.exit_code, 2);
  EXPECT_NE(negative.err.find("batchccd run: --min-distance must be >= 0 and finite, got -1"), std::string::npos)
      << negative.err;
  const CliRun late = run_cli({"run", "--tmax", "2", "vf/q.csv"});
  EXPECT_EQ(late.exit_code, 2);
  EXPECT_NE(late.err.find("batchccd run: --tmax must be in (0, 1], got 2"), std::string::npos) << late.err;
  for (const CliRun& run : {negative, late}) {
    EXPECT_EQ(run.err.find("Options::"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("Run 'batchccd run --help' for usage."), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty());
  }
}

// Truth labelled for touching (no ms.txt) and the whole step is not scored
// against a run with a separation or an earlier tmax: the counts are blank,
// the JSON says what the truth is labelled for, the table says why.
TEST_F(CliTest, TruthForAnotherSeparationOrTmaxIsNotScoredAndSaysWhy) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const auto scored = run_json({"vf/q.csv"});
  ASSERT_EQ(scored.size(), 1u);
  EXPECT_EQ(scored[0].at("false_negatives"), "0");
  EXPECT_EQ(scored[0].at("truth_min_distance"), "0.0");
  EXPECT_EQ(scored[0].at("truth_tmax"), "1.0");
  for (const std::vector<std::string>& other : {std::vector<std::string>{"--min-distance", "0.25", "vf/q.csv"},
                                                std::vector<std::string>{"--tmax", "0.75", "vf/q.csv"}}) {
    const auto objects = run_json(other);
    ASSERT_EQ(objects.size(), 1u) << other[0];
    for (const char* count : {"positives", "false_positives", "false_negatives"})
      EXPECT_EQ(objects[0].at(count), "null") << other[0] << " " << count;
    EXPECT_EQ(objects[0].at("truth_min_distance"), "0.0") << other[0];
    EXPECT_EQ(objects[0].at("truth_tmax"), "1.0") << other[0];
    EXPECT_EQ(objects[0].at("hits"), "1") << other[0];  // the run itself still counts
  }
  const CliRun table = run_cli({"run", "--min-distance", "0.25", "vf/q.csv"});
  EXPECT_EQ(table.exit_code, 0) << table.err;
  const auto lines = lines_of(table.out);
  ASSERT_GE(lines.size(), 5u) << table.out;
  EXPECT_EQ(lines[2].rfind("vf/q.csv", 0), 0u);
  EXPECT_NE(lines[2].find(" -  "), std::string::npos) << lines[2];
  EXPECT_NE(table.out.find("note: vf/q.csv (vf): truth labelled for min_distance 0, tmax 1; this run asked "
                           "min_distance 0.25, tmax 1: not scored"),
            std::string::npos)
      << table.out;
  // A scored run has no note.
  EXPECT_EQ(run_cli({"run", "vf/q.csv"}).out.find("note:"), std::string::npos);
}

// ms.txt states the separation a data set's truth is labelled for: without
// --min-distance the run takes it (each input its own), and scores the truth.
TEST_F(CliTest, StatedSeparationIsTheDefaultAndItsTruthIsScored) {
  write_file(path("far/vv/pass.csv"), point_query_csv({vertex_vertex_pass(true)}));  // a contact within 0.25
  write_file(path("far/vv/ms.txt"), " 0.3\n");
  write_file(path("touching/vv/pass.csv"), point_query_csv({vertex_vertex_pass(false)}));
  const auto objects = run_json({"far", "touching"});
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].at("min_distance"), "0.3");
  EXPECT_EQ(objects[0].at("truth_min_distance"), "0.3");
  EXPECT_EQ(objects[0].at("hits"), "1");
  EXPECT_EQ(objects[0].at("false_negatives"), "0");
  EXPECT_EQ(objects[1].at("min_distance"), "0.0");  // no ms.txt: touching
  EXPECT_EQ(objects[1].at("hits"), "0");
  EXPECT_EQ(objects[1].at("false_positives"), "0");
  // The table names each input's separation when they differ.
  const CliRun table = run_cli({"run", "far", "touching"});
  EXPECT_EQ(table.exit_code, 0) << table.err;
  const auto lines = lines_of(table.out);
  ASSERT_EQ(lines.size(), 5u) << table.out;
  EXPECT_NE(lines[0].find("min_distance per input"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("min_distance"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("  0.3  "), std::string::npos) << lines[2];
  // --min-distance overrides it, and that truth is then not scored.
  const auto overridden = run_json({"--min-distance", "0", "far"});
  EXPECT_EQ(overridden.at(0).at("hits"), "0");
  EXPECT_EQ(overridden.at(0).at("false_negatives"), "null");
  // A scene states it in its directory.
  write_scene(path("scene"));
  write_file(path("scene/ms.txt"), "0.001\n");
  for (const auto& object : run_json({"scene"})) EXPECT_EQ(object.at("min_distance"), "0.001");
}

TEST_F(CliTest, UnreadableStatedSeparationIsAnInputErrorNamingTheFile) {
  write_file(path("vv/pass.csv"), point_query_csv({vertex_vertex_pass(true)}));
  for (const char* bad : {"-1\n", "0.3 0.4\n", "wide\n", "", "inf\n"}) {
    write_file(path("vv/ms.txt"), bad);
    const CliRun result = run_cli({"run", "vv/pass.csv"});
    EXPECT_EQ(result.exit_code, 1) << bad;
    EXPECT_NE(result.err.find("ms.txt:1: must hold one separation, a number >= 0 and finite"), std::string::npos)
        << bad << "\n" << result.err;
  }
}

// --truth is labelled by whoever passes it for this run's separation and tmax.
TEST_F(CliTest, TruthFileIsScoredAtTheRunsOwnSeparation) {
  // Its truth column (labelled for touching) is replaced by --truth.
  write_file(path("vv/pass.csv"), point_query_csv({vertex_vertex_pass(false)}));
  write_file(path("truth.txt"), "1\n");
  const auto objects = run_json({"--min-distance", "0.3", "--truth", "truth.txt", "vv/pass.csv"});
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].at("truth_min_distance"), "0.3");
  EXPECT_EQ(objects[0].at("false_negatives"), "0");
}

// ---- formatting -------------------------------------------------------------------

// Paths are bytes: what is not UTF-8 becomes U+FFFD, the rest survives.
TEST(CliFormat, JsonLineEscapesAnyPath) {
  InputReport report;
  report.input = std::string("a\"b\\c\nd\x01 caf\xc3\xa9 bad\xff");
  const auto fields = parse_json_line(batchccd::cli::json_line(report));
  EXPECT_EQ(fields.at("input"), "a\"b\\c\nd\x01 caf\xc3\xa9 bad\xef\xbf\xbd");
}

TEST(CliFormat, ResultLinesRoundTrip) {
  using batchccd::cli::result_line;
  batchccd::QueryResult hit;
  hit.hit = true;
  hit.toi = 0.1;
  EXPECT_EQ(result_line(hit), "1,0.1");
  hit.toi = 1.0 / 3.0;
  EXPECT_EQ(std::stod(result_line(hit).substr(2)), 1.0 / 3.0);
  EXPECT_EQ(result_line(batchccd::QueryResult{}), "0,inf");
}

TEST(CliFormat, JsonLineWithoutTimeHasNoInfinity) {
  InputReport report;
  report.input = "x";
  const std::string line = batchccd::cli::json_line(report);
  EXPECT_EQ(line.find("inf"), std::string::npos) << line;
  EXPECT_EQ(parse_json_line(line).at("queries_per_second"), "0.0");
  EXPECT_EQ(parse_json_line(line).at("positives"), "null");
}

// ---- never losing work -----------------------------------------------------

// One report holding `hits` hits followed by `misses` misses.
InputReport report_of(int hits, int misses) {
  InputReport report;
  for (int i = 0; i < hits; ++i) report.results.push_back({true, 0.5, batchccd::Status::ok});
  for (int i = 0; i < misses; ++i) report.results.push_back({});
  return report;
}

TEST_F(CliTest, OutKeepsTheOldFileWhenTheNewOneCannotBeWritten) {
  const fs::path out = path("results.txt");
  write_file(out, "earlier results\n");
  // Occupy the temporary file's name with a directory: the write must fail
  // before anything touches results.txt.
  fs::path blocker = out;
  blocker += ".tmp-" + std::to_string(::getpid());
  fs::create_directories(blocker);
  EXPECT_THROW(batchccd::cli::write_results_file(out, {report_of(2, 1)}), std::runtime_error);
  EXPECT_EQ(read_file(out), "earlier results\n");
  fs::remove(blocker);
  batchccd::cli::write_results_file(out, {report_of(2, 1)});
  EXPECT_EQ(lines_of(read_file(out)).size(), 3u);
  EXPECT_TRUE(files_containing(".tmp-").empty());
}

TEST_F(CliTest, OutOntoADirectoryFailsAndLeavesItAlone) {
  const fs::path out = path("results");
  write_file(out / "inside.txt", "keep\n");
  EXPECT_THROW(batchccd::cli::write_results_file(out, {report_of(1, 1)}), std::runtime_error);
  EXPECT_EQ(read_file(out / "inside.txt"), "keep\n");
  EXPECT_TRUE(files_containing(".tmp-").empty());
}

// A scene with an out-of-range candidate between two good query files: the
// scene is reported, the good files' results are all written, in order.
TEST_F(CliTest, BadSceneAmongGoodInputsCostsOnlyItsOwnResults) {
  write_file(path("vf/good.csv"),
             query_csv({{vertex_face_hit, true}, {vertex_face_miss, false}, {vertex_face_hit, true}}));
  write_file(path("ee/good.csv"), query_csv({{edge_edge_miss, false}, {edge_edge_hit, true}}));
  test_support::write_scene_with_an_out_of_range_candidate(path("scene"));
  write_file(path("results.txt"), "earlier results\n");
  const CliRun result =
      run_cli({"run", "--json", "--out", "results.txt", "vf/good.csv", "scene", "ee/good.csv"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("ee.csv:2"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("out of range"), std::string::npos) << result.err;
  EXPECT_EQ(lines_of(result.out).size(), 2u);  // one JSON line per good file
  const std::string results = read_file(path("results.txt"));
  EXPECT_EQ(lines_of(results).size(), 5u) << results;
  EXPECT_EQ(results.rfind("1,", 0), 0u) << results;  // the first query of vf/good.csv hits
  EXPECT_TRUE(files_containing(".tmp-").empty());
}

// In process: every error is told, every good input keeps its report.
TEST_F(CliTest, EveryBadInputIsToldAndEveryGoodOneReported) {
  write_file(path("vf/good.csv"), query_csv({{vertex_face_hit, true}}));
  write_file(path("vf/short.csv"), "1,1,2,1,3,1\n");  // 1 of 8 rows
  write_file(path("vf/not-double.csv"), query_csv({{vertex_face_miss, false}}).replace(0, 4, "1,3,"));
  write_file(path("ee/good.csv"), query_csv({{edge_edge_hit, true}, {edge_edge_miss, false}}));
  RunSettings settings;
  settings.inputs = {path("vf/good.csv"), path("vf/short.csv"), path("missing/vf.csv"),
                     path("vf/not-double.csv"), path("ee/good.csv")};
  settings.keep_results = true;
  std::ostringstream errors;
  const RunOutcome outcome = batchccd::cli::run_inputs(settings, errors);
  EXPECT_TRUE(outcome.any_error);
  ASSERT_EQ(outcome.reports.size(), 2u);
  EXPECT_EQ(outcome.reports[0].results.size(), 1u);
  EXPECT_EQ(outcome.reports[1].results.size(), 2u);
  for (const char* bad : {"short.csv", "missing", "not-double.csv"})
    EXPECT_NE(errors.str().find(bad), std::string::npos) << errors.str();
}

// ---- the shared data set ----------------------------------------------------------

// The minimum-separation set (its README says how it is labelled): the tool
// with --min-distance misses no contact in the certified modes.
TEST_F(CliTest, SharedMinDistanceSetHasNoFalseNegatives) {
  const fs::path data = batchccd::testing::kSharedData / "min-distance" / "unit-ms1e-3";
  if (!fs::exists(data / "vf.csv") || !fs::exists(data / "ee.csv")) {
    GTEST_SKIP() << "no shared data at " << data;
  }
  // The separation the truth is labelled for.
  std::ifstream ms_file(data / "ms.txt");
  double min_distance = -1;
  ms_file >> min_distance;
  ASSERT_EQ(min_distance, 0.001);
  for (const char* mode : {"conservative", "exact"}) {
    const auto objects = run_json({"--mode", mode, "--min-distance", "1e-3", data.string()});
    ASSERT_EQ(objects.size(), 2u) << mode;
    std::int64_t queries = 0;
    for (const auto& object : objects) {
      EXPECT_EQ(object.at("min_distance"), "0.001") << mode;
      EXPECT_EQ(object.at("false_negatives"), "0") << mode << " " << object.at("input");
      EXPECT_NE(object.at("positives"), "0") << object.at("input");
      queries += std::stoll(object.at("queries"));
    }
    EXPECT_EQ(queries, 250 + 74) << mode;  // the README's counts
  }
  // Touching alone finds all but the contacts the separation adds (README: 18 + 15).
  std::int64_t positives = 0, touching = 0;
  for (const auto& object : run_json({"--mode", "exact", data.string()})) positives += std::stoll(object.at("positives"));
  for (const auto& object : run_json({"--mode", "exact", "--min-distance", "0", data.string()}))
    touching += std::stoll(object.at("hits"));
  EXPECT_EQ(positives - touching, 18 + 15);
}

// The shared data, run as a new user would: the minimum-separation set at
// its stated separation without being told, and a touching scene never
// scored at a separation it was not labelled for.
TEST_F(CliTest, SharedDataIsScoredOnlyAtItsLabelledSeparation) {
  const fs::path& data = batchccd::testing::kSharedData;
  const fs::path set = data / "min-distance" / "unit-ms1e-3", scene = data / "scenes" / "cloth-funnel-227";
  if (!fs::exists(set / "ms.txt") || !fs::exists(scene / "vf_truth.txt")) GTEST_SKIP() << "no shared data at " << data;
  for (const char* mode : {"conservative", "exact"}) {
    for (const auto& object : run_json({"--mode", mode, set.string()})) {
      EXPECT_EQ(object.at("min_distance"), "0.001") << mode;
      EXPECT_EQ(object.at("false_negatives"), "0") << mode << " " << object.at("input");
    }
  }
  for (const auto& object : run_json({"--mode", "exact", "--min-distance", "1e-3", scene.string()})) {
    EXPECT_EQ(object.at("truth_min_distance"), "0.0");
    EXPECT_EQ(object.at("false_negatives"), "null") << object.at("kind");
    EXPECT_EQ(object.at("false_positives"), "null") << object.at("kind");
  }
}

// The tool's own path over the reference data (the library's is tested in
// test_shared_data.cpp): every file found, read and counted against its truth.
TEST(CliSharedData, SampleQueriesAndScenesRunWithTruth) {
  const fs::path& data = batchccd::testing::kSharedData;
  if (!batchccd::testing::shared_data_present()) GTEST_SKIP() << "no shared data at " << data;
  const std::size_t query_files = batchccd::testing::shared_query_files().size();
  const std::size_t scenes = batchccd::testing::shared_scene_directories().size();
  ASSERT_GT(query_files, 0u);
  ASSERT_GT(scenes, 0u);

  RunSettings settings;
  settings.inputs = {data / "sample-queries", data / "scenes"};
  std::ostringstream errors;
  const RunOutcome outcome = batchccd::cli::run_inputs(settings, errors);
  EXPECT_FALSE(outcome.any_error) << errors.str();
  EXPECT_EQ(outcome.reports.size(), query_files + 2 * scenes);
  for (const InputReport& report : outcome.reports) {
    ASSERT_TRUE(report.false_negatives.has_value()) << report.input;
    // Conservative mode never misses a contact.
    EXPECT_EQ(*report.false_negatives, 0) << report.input;
  }
}

}  // namespace

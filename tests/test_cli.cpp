// The command-line tool: argument handling and exit codes through the built
// executable, the rest in process through run_inputs (the same code path).

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "compare.hpp"
#include "demo.hpp"
#include "report_format.hpp"
#include "run.hpp"

namespace {

namespace fs = std::filesystem;
using batchccd::Kind;
using batchccd::cli::InputReport;
using batchccd::cli::RunOutcome;
using batchccd::cli::RunSettings;

// ---- query files ----------------------------------------------------------

// A point in quarters: (x, y, z) / 4, so 0.25 is 1.
struct QuarterPoint {
  int x, y, z;
};
using QueryPoints = std::array<QuarterPoint, 8>;

// The vertex falls through the static triangle (0,0,0), (1,0,0), (0,1,0) at t = 1/2.
constexpr QueryPoints vertex_face_hit{{{1, 1, 4}, {0, 0, 0}, {4, 0, 0}, {0, 4, 0},
                                       {1, 1, -4}, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}}};
// The vertex stays far from the triangle.
constexpr QueryPoints vertex_face_miss{{{40, 40, 40}, {0, 0, 0}, {4, 0, 0}, {0, 4, 0},
                                        {40, 40, 40}, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}}};
// Edge a sweeps down through the static edge b on the x axis at t = 1/2.
constexpr QueryPoints edge_edge_hit{{{2, -4, 4}, {2, 4, 4}, {0, 0, 0}, {4, 0, 0},
                                     {2, -4, -4}, {2, 4, -4}, {0, 0, 0}, {4, 0, 0}}};
// Edge a stays far above edge b.
constexpr QueryPoints edge_edge_miss{{{2, -4, 40}, {2, 4, 40}, {0, 0, 0}, {4, 0, 0},
                                      {2, -4, 40}, {2, 4, 40}, {0, 0, 0}, {4, 0, 0}}};

struct TestQuery {
  QueryPoints points;
  bool truth;
};

// 7 columns with truth, 6 without.
std::string query_csv(const std::vector<TestQuery>& queries, bool with_truth = true) {
  std::ostringstream text;
  for (const TestQuery& query : queries) {
    for (const QuarterPoint& point : query.points) {
      text << point.x << ",4," << point.y << ",4," << point.z << ",4";
      if (with_truth) text << ',' << (query.truth ? 1 : 0);
      text << '\n';
    }
  }
  return text.str();
}

const std::string vertex_face_hit_and_miss =
    query_csv({{vertex_face_hit, true}, {vertex_face_miss, false}});
const std::string edge_edge_hit_and_miss =
    query_csv({{edge_edge_hit, true}, {edge_edge_miss, false}});

void write_file(const fs::path& path, const std::string& content) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << content;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A small scene: triangle 0-1-2 with vertex 3 falling through it; edge 4-5
// sweeping down through edge 0-1; vertices 6, 7 far away and still.
void write_scene(const fs::path& directory) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string fixed_vertices = "0 0 0\n1 0 0\n0 1 0\n";
  const std::string far_vertices = "10 10 10\n11 10 10\n";
  write_file(directory / "t0.ply", header + fixed_vertices + "0.25 0.25 1\n0.5 -1 1\n0.5 1 1\n" +
                                       far_vertices + "3 0 1 2\n");
  write_file(directory / "t1.ply", header + fixed_vertices +
                                       "0.25 0.25 -1\n0.5 -1 -1\n0.5 1 -1\n" + far_vertices +
                                       "3 0 1 2\n");
  write_file(directory / "vf.csv", "3,0\n6,0\n");
  write_file(directory / "vf_truth.txt", "1\n0\n");
  write_file(directory / "ee.csv", "4,5,0,1\n4,5,6,7\n");
  write_file(directory / "ee_truth.txt", "1\n0\n");
  // A scene's own query file belongs to the scene, not to a directory search.
  write_file(directory / "queries_vf.csv", vertex_face_hit_and_miss);
}

// ---- a minimal JSON reader for flat objects --------------------------------

// Parses one JSON object whose values are strings, numbers, true, false or
// null; returns nullopt on any syntax error. Values keep their JSON text,
// except strings, which are unescaped (\u escapes as "?").
class FlatJsonReader {
 public:
  explicit FlatJsonReader(std::string_view text) : text_(text) {}

  std::optional<std::map<std::string, std::string>> object() {
    std::map<std::string, std::string> fields;
    if (!consume('{')) return std::nullopt;
    if (consume('}')) return finish(fields);
    do {
      auto name = string();
      if (!name || !consume(':')) return std::nullopt;
      auto value = scalar();
      if (!value || fields.count(*name) != 0) return std::nullopt;
      fields[*name] = *value;
    } while (consume(','));
    if (!consume('}')) return std::nullopt;
    return finish(fields);
  }

 private:
  std::optional<std::map<std::string, std::string>> finish(
      std::map<std::string, std::string> fields) {
    skip_space();
    if (at_ != text_.size()) return std::nullopt;
    return fields;
  }

  void skip_space() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }

  bool consume(char expected) {
    skip_space();
    if (at_ < text_.size() && text_[at_] == expected) {
      ++at_;
      return true;
    }
    return false;
  }

  std::optional<std::string> string() {
    if (!consume('"')) return std::nullopt;
    std::string value;
    while (at_ < text_.size() && text_[at_] != '"') {
      const char character = text_[at_++];
      if (static_cast<unsigned char>(character) < 0x20) return std::nullopt;
      if (character != '\\') {
        value += character;
        continue;
      }
      if (at_ >= text_.size()) return std::nullopt;
      const char escape = text_[at_++];
      if (escape == 'u') {
        for (int digit = 0; digit < 4; ++digit, ++at_) {
          if (at_ >= text_.size() || !std::isxdigit(static_cast<unsigned char>(text_[at_])))
            return std::nullopt;
        }
        value += '?';
      } else if (std::string_view("\"\\/bfnrt").find(escape) != std::string_view::npos) {
        value += escape == 'n' ? '\n' : escape == 't' ? '\t' : escape;
      } else {
        return std::nullopt;
      }
    }
    if (at_ >= text_.size()) return std::nullopt;
    ++at_;
    return value;
  }

  std::optional<std::string> scalar() {
    skip_space();
    if (at_ < text_.size() && text_[at_] == '"') return string();
    for (std::string_view word : {"true", "false", "null"}) {
      if (text_.substr(at_, word.size()) == word) {
        at_ += word.size();
        return std::string(word);
      }
    }
    return number();
  }

  // -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
  std::optional<std::string> number() {
    const std::size_t start = at_;
    const auto digits = [&] {
      const std::size_t first = at_;
      while (at_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_]))) ++at_;
      return at_ > first;
    };
    if (at_ < text_.size() && text_[at_] == '-') ++at_;
    if (at_ < text_.size() && text_[at_] == '0') {
      ++at_;
    } else if (!digits()) {
      return std::nullopt;
    }
    if (at_ < text_.size() && text_[at_] == '.') {
      ++at_;
      if (!digits()) return std::nullopt;
    }
    if (at_ < text_.size() && (text_[at_] == 'e' || text_[at_] == 'E')) {
      ++at_;
      if (at_ < text_.size() && (text_[at_] == '+' || text_[at_] == '-')) ++at_;
      if (!digits()) return std::nullopt;
    }
    return std::string(text_.substr(start, at_ - start));
  }

  std::string_view text_;
  std::size_t at_ = 0;
};

std::map<std::string, std::string> parse_json_line(const std::string& line) {
  auto fields = FlatJsonReader(line).object();
  EXPECT_TRUE(fields.has_value()) << "not a JSON object: " << line;
  return fields.value_or(std::map<std::string, std::string>{});
}

const std::vector<std::string> json_field_names = {
    "input",     "kind",           "mode",           "isa",
    "threads",   "queries",        "hits",           "positives",
    "false_positives", "false_negatives", "culled", "seconds",
    "queries_per_second", "exact_escalations", "max_query_seconds"};

// ---- running the executable -------------------------------------------------

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char character : text) quoted += character == '\'' ? std::string("'\\''") : std::string(1, character);
  return quoted + "'";
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    temporary_ = fs::temp_directory_path() /
                 ("batchccd_cli_" + std::string(test->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(temporary_);
    fs::create_directories(temporary_);
  }
  void TearDown() override { fs::remove_all(temporary_); }

  fs::path path(const std::string& relative) const { return temporary_ / relative; }

  // Runs `batchccd ARGUMENTS` in the temporary directory.
  CliRun run_cli(const std::vector<std::string>& arguments) const {
    std::vector<std::string> words = {"cd", shell_quoted(temporary_.string()), "&&",
                                      shell_quoted(BATCHCCD_CLI_PATH)};
    for (const std::string& argument : arguments) words.push_back(shell_quoted(argument));
    words.insert(words.end(), {">", shell_quoted((temporary_ / "stdout.txt").string()), "2>",
                               shell_quoted((temporary_ / "stderr.txt").string())});
    std::string command;
    for (const std::string& word : words) (command += word) += ' ';
    const int status = std::system(command.c_str());
    CliRun result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read_file(temporary_ / "stdout.txt");
    result.err = read_file(temporary_ / "stderr.txt");
    fs::remove(temporary_ / "stdout.txt");
    fs::remove(temporary_ / "stderr.txt");
    return result;
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
    for (const auto& entry : fs::recursive_directory_iterator(temporary_)) {
      if (entry.path().filename().string().find(fragment) != std::string::npos)
        found.push_back(entry.path());
    }
    return found;
  }

  fs::path temporary_;
};

// ---- command line -----------------------------------------------------------

TEST_F(CliTest, NoArgumentsPrintsUsageAndExitsTwo) {
  const CliRun result = run_cli({});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("usage:"), std::string::npos);
  EXPECT_TRUE(result.out.empty());
}

TEST_F(CliTest, HelpDocumentsEveryOption) {
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"--help"}, std::vector<std::string>{"run", "--help"}}) {
    const CliRun result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, 0);
    for (const char* option : {"--kind", "--truth", "--mode", "--threads", "--isa", "--json",
                               "--out", "conservative", "fast", "cubic", "exact", "avx512",
                               "INPUT", "exact_escalations", "max_query_seconds"}) {
      EXPECT_NE(result.out.find(option), std::string::npos) << arguments.front() << ": " << option;
    }
  }
}

TEST_F(CliTest, BadCommandLinesExitTwoWithUsage) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  const std::vector<std::vector<std::string>> bad_command_lines = {
      {"frobnicate"},
      {"run"},
      {"run", "--json"},
      {"run", "--bogus", "vf/q.csv"},
      {"run", "--mode", "exactly", "vf/q.csv"},
      {"run", "--mode=sloppy", "vf/q.csv"},
      {"run", "vf/q.csv", "--mode"},
      {"run", "--threads", "0", "vf/q.csv"},
      {"run", "--threads", "-2", "vf/q.csv"},
      {"run", "--threads", "two", "vf/q.csv"},
      {"run", "--threads", "3x", "vf/q.csv"},
      {"run", "--isa", "neon", "vf/q.csv"},
      {"run", "--kind", "xy", "vf/q.csv"},
      {"run", "--json=yes", "vf/q.csv"},
      {"run", "--truth", "t.txt", "vf/q.csv", "vf/q.csv"},
  };
  for (const auto& arguments : bad_command_lines) {
    const CliRun result = run_cli(arguments);
    std::string shown;
    for (const auto& argument : arguments) shown += argument + " ";
    EXPECT_EQ(result.exit_code, 2) << shown;
    EXPECT_NE(result.err.find("usage:"), std::string::npos) << shown;
    EXPECT_TRUE(result.out.empty()) << shown;
  }
}

TEST_F(CliTest, AcceptsEveryDocumentedOptionForm) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"run", "--mode", "fast", "--threads", "2", "vf/q.csv"},
        std::vector<std::string>{"run", "--mode=cubic", "--isa=scalar", "vf/q.csv"},
        std::vector<std::string>{"run", "--mode", "exact", "vf/q.csv"},
        std::vector<std::string>{"run", "--isa", "auto", "--kind", "vf", "--", "vf/q.csv"}}) {
    const CliRun result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, 0) << result.err;
  }
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
  for (const char* mode : {"conservative", "fast", "cubic", "exact"}) {
    const auto objects = run_json({"--mode", mode, "vertex-face/q.csv"});
    ASSERT_EQ(objects.size(), 1u) << mode;
    const auto& object = objects.front();
    EXPECT_EQ(object.at("mode"), mode);
    EXPECT_EQ(object.at("false_positives"), "0") << mode;
    EXPECT_EQ(object.at("false_negatives"), "0") << mode;
    const double slowest = std::stod(object.at("max_query_seconds"));
    EXPECT_GE(slowest, 0.0) << mode;
    EXPECT_LE(slowest, std::stod(object.at("seconds"))) << mode;
    // Only the certified modes use exact arithmetic (here at most for the
    // hit's TOI).
    if (std::string(mode) == "exact" || std::string(mode) == "conservative") {
      EXPECT_LE(std::stoi(object.at("exact_escalations")), 1);
    } else {
      EXPECT_EQ(object.at("exact_escalations"), "0") << mode;
    }
  }
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

// An instruction set this build lacks is refused, never silently replaced.
TEST_F(CliTest, UnavailableInstructionSetIsAnError) {
  write_file(path("vf/good.csv"), vertex_face_hit_and_miss);
  const auto isas = batchccd::available_isas();
  if (std::find(isas.begin(), isas.end(), batchccd::Isa::avx2) != isas.end())
    GTEST_SKIP() << "avx2 kernels are available";
  const CliRun result = run_cli({"run", "--isa", "avx2", "vf/good.csv"});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("avx2"), std::string::npos) << result.err;
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

// ---- formatting -------------------------------------------------------------------

TEST(CliFormat, JsonStringsAreEscaped) {
  using batchccd::cli::json_string;
  EXPECT_EQ(json_string("plain"), "\"plain\"");
  EXPECT_EQ(json_string("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json_string("line\nbreak\ttab"), "\"line\\nbreak\\ttab\"");
  EXPECT_EQ(json_string(std::string("\x01", 1)), "\"\\u0001\"");
  EXPECT_EQ(json_string("caf\xc3\xa9"), "\"caf\xc3\xa9\"");   // valid UTF-8 kept
  EXPECT_EQ(json_string("bad\xff"), "\"bad\\ufffd\"");        // invalid byte replaced
  EXPECT_EQ(json_string("\xc3"), "\"\\ufffd\"");              // truncated sequence
  EXPECT_EQ(json_string("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // a surrogate
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
  EXPECT_EQ(FlatJsonReader(line).object()->at("queries_per_second"), "0");
}

// ---- demo and report --------------------------------------------------------------

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
  for (const auto method : batchccd::cli::compared_methods())
    names.emplace_back(batchccd::cli::name_of(method));
  return names;
}

TEST(CliCompare, TallyCountsErrorsAgainstTruthAndToiAgainstTheReference) {
  using batchccd::QueryResult;
  batchccd::cli::MethodRun run;
  run.results = {{true, 0.5}, {false}, {true, 0.25}, {true, 0.0}};
  run.seconds = 2;
  run.culled = 1;
  const std::vector<bool> truth = {true, true, true, false};
  const std::vector<QueryResult> reference = {{true, 0.5}, {true, 0.1}, {true, 0.3}, {false}};
  batchccd::cli::MethodTally tally;
  tally.add(run, truth, reference);
  EXPECT_EQ(tally.candidates, 4);
  EXPECT_EQ(tally.false_negatives, 1);
  EXPECT_EQ(tally.false_positives, 1);
  EXPECT_EQ(tally.toi_compared, 2);
  EXPECT_DOUBLE_EQ(tally.toi_error_max, 0.05);
  EXPECT_DOUBLE_EQ(tally.toi_error_mean(), 0.025);
  EXPECT_DOUBLE_EQ(tally.candidates_per_second(), 2);
  EXPECT_DOUBLE_EQ(tally.cull_ratio(), 0.25);
  batchccd::cli::MethodTally twice = tally;
  twice += tally;
  EXPECT_EQ(twice.false_negatives, 2);
  EXPECT_DOUBLE_EQ(twice.toi_error_max, 0.05);
  EXPECT_DOUBLE_EQ(twice.toi_error_mean(), 0.025);
  EXPECT_THROW(tally.add(run, {true}, reference), std::logic_error);
}

TEST_F(CliTest, ReportComparesEveryMethodAgainstTheFilesTruth) {
  write_scene(path("data/scene"));
  write_file(path("data/vf/q.csv"), vertex_face_hit_and_miss);
  write_file(path("data/ee/q.csv"), edge_edge_hit_and_miss);
  const CliRun result = run_cli({"report", "--threads", "2", "--out", "out", "data"});
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
  const std::string svg = read_file(path("out/plot.svg"));
  EXPECT_NE(svg.find("run time"), std::string::npos);
  for (const std::string& method : method_names()) EXPECT_NE(svg.find(">" + method + "<"), std::string::npos);
}

TEST_F(CliTest, ReportGoesOnPastABadInputAndSaysSo) {
  write_file(path("vf/q.csv"), vertex_face_hit_and_miss);
  write_file(path("vf/bad.csv"), "1,1,2\n");
  const CliRun result = run_cli({"report", "vf/bad.csv", "missing", "vf/q.csv"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("bad.csv:1"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("missing"), std::string::npos) << result.err;
  EXPECT_NE(result.out.find("1 inputs, 2 candidates"), std::string::npos) << result.out;
}

TEST_F(CliTest, DemoAndReportCommandLines) {
  for (const auto& arguments : std::vector<std::vector<std::string>>{
           {"demo", "--scene", "sphere"}, {"demo", "--resolution", "0"}, {"demo", "extra"},
           {"demo", "--methods-only=yes"}, {"report"}, {"report", "--threads", "x", "a"},
           {"report", "--bogus", "a"}}) {
    const CliRun result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, 2) << arguments[1];
    EXPECT_NE(result.err.find("usage: batchccd " + arguments[0]), std::string::npos) << result.err;
  }
  for (const std::string command : {"demo", "report"}) {
    const CliRun help = run_cli({command, "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("usage: batchccd " + command), std::string::npos);
    EXPECT_NE(help.out.find("--threads"), std::string::npos);
  }
}

// A small cloth: every method runs, exact mode is the truth, and the
// certified mode misses nothing.
TEST_F(CliTest, DemoPrintsTheTableAndWritesReportCsvAndPlot) {
  const CliRun result = run_cli({"demo", "--resolution", "24", "--threads", "2", "--out", "out"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << "progress must stay off a non-terminal: " << result.err;
  for (const char* section : {"candidates/s", "What a call pays for", "Stiff and extreme"})
    EXPECT_NE(result.out.find(section), std::string::npos) << section;
  EXPECT_EQ(read_file(path("out/report.txt")) + "wrote out/report.txt, out/methods.csv, out/plot.svg\n",
            result.out);
  const auto rows = read_csv(path("out/methods.csv"));
  ASSERT_EQ(rows.size(), method_names().size());
  std::map<std::string, std::map<std::string, std::string>> by_method;
  for (const auto& row : rows) by_method[row.at("method")] = row;
  EXPECT_EQ(by_method.at("exact").at("false_negatives"), "0");
  EXPECT_EQ(by_method.at("exact").at("false_positives"), "0");
  EXPECT_EQ(by_method.at("exact").at("toi_error_max"), "0");
  EXPECT_EQ(by_method.at("conservative").at("false_negatives"), "0");
  EXPECT_GT(std::stod(by_method.at("conservative").at("cull_ratio")), 0.9);
  EXPECT_EQ(by_method.at("cubic").at("culled"), "0");
  // The scene has contacts: TOIs were compared.
  EXPECT_GT(std::stol(by_method.at("conservative").at("toi_compared")), 0);
  EXPECT_NE(read_file(path("out/plot.svg")).find("</svg>"), std::string::npos);
}

TEST_F(CliTest, DemoIntoAnUnwritableDirectoryIsAnErrorAfterTheReport) {
  write_file(path("blocker"), "a file where the directory should go");
  const CliRun result =
      run_cli({"demo", "--scene", "rigid", "--resolution", "2", "--methods-only", "--out", "blocker/out"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.out.find("candidates/s"), std::string::npos);  // the report came first
  EXPECT_NE(result.err.find("blocker"), std::string::npos) << result.err;
}

// ---- the shared data set ----------------------------------------------------------

TEST(CliSharedData, SampleQueriesAndScenesRunWithTruth) {
  const fs::path data = BATCHCCD_SHARED_DATA;
  if (!fs::exists(data / "sample-queries") || !fs::exists(data / "scenes")) {
    GTEST_SKIP() << "no shared data at " << data;
  }
  std::size_t query_files = 0, scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(data / "sample-queries"))
    query_files += entry.path().extension() == ".csv" ? 1 : 0;
  for (const auto& entry : fs::directory_iterator(data / "scenes"))
    scenes += batchccd::is_scene_directory(entry.path()) ? 1 : 0;

  RunSettings settings;
  settings.inputs = {data / "sample-queries", data / "scenes"};
  std::ostringstream errors;
  const RunOutcome outcome = batchccd::cli::run_inputs(settings, errors);
  EXPECT_FALSE(outcome.any_error) << errors.str();
  EXPECT_EQ(outcome.reports.size(), query_files + 2 * scenes);
  for (const InputReport& report : outcome.reports) {
    ASSERT_TRUE(report.false_negatives.has_value()) << report.input;
    // Conservative mode never misses a contact (docs/design.md §7).
    EXPECT_EQ(*report.false_negatives, 0) << report.input;
  }
}

}  // namespace

#pragma once

// Running a built program from a test, in a temporary directory of its own:
// what the tool's tests (test_cli.cpp) and the report's (test_report.cpp)
// share.
#include <array>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "temporary_directory.hpp"

namespace program_test {

namespace fs = std::filesystem;

using test_support::read_file;
using test_support::write_file;

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Query files both programs read: hits and misses in quarters, with truth.

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
inline std::string query_csv(const std::vector<TestQuery>& queries, bool with_truth = true) {
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

inline const std::string vertex_face_hit_and_miss =
    query_csv({{vertex_face_hit, true}, {vertex_face_miss, false}});
inline const std::string edge_edge_hit_and_miss =
    query_csv({{edge_edge_hit, true}, {edge_edge_miss, false}});

// A small scene: triangle 0-1-2 with vertex 3 falling through it; edge 4-5
// sweeping down through edge 0-1; vertices 6, 7 far away and still.
inline void write_small_scene(const fs::path& directory) {
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
}

inline std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char character : text) quoted += character == '\'' ? std::string("'\\''") : std::string(1, character);
  return quoted + "'";
}

struct ProgramRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// A fixture with a fresh temporary directory per test, where programs run.
class ProgramTest : public test_support::TemporaryDirectoryTest {
 protected:
  // Runs `PROGRAM ARGUMENTS` in the temporary directory, with `environment`
  // ("NAME=value" words) added to its environment.
  ProgramRun run(const std::string& program, const std::vector<std::string>& arguments,
                 const std::vector<std::string>& environment = {}) const {
    std::vector<std::string> words = {"cd", shell_quoted(directory().string()), "&&", "env"};
    for (const std::string& setting : environment) words.push_back(shell_quoted(setting));
    words.push_back(shell_quoted(program));
    for (const std::string& argument : arguments) words.push_back(shell_quoted(argument));
    words.insert(words.end(), {">", shell_quoted((directory() / "stdout.txt").string()), "2>",
                               shell_quoted((directory() / "stderr.txt").string())});
    std::string command;
    for (const std::string& word : words) (command += word) += ' ';
    const int status = std::system(command.c_str());
    ProgramRun result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read_file(directory() / "stdout.txt");
    result.err = read_file(directory() / "stderr.txt");
    fs::remove(directory() / "stdout.txt");
    fs::remove(directory() / "stderr.txt");
    return result;
  }
};

}  // namespace program_test

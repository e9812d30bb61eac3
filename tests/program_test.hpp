#pragma once

// Running a built program from a test, in a temporary directory of its own:
// what the tool's tests (test_cli.cpp) and the report's (test_report.cpp)
// share.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace program_test {

namespace fs = std::filesystem;

inline void write_file(const fs::path& path, const std::string& content) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << content;
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
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

// A fixture with a fresh temporary directory per test.
class ProgramTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    temporary_ = fs::temp_directory_path() / ("batchccd_" + std::string(test->test_suite_name()) + "_" +
                                              std::string(test->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(temporary_);
    fs::create_directories(temporary_);
  }
  void TearDown() override { fs::remove_all(temporary_); }

  fs::path path(const std::string& relative) const { return temporary_ / relative; }

  // Runs `PROGRAM ARGUMENTS` in the temporary directory, with `environment`
  // ("NAME=value" words) added to its environment.
  ProgramRun run(const std::string& program, const std::vector<std::string>& arguments,
                 const std::vector<std::string>& environment = {}) const {
    std::vector<std::string> words = {"cd", shell_quoted(temporary_.string()), "&&", "env"};
    for (const std::string& setting : environment) words.push_back(shell_quoted(setting));
    words.push_back(shell_quoted(program));
    for (const std::string& argument : arguments) words.push_back(shell_quoted(argument));
    words.insert(words.end(), {">", shell_quoted((temporary_ / "stdout.txt").string()), "2>",
                               shell_quoted((temporary_ / "stderr.txt").string())});
    std::string command;
    for (const std::string& word : words) (command += word) += ' ';
    const int status = std::system(command.c_str());
    ProgramRun result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read_file(temporary_ / "stdout.txt");
    result.err = read_file(temporary_ / "stderr.txt");
    fs::remove(temporary_ / "stdout.txt");
    fs::remove(temporary_ / "stderr.txt");
    return result;
  }

  fs::path temporary_;
};

}  // namespace program_test

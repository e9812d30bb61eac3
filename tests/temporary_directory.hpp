#pragma once

// Files in a fresh temporary directory per test, for the tests that read
// or write files: the library's readers, the tool's and the report's runs.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include <unistd.h>

#include <gtest/gtest.h>

namespace test_support {

namespace fs = std::filesystem;

// Writes `content` to `path` as it is (binary), creating its directories.
inline void write_file(const fs::path& path, const std::string& content) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << content;
}

// A one-triangle scene whose second edge-edge candidate names vertex 7 of
// 3: read_scene refuses it at line 2 of ee.csv.
inline void write_scene_with_an_out_of_range_candidate(const fs::path& scene) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  write_file(scene / "t0.ply", ply);
  write_file(scene / "t1.ply", ply);
  write_file(scene / "vf.csv", "0,0\n");
  write_file(scene / "ee.csv", "0,1,1,2\n0,1,2,7\n");
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// An empty directory named after the running test and the process (ctest
// runs tests in parallel processes), removed with everything in it when it
// goes out of scope.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("batchccd_" + std::string(test->test_suite_name()) + "_" +
                                         std::string(test->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A fixture with a TemporaryDirectory: path("a/b.csv") lies in it.
class TemporaryDirectoryTest : public ::testing::Test {
 protected:
  const fs::path& directory() const { return directory_.path(); }
  fs::path path(const std::string& relative) const { return directory() / relative; }
  // Writes a file into the directory; returns its path.
  fs::path write(const std::string& relative, const std::string& content) const {
    write_file(path(relative), content);
    return path(relative);
  }

 private:
  TemporaryDirectory directory_;
};

}  // namespace test_support

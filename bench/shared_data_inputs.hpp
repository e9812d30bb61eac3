#pragma once

#include <algorithm>
#include <filesystem>
#include <vector>

#include "batchccd/io.hpp"

namespace batchccd::scenes {

// What a benchmark runs over in ../shared/data (or another copy of it): the
// query files under sample-queries/ whose path names their kind, and the
// scene directories under scenes/, each list sorted; empty where absent.
struct SharedDataInputs {
  std::vector<std::filesystem::path> query_files;
  std::vector<std::filesystem::path> scenes;
};

inline SharedDataInputs shared_data_inputs(const std::filesystem::path& data) {
  namespace fs = std::filesystem;
  SharedDataInputs inputs;
  if (fs::is_directory(data / "sample-queries"))
    for (const auto& entry : fs::recursive_directory_iterator(data / "sample-queries"))
      if (entry.path().extension() == ".csv" && kind_from_path(entry.path())) inputs.query_files.push_back(entry.path());
  if (fs::is_directory(data / "scenes"))
    for (const auto& entry : fs::directory_iterator(data / "scenes"))
      if (is_scene_directory(entry.path())) inputs.scenes.push_back(entry.path());
  std::sort(inputs.query_files.begin(), inputs.query_files.end());
  std::sort(inputs.scenes.begin(), inputs.scenes.end());
  return inputs;
}

}  // namespace batchccd::scenes

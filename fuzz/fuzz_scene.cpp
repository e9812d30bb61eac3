// libFuzzer target: read_scene, on a scene directory whose ten files the
// input writes. Its answer is held to the one the single-file readers
// (fuzzed on their own by the ply, pairs and truth targets) and io.hpp's
// rules give: the meshes and lists as those readers read them, absent lists
// empty and absent truths none; or an InputError naming the first bad file
// and line, with the reader's own message for a malformed file, and for an
// id out of range or a length that does not match, that file and row.
//
// Bytes: a presence byte (bit i: the i-th file after t1.ply is there; t0.ply
// and t1.ply always are), then the files' contents in the order of kFiles,
// each ended by kSeparator (the last may end with the input; files past the
// input's end are empty).
//
// The directory (in the temporary directory, one a process) holds symbolic
// links to in-memory files rewritten for every input (fuzz_input_file.hpp
// says why); links of absent files are removed.

#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "batchccd/io.hpp"
#include "fuzz_check.hpp"

namespace {

namespace fs = std::filesystem;
using batchccd::fuzz::require;

constexpr std::array<const char*, 10> kFiles = {"t0.ply",   "t1.ply",       "vf.csv",       "ee.csv",
                                                "ve.csv",   "vv.csv",       "vf_truth.txt", "ee_truth.txt",
                                                "ve_truth.txt", "vv_truth.txt"};
enum FileIndex { t0, t1, vf, ee, ve, vv, vf_truth, ee_truth, ve_truth, vv_truth };
constexpr std::string_view kSeparator = "--next file--\n";

void write_all(int descriptor, std::string_view bytes) {
  if (::ftruncate(descriptor, 0) != 0) std::abort();
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t count =
        ::pwrite(descriptor, bytes.data() + written, bytes.size() - written, static_cast<off_t>(written));
    if (count <= 0) std::abort();
    written += static_cast<std::size_t>(count);
  }
}

// The scene directory of this process; its links point at in-memory files.
class SceneDirectory {
 public:
  SceneDirectory() : path_(fs::temp_directory_path() / ("batchccd-fuzz-scene-" + std::to_string(::getpid()))) {
    remove_stale_directories();
    fs::create_directories(path_);
    for (std::size_t i = 0; i < kFiles.size(); ++i) {
      descriptors_[i] = ::memfd_create(kFiles[i], 0);
      if (descriptors_[i] < 0) std::abort();  // a harness failure, not a finding
      present_[i] = false;
      fs::remove(path_ / kFiles[i]);
    }
  }

  const fs::path& path() const { return path_; }
  fs::path file(FileIndex index) const { return path_ / kFiles[index]; }

  void write(std::size_t index, std::optional<std::string_view> contents) {
    if (contents) write_all(descriptors_[index], *contents);
    if (contents.has_value() == present_[index]) return;
    const fs::path link = path_ / kFiles[index];
    if (contents)
      fs::create_symlink("/proc/self/fd/" + std::to_string(descriptors_[index]), link);
    else
      fs::remove(link);
    present_[index] = contents.has_value();
  }

 private:
  // Those of processes that ended (libFuzzer leaves with _Exit, past any
  // cleanup).
  void remove_stale_directories() const {
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(path_.parent_path(), error)) {
      const std::string name = entry.path().filename().string();
      const std::string prefix = "batchccd-fuzz-scene-";
      if (name.rfind(prefix, 0) != 0 || fs::exists("/proc/" + name.substr(prefix.size()), error)) continue;
      fs::remove_all(entry.path(), error);
    }
  }

  fs::path path_;
  std::array<int, kFiles.size()> descriptors_{};
  std::array<bool, kFiles.size()> present_{};
};

// What read_scene must do: the scene, or the error it must throw.
struct Refusal {
  std::string file;
  long line = 0;
  std::string message;   // the whole message, when known
  std::string fragment;  // else a part it must hold: the value at fault
};
struct Expected {
  std::optional<Refusal> refusal;
  batchccd::PlyMesh start, end;
  batchccd::Candidates candidates;
  std::array<std::optional<std::vector<bool>>, 4> truths;
};

Refusal as_refusal(const batchccd::InputError& error) { return {error.file(), error.line(), error.what(), ""}; }

template <class Rows>
std::optional<Refusal> out_of_range(const fs::path& file, const Rows& rows, Eigen::Index vertices,
                                    std::optional<Eigen::Index> faces = std::nullopt) {
  for (std::size_t row = 0; row < rows.size(); ++row)
    for (std::size_t k = 0; k < rows[row].size(); ++k) {
      const bool face_id = faces && k == 1;
      if (rows[row][k] >= (face_id ? *faces : vertices))
        return Refusal{file.string(), static_cast<long>(row) + 1, "",
                       (face_id ? "face id " : "vertex id ") + std::to_string(rows[row][k]) + " is out of range"};
    }
  return std::nullopt;
}

Expected expected_scene(const SceneDirectory& directory, const std::array<bool, kFiles.size()>& present) {
  Expected expected;
  try {
    expected.start = batchccd::read_ply(directory.file(t0));
    expected.end = batchccd::read_ply(directory.file(t1));
    if (expected.end.vertices.rows() != expected.start.vertices.rows()) {
      expected.refusal = Refusal{directory.file(t1).string(), 0, "",
                                 "has " + std::to_string(expected.end.vertices.rows()) + " vertices"};
      return expected;
    }
    const Eigen::Index vertices = expected.start.vertices.rows(), faces = expected.start.faces.rows();
    batchccd::Candidates& c = expected.candidates;
    if (present[vf]) c.vertex_face = batchccd::read_vertex_face_pairs(directory.file(vf));
    if ((expected.refusal = out_of_range(directory.file(vf), c.vertex_face, vertices, faces))) return expected;
    if (present[ee]) c.edge_edge = batchccd::read_edge_edge_pairs(directory.file(ee));
    if ((expected.refusal = out_of_range(directory.file(ee), c.edge_edge, vertices))) return expected;
    if (present[ve]) c.vertex_edge = batchccd::read_vertex_edge_triples(directory.file(ve));
    if ((expected.refusal = out_of_range(directory.file(ve), c.vertex_edge, vertices))) return expected;
    if (present[vv]) c.vertex_vertex = batchccd::read_vertex_vertex_pairs(directory.file(vv));
    if ((expected.refusal = out_of_range(directory.file(vv), c.vertex_vertex, vertices))) return expected;
    const std::array<std::size_t, 4> lengths = {c.vertex_face.size(), c.edge_edge.size(), c.vertex_edge.size(),
                                                c.vertex_vertex.size()};
    for (int k = 0; k < 4; ++k) {
      const auto index = static_cast<FileIndex>(vf_truth + k);
      if (!present[index]) continue;
      expected.truths[k] = batchccd::read_truth(directory.file(index));
      if (expected.truths[k]->size() != lengths[k]) {
        expected.refusal = Refusal{directory.file(index).string(), 0, "",
                                   "has " + std::to_string(expected.truths[k]->size()) + " entries"};
        return expected;
      }
    }
  } catch (const batchccd::InputError& error) {
    expected.refusal = as_refusal(error);
  }
  return expected;
}

bool same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}
bool same(const Eigen::MatrixXi& a, const Eigen::MatrixXi& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}

void check_scene(const batchccd::Scene& scene, const Expected& expected, const SceneDirectory& directory) {
  require(scene.path == directory.path().string(), "the scene keeps its path");
  require(same(scene.positions_t0, expected.start.vertices), "positions at t0 as t0.ply reads");
  require(same(scene.positions_t1, expected.end.vertices), "positions at t1 as t1.ply reads");
  require(same(scene.faces, expected.start.faces), "faces as t0.ply reads");
  const batchccd::Candidates& c = scene.candidates;
  require(c.vertex_face == expected.candidates.vertex_face, "vf.csv as its reader reads it (or empty)");
  require(c.edge_edge == expected.candidates.edge_edge, "ee.csv as its reader reads it (or empty)");
  require(c.vertex_edge == expected.candidates.vertex_edge, "ve.csv as its reader reads it (or empty)");
  require(c.vertex_vertex == expected.candidates.vertex_vertex, "vv.csv as its reader reads it (or empty)");
  require(scene.vertex_face_truth == expected.truths[0], "vf_truth.txt as read (or none)");
  require(scene.edge_edge_truth == expected.truths[1], "ee_truth.txt as read (or none)");
  require(scene.vertex_edge_truth == expected.truths[2], "ve_truth.txt as read (or none)");
  require(scene.vertex_vertex_truth == expected.truths[3], "vv_truth.txt as read (or none)");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static SceneDirectory directory;
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  const unsigned presence = rest.empty() ? 0u : static_cast<std::uint8_t>(rest.front());
  if (!rest.empty()) rest.remove_prefix(1);
  std::array<bool, kFiles.size()> present{};
  for (std::size_t i = 0; i < kFiles.size(); ++i) {
    const std::size_t end = std::min(rest.find(kSeparator), rest.size());
    const std::string_view contents = rest.substr(0, end);
    rest.remove_prefix(std::min(end + kSeparator.size(), rest.size()));
    present[i] = i < 2 || (presence >> (i - 2) & 1u) != 0;
    directory.write(i, present[i] ? std::optional(contents) : std::nullopt);
  }

  const Expected expected = expected_scene(directory, present);
  try {
    const batchccd::Scene scene = batchccd::read_scene(directory.path());
    require(!expected.refusal, "a bad scene is refused", expected.refusal ? expected.refusal->message.c_str() : "");
    check_scene(scene, expected, directory);
  } catch (const batchccd::InputError& error) {
    require(expected.refusal.has_value(), "a good scene is read", error.what());
    require(error.file() == expected.refusal->file, "the error names the first bad file", error.what());
    require(error.line() == expected.refusal->line, "the error names the bad line (or none)", error.what());
    if (!expected.refusal->message.empty())
      require(error.what() == expected.refusal->message, "a malformed file's error is its reader's", error.what());
    else
      require(std::string_view(error.what()).find(expected.refusal->fragment) != std::string_view::npos,
              "the error names the value at fault", error.what());
  }
  return 0;
}

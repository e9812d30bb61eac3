// Scene-directory writer. Candidate lists reach hundreds of megabytes, so
// text is formatted with std::to_chars into a buffer flushed in large blocks.

#include "scene_writer.hpp"

#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace batchccd::scenes {
namespace {

namespace fs = std::filesystem;

// A file written through a growing buffer; flush() hands it to the stream.
class BufferedFile {
 public:
  explicit BufferedFile(const fs::path& path) : path_(path), stream_(path, std::ios::binary) {
    if (!stream_) fail();
    buffer_.reserve(kBlock + 256);
  }

  void text(const std::string& s) { buffer_ += s; }
  void integer(long long value) {
    std::array<char, 24> digits;
    const auto end = std::to_chars(digits.data(), digits.data() + digits.size(), value).ptr;
    buffer_.append(digits.data(), end);
  }
  void character(char c) { buffer_ += c; }
  // Little-endian bytes whatever the host's order.
  template <class Unsigned>
  void little_endian(Unsigned bits) {
    for (std::size_t byte = 0; byte < sizeof(Unsigned); ++byte)
      buffer_ += static_cast<char>((bits >> (8 * byte)) & 0xff);
  }
  void float64(double value) { little_endian(std::bit_cast<std::uint64_t>(value)); }
  void int32(int value) { little_endian(static_cast<std::uint32_t>(value)); }

  // Call after every item: writes out full blocks.
  void maybe_flush() {
    if (buffer_.size() >= kBlock) flush();
  }
  void close() {
    flush();
    stream_.close();
    if (!stream_) fail();
  }

 private:
  static constexpr std::size_t kBlock = std::size_t{1} << 20;

  void flush() {
    stream_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    if (!stream_) fail();
    buffer_.clear();
  }
  [[noreturn]] void fail() const { throw std::runtime_error("cannot write " + path_.string()); }

  fs::path path_;
  std::ofstream stream_;
  std::string buffer_;
};

void write_ply(const fs::path& path, const PositionsView& positions, const IdsView& faces) {
  BufferedFile file(path);
  file.text("ply\nformat binary_little_endian 1.0\ncomment written by batchccd_scenes\n");
  file.text("element vertex " + std::to_string(positions.rows()) + "\n");
  file.text("property double x\nproperty double y\nproperty double z\n");
  file.text("element face " + std::to_string(faces.rows()) + "\n");
  file.text("property list uchar int vertex_indices\nend_header\n");
  for (std::int64_t v = 0; v < positions.rows(); ++v) {
    for (int axis = 0; axis < 3; ++axis) file.float64(positions(v, axis));
    file.maybe_flush();
  }
  for (std::int64_t f = 0; f < faces.rows(); ++f) {
    file.little_endian(std::uint8_t{3});
    for (int k = 0; k < 3; ++k) file.int32(faces(f, k));
    file.maybe_flush();
  }
  file.close();
}

template <std::size_t N>
void write_csv(const fs::path& path, const std::vector<std::array<int, N>>& rows) {
  BufferedFile file(path);
  for (const auto& row : rows) {
    for (std::size_t k = 0; k < N; ++k) {
      if (k > 0) file.character(',');
      file.integer(row[k]);
    }
    file.character('\n');
    file.maybe_flush();
  }
  file.close();
}

}  // namespace

void write_scene_directory(const fs::path& directory, const MeshView& mesh,
                           const Candidates& candidates) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) throw std::runtime_error("cannot create " + directory.string() + ": " + error.message());
  write_ply(directory / "t0.ply", mesh.positions_t0, mesh.faces);
  write_ply(directory / "t1.ply", mesh.positions_t1, mesh.faces);
  write_csv(directory / "vf.csv", candidates.vertex_face);
  write_csv(directory / "ee.csv", candidates.edge_edge);
  // Truth left from an earlier scene would no longer match the lists.
  for (const char* stale : {"vf_truth.txt", "ee_truth.txt"}) fs::remove(directory / stale, error);
}

}  // namespace batchccd::scenes

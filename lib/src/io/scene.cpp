// Candidate lists and scene directories (docs/design.md §9).

#include <charconv>
#include <string>
#include <system_error>
#include <vector>

#include "batchccd/io.hpp"
#include "io/text_input.hpp"

namespace batchccd {

namespace {

using io_detail::all_digits;
using io_detail::in_quotes;
using io_detail::NumberedLine;

int parse_id(const std::string& file, const NumberedLine& line, std::size_t column, std::string_view field) {
  const std::string where = "column " + std::to_string(column + 1) + ": ";
  if (!field.empty() && field.front() == '-' && all_digits(field.substr(1)))
    throw InputError(file, line.number, where + "negative id " + in_quotes(field));
  if (!all_digits(field))
    throw InputError(file, line.number, where + "expected a non-negative integer, found " + in_quotes(field));
  int id = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), id);
  if (error != std::errc() || end != field.data() + field.size())
    throw InputError(file, line.number, where + "id " + in_quotes(field) + " is too large for an int");
  return id;
}

// Rows of N comma-separated ids; row i is on line i + 1 since no blank line
// may precede the trailing ones.
template <std::size_t N>
std::vector<std::array<int, N>> read_id_rows(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string text = io_detail::read_input_file(path);
  std::vector<std::array<int, N>> rows;
  for (const NumberedLine& line : io_detail::numbered_lines(text)) {
    if (io_detail::trim(line.text).empty()) throw InputError(file, line.number, "empty line");
    const std::vector<std::string_view> fields = io_detail::split_fields(line.text);
    if (fields.size() != N)
      throw InputError(
          file, line.number,
          "expected " + std::to_string(N) + " comma-separated ids, found " + std::to_string(fields.size()));
    std::array<int, N> row{};
    for (std::size_t column = 0; column < N; ++column) row[column] = parse_id(file, line, column, fields[column]);
    rows.push_back(row);
  }
  return rows;
}

bool is_file(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

struct IdKind {
  const char* singular;
  const char* plural;
};
constexpr IdKind vertex_ids{"vertex", "vertices"};
constexpr IdKind face_ids{"face", "faces"};

void check_id(const std::filesystem::path& file, std::size_t row, IdKind kind, int id, Eigen::Index count) {
  if (id < count) return;
  throw InputError(file.string(), static_cast<long>(row) + 1,
                   std::string(kind.singular) + " id " + std::to_string(id) + " is out of range (the mesh has " +
                       std::to_string(count) + " " + kind.plural + ")");
}

std::vector<std::array<int, 2>> read_checked_vertex_face(const std::filesystem::path& file, const Scene& scene) {
  if (!is_file(file)) return {};
  std::vector<std::array<int, 2>> pairs = read_vertex_face_pairs(file);
  for (std::size_t row = 0; row < pairs.size(); ++row) {
    check_id(file, row, vertex_ids, pairs[row][0], scene.positions_t0.rows());
    check_id(file, row, face_ids, pairs[row][1], scene.faces.rows());
  }
  return pairs;
}

// Lists of vertex ids alone (ee, ve, vv); empty when the file is absent.
template <std::size_t N>
std::vector<std::array<int, N>> read_checked_vertex_ids(const std::filesystem::path& file, const Scene& scene) {
  if (!is_file(file)) return {};
  std::vector<std::array<int, N>> rows = read_id_rows<N>(file);
  for (std::size_t row = 0; row < rows.size(); ++row)
    for (const int id : rows[row]) check_id(file, row, vertex_ids, id, scene.positions_t0.rows());
  return rows;
}

// One truth a candidate, when the truth file is there.
std::optional<std::vector<bool>> read_matching_truth(const std::filesystem::path& file, std::size_t candidate_count,
                                                     const char* candidate_file) {
  if (!is_file(file)) return std::nullopt;
  std::vector<bool> truth = read_truth(file);
  if (truth.size() != candidate_count)
    throw InputError(file.string(), 0,
                     "has " + std::to_string(truth.size()) + " entries but " + candidate_file + " has " +
                         std::to_string(candidate_count) + " candidates");
  return truth;
}

}  // namespace

std::vector<std::array<int, 2>> read_vertex_face_pairs(const std::filesystem::path& path) {
  return read_id_rows<2>(path);
}

std::vector<std::array<int, 4>> read_edge_edge_pairs(const std::filesystem::path& path) {
  return read_id_rows<4>(path);
}

std::vector<std::array<int, 3>> read_vertex_edge_triples(const std::filesystem::path& path) {
  return read_id_rows<3>(path);
}

std::vector<std::array<int, 2>> read_vertex_vertex_pairs(const std::filesystem::path& path) {
  return read_id_rows<2>(path);
}

bool is_scene_directory(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_directory(path, error) && is_file(path / "t0.ply") && is_file(path / "t1.ply");
}

Scene read_scene(const std::filesystem::path& directory) {
  if (!is_scene_directory(directory))
    throw InputError(directory.string(), 0, "not a scene directory: it must hold t0.ply and t1.ply");
  Scene scene;
  scene.path = directory.string();
  PlyMesh start = read_ply(directory / "t0.ply");
  PlyMesh end = read_ply(directory / "t1.ply");
  if (end.vertices.rows() != start.vertices.rows())
    throw InputError((directory / "t1.ply").string(), 0,
                     "has " + std::to_string(end.vertices.rows()) + " vertices but t0.ply has " +
                         std::to_string(start.vertices.rows()));
  scene.positions_t0 = std::move(start.vertices);
  scene.positions_t1 = std::move(end.vertices);
  scene.faces = std::move(start.faces);

  scene.candidates.vertex_face = read_checked_vertex_face(directory / "vf.csv", scene);
  scene.candidates.edge_edge = read_checked_vertex_ids<4>(directory / "ee.csv", scene);
  scene.candidates.vertex_edge = read_checked_vertex_ids<3>(directory / "ve.csv", scene);
  scene.candidates.vertex_vertex = read_checked_vertex_ids<2>(directory / "vv.csv", scene);
  scene.vertex_face_truth =
      read_matching_truth(directory / "vf_truth.txt", scene.candidates.vertex_face.size(), "vf.csv");
  scene.edge_edge_truth = read_matching_truth(directory / "ee_truth.txt", scene.candidates.edge_edge.size(), "ee.csv");
  scene.vertex_edge_truth =
      read_matching_truth(directory / "ve_truth.txt", scene.candidates.vertex_edge.size(), "ve.csv");
  scene.vertex_vertex_truth =
      read_matching_truth(directory / "vv_truth.txt", scene.candidates.vertex_vertex.size(), "vv.csv");
  return scene;
}

}  // namespace batchccd

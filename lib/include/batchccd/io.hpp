#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "batchccd/batch.hpp"
#include "batchccd/query.hpp"

// Readers for the data formats of docs/design.md §9 (query CSV files, PLY
// meshes, candidate lists, scene directories). Every reader validates what
// it reads and throws InputError naming the file, the line (0 when the
// problem has no line, e.g. a missing file, or a binary PLY body, where the
// message names the element entry instead) and the problem; none crashes on
// malformed input. Coordinates are returned as read, in the file's units.
namespace batchccd {

// What every reader throws on a missing, unreadable or malformed file.
// what() is "file:line: problem" ("file: problem" when line is 0).
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, long line, const std::string& problem);
  const std::string& file() const { return file_; }
  long line() const { return line_; }  // 1-based; 0 when not tied to a line

 private:
  std::string file_;
  long line_;
};

// x_num / x_den as the exact double it denotes. Both are decimal integers of
// any length (the denominator positive). Throws std::invalid_argument when the
// text is not an integer or the value is not exactly a finite double.
double exact_double_from_rational(std::string_view numerator,
                                  std::string_view denominator);

// The kind a path names, ignoring case: "vertex-face" or a "vf" word means
// vertex_face, "edge-edge" or an "ee" word edge_edge, "vertex-edge",
// "point-edge" or a "ve" word vertex_edge, "vertex-vertex", "point-point" or
// a "vv" word vertex_vertex (the last such component wins, and within it the
// last mention; a pair's words may be joined by '-', '_' or any other single
// separator). std::nullopt when no component names one. Never throws.
std::optional<Kind> kind_from_path(const std::filesystem::path& path);

// The queries of one query CSV file, in file order.
struct QueryFile {
  std::string path;  // as given to read_query_csv
  Kind kind = Kind::vertex_face;
  std::vector<Query> queries;
  std::optional<std::vector<bool>> truth;  // one per query, when the file has it
};

// Query CSV: 2 * points_per_time(kind) rows a query, its points at t0 then
// at t1, each point once: vertex_face and edge_edge 8 rows in the point
// order of Query; vertex_edge 6 (p, e0, e1 at t0, then at t1); vertex_vertex
// 4 (p, q at t0, then at t1). Read into Query's layout (make_query). 7
// columns x_num,x_den,y_num,y_den,z_num,z_den,truth (truth 0/1, equal on the
// query's rows) or 6 columns without truth. Commas with or without a space
// after them. The file does not say its kind, so the caller does
// (kind_from_path helps). Each coordinate must be exactly a double
// (exact_double_from_rational). Throws InputError on any bad row: a wrong
// column count, a row count that is not a multiple of the kind's rows, a
// value that is not exactly a double, a truth that is not 0/1 or differs
// within a query, an empty line.
QueryFile read_query_csv(const std::filesystem::path& path, Kind kind);

// Ground truth: a JSON array of booleans (true/false, or 0/1), or one 0/1 a
// line. Throws InputError on anything else.
std::vector<bool> read_truth(const std::filesystem::path& path);

// A triangle mesh as read from a PLY file.
struct PlyMesh {
  Eigen::MatrixXd vertices;  // n x 3
  Eigen::MatrixXi faces;     // m x 3 (triangles only)
};

// PLY in any standard encoding: ascii, binary_little_endian,
// binary_big_endian; x/y/z of any numeric type among other vertex properties
// (converted to double; other properties are skipped); faces as a list
// property named vertex_indices or vertex_index (a file without a face
// element gives 0 x 3 faces). Throws InputError on a malformed header, a
// truncated body, a face that is not a triangle or a vertex index out of
// range.
PlyMesh read_ply(const std::filesystem::path& path);

// Candidate lists: "vertex,face", "a0,a1,b0,b1", "vertex,e0,e1" or "p,q" a
// line, no header; ids are 0-based. Throws InputError on a wrong field
// count, a negative or non-integer id, an id too large for an int, an empty
// line. Ids are not checked against a mesh here (read_scene does).
std::vector<std::array<int, 2>> read_vertex_face_pairs(const std::filesystem::path& path);
std::vector<std::array<int, 4>> read_edge_edge_pairs(const std::filesystem::path& path);
std::vector<std::array<int, 3>> read_vertex_edge_triples(const std::filesystem::path& path);
std::vector<std::array<int, 2>> read_vertex_vertex_pairs(const std::filesystem::path& path);

// A scene directory's contents, ready for mesh_ccd:
//   mesh_ccd({scene.positions_t0, scene.positions_t1, scene.faces}, scene.candidates)
struct Scene {
  std::string path;  // the directory, as given
  Eigen::MatrixXd positions_t0;
  Eigen::MatrixXd positions_t1;
  Eigen::MatrixXi faces;
  Candidates candidates;
  std::optional<std::vector<bool>> vertex_face_truth;
  std::optional<std::vector<bool>> edge_edge_truth;
  std::optional<std::vector<bool>> vertex_edge_truth;
  std::optional<std::vector<bool>> vertex_vertex_truth;
};

// A directory holding t0.ply and t1.ply. Never throws (false when the path
// cannot be examined).
bool is_scene_directory(const std::filesystem::path& path);

// t0.ply, t1.ply (same vertex count, faces from t0.ply), vf.csv, ee.csv,
// ve.csv and vv.csv (any may be absent: an empty list), vf_truth.txt,
// ee_truth.txt, ve_truth.txt and vv_truth.txt (optional; their length must
// match). Every index is checked against the mesh.
// Throws InputError when the directory is not a scene directory, a file is
// malformed, the vertex counts differ, an id is out of range or a truth
// file's length does not match its candidate list.
Scene read_scene(const std::filesystem::path& directory);

}  // namespace batchccd

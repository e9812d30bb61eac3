// Seed corpora for the fuzz targets, cut from ../shared/data (never copied
// into the repository): small pieces, since libFuzzer mutates small inputs
// fastest and infers its maximum input length from the seeds.
//
//   make_seed_corpora SHARED_DATA_DIR OUTPUT_DIR
//
// writes OUTPUT_DIR/{query_csv,truth,pairs,ply,scene,query_kernels}/, and the
// built-in seeds of the targets whose inputs need no data
// (OUTPUT_DIR/{query_kernels,planar,point_kinds}/).

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "batchccd/io.hpp"
#include "kernel_input.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kQueryRows = 8;      // one query
constexpr std::size_t kListLines = 16;     // candidate and truth lists
constexpr Eigen::Index kPlyFaces = 3;      // faces kept of a scene mesh
constexpr Eigen::Index kPlyVertices = 6;   // vertices kept of a mesh without faces
constexpr std::size_t kKernelQueries = 2;  // queries of a sample file made kernel seeds

void write_bytes(const fs::path& file, const std::string& bytes) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string as_string(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

std::vector<std::string> first_lines(const fs::path& file, std::size_t count) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string line; lines.size() < count && std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// A 7-column row without its truth column.
std::string without_last_column(const std::string& row) { return row.substr(0, row.rfind(',')); }

// "scenes/cloth-funnel-227/vf.csv" -> "cloth-funnel-227-vf.csv"
std::string seed_name(const fs::path& file, int parents) {
  std::string name = file.filename().string();
  fs::path at = file.parent_path();
  for (int i = 0; i < parents; ++i, at = at.parent_path()) name = at.filename().string() + "-" + name;
  return name;
}

std::vector<fs::path> sorted_files(const fs::path& root, const std::string& extension) {
  std::vector<fs::path> files;
  if (!fs::is_directory(root)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file() && entry.path().extension() == extension) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// ---- query CSV and query kernels --------------------------------------------

// Kernel inputs start with a setup byte (kernel_input.hpp): the seeds take
// turns over its first 128 values (those without a time window), so that
// every configuration has seeds.
std::string next_setup_byte() {
  static unsigned next = 0;
  return std::string(1, static_cast<char>(next++ % 128u));
}

// Every CSV under `root` that names a kind, or only those named queries_*.
void query_seeds(const fs::path& root, bool only_named_queries, const fs::path& out) {
  for (const fs::path& file : sorted_files(root, ".csv")) {
    const std::optional<batchccd::Kind> kind = batchccd::kind_from_path(file);
    const bool named_queries = file.filename().string().rfind("queries", 0) == 0;
    if (!kind || (only_named_queries && !named_queries)) continue;
    const std::vector<std::string> rows = first_lines(file, kQueryRows);
    if (rows.size() < kQueryRows) continue;
    const std::string name = seed_name(file, 2);
    write_bytes(out / "query_csv" / (name + "-7col"), joined(rows));
    std::vector<std::string> six_columns;
    for (const std::string& row : rows) six_columns.push_back(without_last_column(row));
    write_bytes(out / "query_csv" / (name + "-6col"), joined(six_columns));

    const batchccd::QueryFile queries = batchccd::read_query_csv(file, *kind);
    std::string all = next_setup_byte();
    for (std::size_t q = 0; q < std::min(kKernelQueries, queries.queries.size()); ++q) {
      std::vector<std::uint8_t> record = batchccd::fuzz::encode_raw_record(*kind, queries.queries[q]);
      write_bytes(out / "query_kernels" / (name + "-" + std::to_string(q)), next_setup_byte() + as_string(record));
      all += as_string(record);
      record[0] |= 4;  // the same query with a contact forced at t0
      write_bytes(out / "query_kernels" / (name + "-" + std::to_string(q) + "-contact"),
                  next_setup_byte() + as_string(record));
    }
    write_bytes(out / "query_kernels" / (name + "-batch"), all);
  }
}

// Grid records need no data: a vertex falling through a triangle and two
// edges crossing, at t = 1/2, in small integers.
void grid_kernel_seeds(const fs::path& out) {
  const std::vector<std::int8_t> vertex_face = {1, 1, 4, 0, 0, 0, 4, 0, 0, 0, 4, 0,
                                                1, 1, -4, 0, 0, 0, 4, 0, 0, 0, 4, 0};
  const std::vector<std::int8_t> edge_edge = {2, -4, 4, 2, 4, 4, 0, 0, 0, 4, 0, 0,
                                              2, -4, -4, 2, 4, -4, 0, 0, 0, 4, 0, 0};
  const auto record = [](std::uint8_t control, const std::vector<std::int8_t>& coordinates) {
    std::string bytes{static_cast<char>(control), 3};  // scale by 2^24 too
    for (const std::int8_t c : coordinates) bytes += static_cast<char>(c);
    return bytes + '\0';  // grid exponent 0
  };
  for (char setup = 0; setup < 32; ++setup) {
    const std::string name = "grid-setup-" + std::to_string(static_cast<int>(setup));
    write_bytes(out / "query_kernels" / (name + "-vertex-face"), setup + record(2, vertex_face));
    write_bytes(out / "query_kernels" / (name + "-edge-edge"), setup + record(3, edge_edge));
    write_bytes(out / "query_kernels" / (name + "-both-contact-t1"),
                setup + record(2 | 8, vertex_face) + record(3 | 8, edge_edge));
  }
  // At each separation, and with time windows ending at the contact (tmax
  // byte 127: 1/2) and before it (95: 3/8), in each mode.
  for (unsigned mode = 0; mode < 4; ++mode)
    for (unsigned separation = 0; separation < 4; ++separation)
      for (const int window : {-1, 127, 95}) {
        std::string setup(1, static_cast<char>(mode | separation << 5 | (window >= 0 ? 128u : 0u)));
        if (window >= 0) setup += static_cast<char>(window);
        const std::string name = "grid-mode-" + std::to_string(mode) + "-separation-" + std::to_string(separation) +
                                 "-window-" + std::to_string(window);
        write_bytes(out / "query_kernels" / name, setup + record(2, vertex_face) + record(3 | 8, edge_edge));
      }
}

// ---- planar and point kinds: built in --------------------------------------

// fuzz_planar.cpp's records: plane, separation index, origin, u, v, then the
// eight points' in-plane coordinates (units of 1/16).
std::string planar_record(std::uint8_t plane, std::uint8_t separation, const std::array<std::int8_t, 9>& frame,
                          const std::array<std::int8_t, 16>& in_plane) {
  std::string bytes{static_cast<char>(plane), static_cast<char>(separation)};
  for (const std::int8_t c : frame) bytes += static_cast<char>(c);
  for (const std::int8_t c : in_plane) bytes += static_cast<char>(c);
  return bytes;
}

// An event of each kind at t = 1/2, on the floor (z = 0, its axis plane) at
// d = 1/2 and on the tilted plane z = x + 2y at d = 0: a vertex crossing a
// triangle's edge, segments crossing, a point through a segment, two points
// passing.
void planar_seeds(const fs::path& out) {
  const std::array<std::int8_t, 9> floor = {0, 0, 0, 1, 0, 0, 0, 1, 0}, tilted = {0, 0, 0, 1, 0, 1, 0, 1, 2};
  const std::array<std::array<std::int8_t, 16>, 4> events = {{
      {-16, 16, 0, 0, 64, 0, 0, 64, 16, 16, 0, 0, 64, 0, 0, 64},        // vf: p, a, b, c at t0, then t1
      {-32, 0, 32, 0, 0, 16, 0, 48, -32, 0, 32, 0, 0, -48, 0, -16},    // ee
      {8, 16, 8, 16, 0, 0, 16, 0, 8, -16, 8, -16, 0, 0, 16, 0},        // ve: p, p, e0, e1
      {32, 0, 32, 0, 0, 0, 0, 0, -32, 0, -32, 0, 0, 0, 0, 0},          // vv: p, p, q, q
  }};
  constexpr std::uint8_t kFloor = 3, kTilted = 0, kHalf = 4, kZero = 0;
  constexpr std::uint8_t kPerQuery = 8, kExact = 4;
  for (std::uint8_t kind = 0; kind < 4; ++kind) {
    const std::string name = std::string("planar-") + batchccd::to_string(static_cast<batchccd::Kind>(kind));
    const std::string on_floor = planar_record(kFloor, kHalf, floor, events[kind]);
    const std::string on_tilted = planar_record(kTilted, kZero, tilted, events[kind]);
    const auto header = [&](std::uint8_t flags, std::uint8_t tmax) {
      return std::string{static_cast<char>(kind | flags), static_cast<char>(tmax)};
    };
    write_bytes(out / "planar" / (name + "-floor"), header(0, 255) + on_floor);
    write_bytes(out / "planar" / (name + "-tilted-exact-tmax"), header(kExact, 127) + on_tilted);
    write_bytes(out / "planar" / (name + "-both"), header(kPerQuery, 255) + on_floor + on_tilted);
    // Four records, the most an input holds (libFuzzer takes its longest seed as the length to reach).
    write_bytes(out / "planar" / (name + "-four"),
                header(kPerQuery | kExact, 191) + on_floor + on_tilted + on_tilted + on_floor);
  }
}

// fuzz_point_kinds.cpp's inputs: a point falling past a segment (or a
// point), placed on it at each contact time, flat and nearly flat, at d = 0
// and d = 2^-6, and once scaled by 2^-400.
void point_kind_seeds(const fs::path& out) {
  const std::array<std::int8_t, 18> points = {8, 8, 16, 0, 0, 0, 16, 16, 0,     // p, e0, e1 at t0
                                              8, 10, -16, 16, 0, 0, 0, 16, 0};  // at t1: e0, e1 swap ends
  for (std::uint8_t kind = 0; kind < 2; ++kind)
    for (std::uint8_t contact = 0; contact <= 4; ++contact)
      for (const int flatness : {0, 8})
        for (const int separation : {0, 3}) {
          const std::uint8_t flags = static_cast<std::uint8_t>(kind | contact << 1 | 2 << 4);
          std::string bytes{static_cast<char>(flags), static_cast<char>(contact == 2 ? 63 : 255),
                            static_cast<char>(separation), static_cast<char>(flatness), 0};
          for (const std::int8_t c : points) bytes += static_cast<char>(c);
          const std::string name = std::string("point-") + (kind ? "vv" : "ve") + "-contact-" +
                                   std::to_string(contact) + "-flat-" + std::to_string(flatness) + "-d-" +
                                   std::to_string(separation);
          write_bytes(out / "point_kinds" / name, bytes);
          if (contact == 3) {
            bytes[4] = static_cast<char>(-100);  // 2^-400
            write_bytes(out / "point_kinds" / (name + "-tiny"), bytes);
          }
        }
}

// ---- truth and candidate lists ------------------------------------------------

void list_seeds(const fs::path& scenes, const fs::path& out) {
  for (const fs::path& file : sorted_files(scenes, ".txt")) {
    const std::string name = file.filename().string();
    if (name.find("truth") == std::string::npos) continue;
    const std::vector<std::string> lines = first_lines(file, kListLines);
    write_bytes(out / "truth" / seed_name(file, 1), joined(lines));
    std::string words = "[", bits = "[";
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const char* separator = i + 1 < lines.size() ? ", " : "";
      words += std::string(lines[i] == "1" ? "true" : "false") + separator;
      bits += lines[i] + (i + 1 < lines.size() ? "," : "");
    }
    write_bytes(out / "truth" / (seed_name(file, 1) + "-words.json"), words + "]\n");
    write_bytes(out / "truth" / (seed_name(file, 1) + "-bits.json"), bits + "]");
  }
  for (const fs::path& file : sorted_files(scenes, ".csv")) {
    const std::string name = file.filename().string();
    if (name == "vf.csv" || name == "ee.csv")
      write_bytes(out / "pairs" / seed_name(file, 1), joined(first_lines(file, kListLines)));
  }
}

// ---- PLY ----------------------------------------------------------------------

// The first faces of a mesh and the vertices they use, renumbered; the first
// vertices alone when the mesh has no faces.
batchccd::PlyMesh small_piece(const batchccd::PlyMesh& mesh) {
  batchccd::PlyMesh piece;
  const Eigen::Index faces = std::min(kPlyFaces, mesh.faces.rows());
  std::vector<int> kept;  // old ids in new order
  piece.faces.resize(faces, 3);
  for (Eigen::Index f = 0; f < faces; ++f)
    for (Eigen::Index k = 0; k < 3; ++k) {
      const int id = mesh.faces(f, k);
      auto at = std::find(kept.begin(), kept.end(), id);
      if (at == kept.end()) at = kept.insert(kept.end(), id);
      piece.faces(f, k) = static_cast<int>(at - kept.begin());
    }
  if (kept.empty())
    for (int v = 0; v < std::min<int>(static_cast<int>(kPlyVertices), static_cast<int>(mesh.vertices.rows())); ++v)
      kept.push_back(v);
  piece.vertices.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    piece.vertices.row(static_cast<Eigen::Index>(i)) = mesh.vertices.row(kept[i]);
  return piece;
}

enum class PlyStyle { ascii, ascii_with_colours, little_double, big_float };

template <class T>
void append_binary(std::string& bytes, T value, bool big_endian) {
  auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if (big_endian == (std::endian::native == std::endian::little)) std::reverse(raw.begin(), raw.end());
  bytes.append(raw.data(), raw.size());
}

std::string ply_text(const batchccd::PlyMesh& mesh, PlyStyle style) {
  const bool binary = style == PlyStyle::little_double || style == PlyStyle::big_float;
  const bool colours = style == PlyStyle::ascii_with_colours;
  const char* format = style == PlyStyle::little_double ? "binary_little_endian"
                       : style == PlyStyle::big_float   ? "binary_big_endian"
                                                        : "ascii";
  const char* coordinate = style == PlyStyle::big_float ? "float" : "double";
  std::ostringstream header;
  header << "ply\nformat " << format << " 1.0\ncomment cut from ../shared/data by make_seed_corpora\n"
         << "element vertex " << mesh.vertices.rows() << "\n";
  for (const char* axis : {"x", "y", "z"}) header << "property " << coordinate << " " << axis << "\n";
  if (colours) header << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (mesh.faces.rows() > 0)
    header << "element face " << mesh.faces.rows() << "\nproperty list uchar int vertex_indices\n";
  header << "end_header\n";
  std::string bytes = header.str();
  std::ostringstream ascii;
  ascii.precision(17);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      const double x = mesh.vertices(v, axis);
      if (style == PlyStyle::little_double) append_binary(bytes, x, false);
      if (style == PlyStyle::big_float) append_binary(bytes, static_cast<float>(x), true);
      if (!binary) ascii << (axis ? " " : "") << x;
    }
    if (colours) ascii << " 200 100 50";
    if (!binary) ascii << "\n";
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (binary) {
      bytes += static_cast<char>(3);
      for (Eigen::Index k = 0; k < 3; ++k) append_binary(bytes, mesh.faces(f, k), style == PlyStyle::big_float);
    } else {
      ascii << "3 " << mesh.faces(f, 0) << " " << mesh.faces(f, 1) << " " << mesh.faces(f, 2) << "\n";
    }
  }
  return bytes + ascii.str();
}

void ply_seeds(const fs::path& scenes, const fs::path& out) {
  for (const fs::path& file : sorted_files(scenes, ".ply")) {
    if (file.filename() != "t0.ply") continue;
    const batchccd::PlyMesh piece = small_piece(batchccd::read_ply(file));
    const std::string name = file.parent_path().filename().string();
    write_bytes(out / "ply" / (name + "-ascii.ply"), ply_text(piece, PlyStyle::ascii));
    write_bytes(out / "ply" / (name + "-colours.ply"), ply_text(piece, PlyStyle::ascii_with_colours));
    write_bytes(out / "ply" / (name + "-little-double.ply"), ply_text(piece, PlyStyle::little_double));
    write_bytes(out / "ply" / (name + "-big-float.ply"), ply_text(piece, PlyStyle::big_float));
  }
}

// ---- scene directories ----------------------------------------------------------

// fuzz_scene.cpp's inputs: a presence byte, then t0.ply, t1.ply, vf.csv,
// ee.csv, ve.csv, vv.csv and the four truth files, each ended by the
// separator. A scene's first faces at t0 and t1 (small_piece's vertices,
// both times), with lists over them: each vertex against each face it is
// not on, the faces' edges pairwise, each vertex against each edge and each
// other vertex; truths of their lengths, 1 every third.
std::string scene_seed(const batchccd::PlyMesh& start, const batchccd::PlyMesh& end, PlyStyle style) {
  const Eigen::Index n = start.vertices.rows();
  std::vector<std::array<int, 2>> edges;
  for (Eigen::Index f = 0; f < start.faces.rows(); ++f)
    for (Eigen::Index k = 0; k < 3; ++k) edges.push_back({start.faces(f, k), start.faces(f, (k + 1) % 3)});
  std::string vf, ee, ve, vv;
  std::array<std::size_t, 4> lengths{};
  for (int v = 0; v < n; ++v)
    for (Eigen::Index f = 0; f < start.faces.rows(); ++f)
      if ((start.faces.row(f).array() != v).all()) {
        vf += std::to_string(v) + "," + std::to_string(f) + "\n";
        ++lengths[0];
      }
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      ee += std::to_string(edges[i][0]) + "," + std::to_string(edges[i][1]) + "," + std::to_string(edges[j][0]) +
            "," + std::to_string(edges[j][1]) + "\n";
      ++lengths[1];
    }
  for (int v = 0; v < n; ++v) {
    for (const auto& edge : edges) {
      ve += std::to_string(v) + ", " + std::to_string(edge[0]) + ", " + std::to_string(edge[1]) + "\n";
      ++lengths[2];
    }
    for (int w = v + 1; w < n; ++w) {
      vv += std::to_string(v) + "," + std::to_string(w) + "\n";
      ++lengths[3];
    }
  }
  constexpr std::string_view separator = "--next file--\n";
  std::string bytes(1, static_cast<char>(0xff));  // every file there
  for (const std::string& file : {ply_text(start, style), ply_text(end, style), vf, ee, ve, vv})
    bytes.append(file).append(separator);
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    std::string truth;
    for (std::size_t i = 0; i < lengths[k]; ++i) truth += i % 3 == 0 ? "1\n" : "0\n";
    bytes.append(truth).append(separator);
  }
  return bytes;
}

void scene_seeds(const fs::path& scenes, const fs::path& out) {
  for (const fs::path& file : sorted_files(scenes, ".ply")) {
    if (file.filename() != "t0.ply" || !fs::is_regular_file(file.parent_path() / "t1.ply")) continue;
    const batchccd::PlyMesh start = small_piece(batchccd::read_ply(file));
    // The same vertices at t1: small_piece of t1's positions under t0's faces.
    batchccd::PlyMesh whole_end = batchccd::read_ply(file.parent_path() / "t1.ply");
    whole_end.faces = batchccd::read_ply(file).faces;
    const batchccd::PlyMesh end = small_piece(whole_end);
    const std::string name = file.parent_path().filename().string();
    write_bytes(out / "scene" / (name + "-ascii"), scene_seed(start, end, PlyStyle::ascii));
    write_bytes(out / "scene" / (name + "-little-double"), scene_seed(start, end, PlyStyle::little_double));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_seed_corpora SHARED_DATA_DIR OUTPUT_DIR\n";
    return 2;
  }
  const fs::path data = argv[1];
  const fs::path out = argv[2];
  try {
    grid_kernel_seeds(out);
    planar_seeds(out);
    point_kind_seeds(out);
    if (!fs::is_directory(data)) {
      std::cerr << "make_seed_corpora: no " << data.string() << ": only the built-in seeds\n";
      return 0;
    }
    query_seeds(data / "sample-queries", false, out);
    query_seeds(data / "scenes", true, out);
    list_seeds(data / "scenes", out);
    ply_seeds(data / "scenes", out);
    scene_seeds(data / "scenes", out);
  } catch (const std::exception& error) {
    std::cerr << "make_seed_corpora: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

#include "mesh_validation.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace batchccd {

namespace {

[[noreturn]] void refuse(const std::string& problem) {
  throw std::invalid_argument("mesh_ccd: " + problem);
}

// A matrix with no rows holds nothing to index: any column count is accepted,
// so that default-constructed (0 x 0) matrices describe an empty mesh.
template <class View>
void check_three_columns(const View& matrix, const char* name) {
  if (matrix.rows() > 0 && matrix.cols() != 3)
    refuse(std::string(name) + " must have 3 columns, it has " + std::to_string(matrix.cols()));
}

// Positions are n x 3, or n x 2 for a 2D mesh (read as z = 0), the same
// at t0 and t1; no rows: any column count.
void check_position_columns(const MeshView& mesh) {
  for (const auto& [positions, name] : {std::pair{&mesh.positions_t0, "positions_t0"},
                                        std::pair{&mesh.positions_t1, "positions_t1"}}) {
    if (positions->rows() > 0 && positions->cols() != 3 && positions->cols() != 2)
      refuse(std::string(name) + " must have 3 columns (2 for a 2D mesh), it has " +
             std::to_string(positions->cols()));
  }
  if (mesh.positions_t0.rows() > 0 && mesh.positions_t0.cols() != mesh.positions_t1.cols())
    refuse("positions_t0 has " + std::to_string(mesh.positions_t0.cols()) + " columns but positions_t1 has " +
           std::to_string(mesh.positions_t1.cols()) + ": a mesh is 2D or 3D at both times");
}

std::string range_text(std::int64_t count) { return " out of range [0, " + std::to_string(count) + ")"; }

// id outside [0, count), negative ids included, in one comparison.
bool outside(int id, std::int64_t count) {
  return static_cast<std::uint64_t>(static_cast<std::int64_t>(id)) >= static_cast<std::uint64_t>(count);
}

// Whether some item of `items` has an index out of range, in parallel
// pieces (the lists are as long as the work), each one branch-free pass.
template <class Item, class Outside>
bool any_outside(std::span<const Item> items, Outside item_outside) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, items.size(), 1 << 16), false,
      [&](const tbb::blocked_range<std::size_t>& range, bool found) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) found |= item_outside(items[i]);
        return found;
      },
      [](bool a, bool b) { return a || b; });
}

// Every index at once, so that a valid call (the common case) pays for no
// per-index message machinery.
bool all_in_range(const MeshView& mesh, const CandidateLists& candidates, ListsToCheck lists) {
  const std::int64_t n = mesh.positions_t0.rows(), m = mesh.faces.rows();
  bool found = false;
  for (std::int64_t f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) found |= outside(mesh.faces(f, k), n);
  if (lists.vertex_face)
    found |= any_outside(candidates.vertex_face, [n, m](const std::array<int, 2>& pair) {
      return outside(pair[0], n) || outside(pair[1], m);
    });
  const auto any_vertex_outside = [n](const auto& ids) {
    bool any = false;
    for (const int id : ids) any |= outside(id, n);
    return any;
  };
  if (lists.edge_edge) found |= any_outside(candidates.edge_edge, any_vertex_outside);
  if (lists.vertex_edge) found |= any_outside(candidates.vertex_edge, any_vertex_outside);
  if (lists.vertex_vertex) found |= any_outside(candidates.vertex_vertex, any_vertex_outside);
  return !found;
}

}  // namespace

void check_mesh(const MeshView& mesh, const CandidateLists& candidates, ListsToCheck lists) {
  const std::int64_t n = mesh.positions_t0.rows();
  const std::int64_t m = mesh.faces.rows();
  check_position_columns(mesh);
  check_three_columns(mesh.faces, "faces");
  if (mesh.positions_t1.rows() != n)
    refuse("positions_t0 has " + std::to_string(n) + " rows but positions_t1 has " +
           std::to_string(mesh.positions_t1.rows()));
  if (all_in_range(mesh, candidates, lists)) return;
  // Something is out of range: find the first offender and name it.
  for (std::int64_t f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const int id = mesh.faces(f, k);
      if (id < 0 || id >= n) refuse("face " + std::to_string(f) + ": vertex " + std::to_string(id) + range_text(n));
    }
  auto check_vertex = [n](int id, const char* list, std::size_t item) {
    if (id < 0 || id >= n)
      refuse(std::string(list) + " candidate " + std::to_string(item) + ": vertex " + std::to_string(id) +
             range_text(n));
  };
  // Every list is checked, also one that Options switches off: a bad index
  // is a bug in the caller's broad phase, better told early.
  for (std::size_t i = 0; i < candidates.vertex_face.size(); ++i) {
    const auto [vertex, face] = candidates.vertex_face[i];
    check_vertex(vertex, "vertex-face", i);
    if (m == 0)  // an empty range would tell nothing: say what is missing
      refuse("vertex-face candidates need faces, and no faces were given (vertex-face candidate " +
             std::to_string(i) + " names face " + std::to_string(face) + ")");
    if (face < 0 || face >= m)
      refuse("vertex-face candidate " + std::to_string(i) + ": face " + std::to_string(face) + range_text(m));
  }
  for (std::size_t i = 0; i < candidates.edge_edge.size(); ++i)
    for (int id : candidates.edge_edge[i]) check_vertex(id, "edge-edge", i);
  for (std::size_t i = 0; i < candidates.vertex_edge.size(); ++i)
    for (int id : candidates.vertex_edge[i]) check_vertex(id, "vertex-edge", i);
  for (std::size_t i = 0; i < candidates.vertex_vertex.size(); ++i)
    for (int id : candidates.vertex_vertex[i]) check_vertex(id, "vertex-vertex", i);
}

}  // namespace batchccd

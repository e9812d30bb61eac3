#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "batchccd/query.hpp"
#include "reference/scaled_query.hpp"

// Where a batch's candidates come from: raw queries, or a mesh and its
// candidate index lists. Plain views (no xsimd types), shared by the lane
// kernels, which gather from them, and the scheduler, which hands survivors
// to the scalar solver.
namespace batchccd::simd {

struct RawQueries {
  Kind kind;
  const Query* queries;
};

// Positions are Eigen's column-major n x 3: x, y, z columns of `rows` each.
struct MeshPositions {
  const double* t0;
  const double* t1;
  std::int64_t rows;
};

struct MeshVertexFace {
  static constexpr Kind kind = Kind::vertex_face;
  MeshPositions positions;
  const int* faces;  // column-major m x 3
  std::int64_t face_rows;
  const std::array<int, 2>* pairs;  // vertex, face
};

struct MeshEdgeEdge {
  static constexpr Kind kind = Kind::edge_edge;
  MeshPositions positions;
  const std::array<int, 4>* pairs;  // a0, a1, b0, b1
};

// Vertex ids of candidate i in DESIGN.md's order x1..x4 (VF: a, b, c, p).
// Always inlined, as the lane kernels compiled with other flags call them.
[[gnu::always_inline]] inline std::array<std::int64_t, 4> vertex_ids(const MeshVertexFace& mesh, std::size_t i) {
  const auto [vertex, face] = mesh.pairs[i];
  const int* f = mesh.faces + face;
  return {f[0], f[mesh.face_rows], f[2 * mesh.face_rows], vertex};
}
[[gnu::always_inline]] inline std::array<std::int64_t, 4> vertex_ids(const MeshEdgeEdge& mesh, std::size_t i) {
  const auto& e = mesh.pairs[i];
  return {e[0], e[1], e[2], e[3]};
}

template <class MeshSource>
Query query_at(const MeshSource& mesh, std::size_t i) {
  const std::array<std::int64_t, 4> ids = vertex_ids(mesh, i);
  const MeshPositions& x = mesh.positions;
  Query query;
  for (int k = 1; k <= 4; ++k) {
    const std::int64_t id = ids[k - 1];
    const int slot = reference::point_index(MeshSource::kind, k);
    query.points[slot] = Vec3(x.t0[id], x.t0[id + x.rows], x.t0[id + 2 * x.rows]);
    query.points[slot + 4] = Vec3(x.t1[id], x.t1[id + x.rows], x.t1[id + 2 * x.rows]);
  }
  return query;
}

inline const Query& query_at(const RawQueries& raw, std::size_t i) { return raw.queries[i]; }

}  // namespace batchccd::simd

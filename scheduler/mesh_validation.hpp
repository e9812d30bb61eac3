#pragma once

#include "batchccd/batch.hpp"

namespace batchccd {

// Which candidate lists check_mesh reads (the lane filters check the ids
// of those they read themselves).
struct ListsToCheck {
  bool vertex_face = true;
  bool edge_edge = true;
  bool vertex_edge = true;
  bool vertex_vertex = true;
};

// Throws std::invalid_argument naming the first bad item: positions that
// are not n x 3 or n x 2 (a 2D mesh) alike at t0 and t1, faces not m x 3
// (zero rows: any column count), positions_t0 and positions_t1 of unequal
// row counts, or an index out of range in a face or in
// one of `lists` (once something is wrong, the first bad item of all, in the
// order faces, vertex-face, edge-edge, vertex-edge, vertex-vertex). Runs in the caller's task arena.
void check_mesh(const MeshView& mesh, const CandidateLists& candidates, ListsToCheck lists = {});

}  // namespace batchccd

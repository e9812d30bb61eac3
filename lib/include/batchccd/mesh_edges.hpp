#pragma once

#include <array>
#include <span>

#include "batchccd/batch.hpp"
#include "batchccd/options.hpp"

namespace batchccd {

// Broad-phase candidates by element id, as a broad phase over vertices,
// faces and edges reports them (ipc-toolkit's candidates name edges by id).
// Views of the caller's buffers: a std::vector converts implicitly.
struct EdgeIdCandidates {
  std::span<const std::array<int, 2>> vertex_face{};    // vertex id, face id (row of faces)
  std::span<const std::array<int, 2>> edge_edge{};      // edge id, edge id (rows of edges)
  std::span<const std::array<int, 2>> vertex_edge{};    // vertex id, edge id
  std::span<const std::array<int, 2>> vertex_vertex{};  // two vertex ids
};

// mesh_ccd (batch.hpp) for edges given by id, read from mesh.edges: edge-edge
// candidate (i, j) is the query of edges row i against row j, vertex-edge
// candidate (v, e) the query of vertex v against edges row e. Same options,
// promises and result: one QueryResult per candidate in input order,
// vertex-face, edge-edge, vertex-edge, vertex-vertex. Costs one pass over the
// candidates to expand edge ids into vertex ids (into a buffer of its own).
//
// Bad input: throws std::invalid_argument naming the first bad item when
// edges is not k x 2, an edge's vertex id is not in [0, n), an edge id is
// not in [0, k), or anything mesh_ccd rejects (matrix shapes, vertex and
// face ids out of range). Nothing is evaluated then.
BatchResult mesh_ccd(const MeshView& mesh, const EdgeIdCandidates& candidates,
                     const Options& options = {});
// The same into `out`, keeping its storage (as the overloads of batch.hpp).
void mesh_ccd(const MeshView& mesh, const EdgeIdCandidates& candidates, const Options& options,
              BatchResult& out);

}  // namespace batchccd

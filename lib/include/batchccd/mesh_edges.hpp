#pragma once

#include <array>
#include <span>

#include <Eigen/Core>

#include "batchccd/batch.hpp"
#include "batchccd/options.hpp"

namespace batchccd {

// A mesh as simulators hold it, by reference (nothing is copied): vertex
// positions at the start and the end of the step (n x 3, same n, any
// length unit), triangles (m x 3 vertex ids) and edges (k x 2 vertex ids).
// An empty faces or edges matrix (0 rows) is allowed.
struct MeshWithEdgesView {
  const Eigen::MatrixXd& positions_t0;
  const Eigen::MatrixXd& positions_t1;
  const Eigen::MatrixXi& faces;
  const Eigen::MatrixXi& edges;
};

// Broad-phase candidates by element id, as a broad phase over vertices,
// faces and edges reports them. Views: a std::vector converts implicitly.
struct EdgeIdCandidates {
  std::span<const std::array<int, 2>> vertex_face;  // vertex id, face id (row of faces)
  std::span<const std::array<int, 2>> edge_edge;    // edge id, edge id (rows of edges)
};

// mesh_ccd (batch.hpp) for edges given by id: each edge-edge candidate
// (i, j) is the query of edges.row(i) against edges.row(j). Same options,
// promises and result: one QueryResult per candidate in input order,
// vertex-face first, then edge-edge; earliest_toi in [0, 1] or +inf.
// Costs one pass over the candidates to expand edge ids into vertex ids.
//
// Bad input: throws std::invalid_argument naming the first bad item when
// edges is not k x 2, an edge's vertex id is not in [0, n), an edge id is
// not in [0, k), or anything mesh_ccd rejects (matrix shapes, vertex and
// face ids out of range). Nothing is evaluated then.
BatchResult mesh_ccd(const MeshWithEdgesView& mesh, const EdgeIdCandidates& candidates,
                     const Options& options = {});
// The same into `out`, keeping its storage (as the overloads of batch.hpp).
void mesh_ccd(const MeshWithEdgesView& mesh, const EdgeIdCandidates& candidates, const Options& options,
              BatchResult& out);

}  // namespace batchccd

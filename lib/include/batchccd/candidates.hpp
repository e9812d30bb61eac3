#pragma once

#include <array>

#include <Eigen/Core>

#include "batchccd/batch.hpp"
#include "batchccd/query.hpp"
#include "batchccd/views.hpp"

// What lies between a mesh and the narrow phase: the edges a broad phase
// needs, and a mesh candidate as the raw Query of batch_ccd and ccd.hpp.
namespace batchccd {

// The undirected edges of the triangles, each once, as a k x 2 matrix of
// vertex ids (i, j) with i < j, rows sorted lexicographically; ready for
// MeshView::edges (mesh_edges.hpp). A face's repeated vertex gives no
// edge of its own. Throws std::invalid_argument when faces has rows but not
// 3 columns, or holds a negative vertex id.
Eigen::MatrixXi unique_edges(const IdsView& faces);

// The query mesh_ccd evaluates for a candidate: its four vertices at t0,
// then at t1, in Query's point order (vertex, then the face's corners in
// the order of its row; edge a, then edge b). Throws std::invalid_argument
// naming the bad id when a vertex or face id is out of range or the
// positions are not n x 3 (or n x 2, a 2D mesh: z = 0) at both times.
Query vertex_face_query(const MeshView& mesh, const std::array<int, 2>& candidate);
Query edge_edge_query(const MeshView& mesh, const std::array<int, 4>& candidate);

}  // namespace batchccd

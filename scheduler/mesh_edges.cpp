#include "batchccd/mesh_edges.hpp"

#include <stdexcept>
#include <string>

namespace batchccd {
namespace {

std::string range(Eigen::Index count) { return " out of range [0, " + std::to_string(count) + ")"; }

void check_edges(const MeshWithEdgesView& mesh, const EdgeIdCandidates& candidates) {
  const Eigen::MatrixXi& edges = mesh.edges;
  if (edges.rows() > 0 && edges.cols() != 2)  // no rows: any column count
    throw std::invalid_argument("mesh_ccd: edges must have 2 columns, got " +
                                std::to_string(edges.cols()));
  const Eigen::Index vertices = mesh.positions_t0.rows();
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    for (int k = 0; k < 2; ++k)
      if (edges(e, k) < 0 || edges(e, k) >= vertices)
        throw std::invalid_argument("mesh_ccd: edge " + std::to_string(e) + ": vertex " +
                                    std::to_string(edges(e, k)) + range(vertices));
  for (std::size_t i = 0; i < candidates.edge_edge.size(); ++i)
    for (int id : candidates.edge_edge[i])
      if (id < 0 || id >= edges.rows())
        throw std::invalid_argument("mesh_ccd: edge-edge candidate " + std::to_string(i) +
                                    ": edge " + std::to_string(id) + range(edges.rows()));
}

}  // namespace

// Expands edge ids into the vertex quadruples of Candidates and hands over to
// the one mesh path, so both entry points share validation and scheduling.
void mesh_ccd(const MeshWithEdgesView& mesh, const EdgeIdCandidates& candidates, const Options& options,
              BatchResult& out) {
  check_edges(mesh, candidates);
  Candidates by_vertex;
  by_vertex.vertex_face.assign(candidates.vertex_face.begin(), candidates.vertex_face.end());
  by_vertex.edge_edge.reserve(candidates.edge_edge.size());
  for (const auto [a, b] : candidates.edge_edge)
    by_vertex.edge_edge.push_back(
        {mesh.edges(a, 0), mesh.edges(a, 1), mesh.edges(b, 0), mesh.edges(b, 1)});
  mesh_ccd(MeshView{mesh.positions_t0, mesh.positions_t1, mesh.faces}, by_vertex, options, out);
}

BatchResult mesh_ccd(const MeshWithEdgesView& mesh, const EdgeIdCandidates& candidates,
                     const Options& options) {
  BatchResult result;
  mesh_ccd(mesh, candidates, options, result);
  return result;
}

}  // namespace batchccd

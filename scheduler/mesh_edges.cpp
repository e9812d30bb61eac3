#include "batchccd/mesh_edges.hpp"

#include <stdexcept>
#include <string>

namespace batchccd {
namespace {

std::string range(std::int64_t count) { return " out of range [0, " + std::to_string(count) + ")"; }

void check_edge_ids(std::span<const std::array<int, 2>> pairs, bool first_is_vertex, const char* list,
                    std::int64_t edges) {
  for (std::size_t i = 0; i < pairs.size(); ++i)
    for (std::size_t k = first_is_vertex ? 1 : 0; k < 2; ++k)
      if (pairs[i][k] < 0 || pairs[i][k] >= edges)
        throw std::invalid_argument(std::string("mesh_ccd: ") + list + " candidate " + std::to_string(i) +
                                    ": edge " + std::to_string(pairs[i][k]) + range(edges));
}

void check_edges(const MeshView& mesh, const EdgeIdCandidates& candidates) {
  const IdsView& edges = mesh.edges;
  if (edges.rows() > 0 && edges.cols() != 2)  // no rows: any column count
    throw std::invalid_argument("mesh_ccd: edges must have 2 columns, got " + std::to_string(edges.cols()));
  const std::int64_t vertices = mesh.positions_t0.rows();
  for (std::int64_t e = 0; e < edges.rows(); ++e)
    for (int k = 0; k < 2; ++k)
      if (edges(e, k) < 0 || edges(e, k) >= vertices)
        throw std::invalid_argument("mesh_ccd: edge " + std::to_string(e) + ": vertex " +
                                    std::to_string(edges(e, k)) + range(vertices));
  check_edge_ids(candidates.edge_edge, false, "edge-edge", edges.rows());
  check_edge_ids(candidates.vertex_edge, true, "vertex-edge", edges.rows());
}

}  // namespace

// Expands edge ids into the vertex ids of CandidateLists and hands over to
// the one mesh path, so both entry points share validation and scheduling.
void mesh_ccd(const MeshView& mesh, const EdgeIdCandidates& candidates, const Options& options,
              BatchResult& out) {
  check_edges(mesh, candidates);
  const IdsView& edges = mesh.edges;
  std::vector<std::array<int, 4>> edge_edge;
  edge_edge.reserve(candidates.edge_edge.size());
  for (const auto [a, b] : candidates.edge_edge) edge_edge.push_back({edges(a, 0), edges(a, 1), edges(b, 0), edges(b, 1)});
  std::vector<std::array<int, 3>> vertex_edge;
  vertex_edge.reserve(candidates.vertex_edge.size());
  for (const auto [v, e] : candidates.vertex_edge) vertex_edge.push_back({v, edges(e, 0), edges(e, 1)});
  mesh_ccd(mesh, CandidateLists{candidates.vertex_face, edge_edge, vertex_edge, candidates.vertex_vertex}, options,
           out);
}

BatchResult mesh_ccd(const MeshView& mesh, const EdgeIdCandidates& candidates, const Options& options) {
  BatchResult result;
  mesh_ccd(mesh, candidates, options, result);
  return result;
}

}  // namespace batchccd

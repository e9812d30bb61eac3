#include "mesh_validation.hpp"

#include <stdexcept>
#include <string>

namespace batchccd {

void check_mesh(const MeshView& mesh, const Candidates& candidates) {
  const Eigen::Index n = mesh.positions_t0.rows();
  if (mesh.positions_t0.cols() != 3 || mesh.positions_t1.cols() != 3)
    throw std::invalid_argument("mesh_ccd: positions must have 3 columns");
  if (mesh.positions_t1.rows() != n)
    throw std::invalid_argument("mesh_ccd: positions_t0 has " + std::to_string(n) +
                                " rows but positions_t1 has " +
                                std::to_string(mesh.positions_t1.rows()));
  if (mesh.faces.size() > 0 && mesh.faces.cols() != 3)
    throw std::invalid_argument("mesh_ccd: faces must have 3 columns");
  auto check_vertex = [n](int id, const char* list, std::size_t item) {
    if (id < 0 || id >= n)
      throw std::invalid_argument("mesh_ccd: " + std::string(list) + " candidate " +
                                  std::to_string(item) + ": vertex " + std::to_string(id) +
                                  " out of range [0, " + std::to_string(n) + ")");
  };
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int id = mesh.faces(f, k);
      if (id < 0 || id >= n)
        throw std::invalid_argument("mesh_ccd: face " + std::to_string(f) + ": vertex " +
                                    std::to_string(id) + " out of range [0, " +
                                    std::to_string(n) + ")");
    }
  for (std::size_t i = 0; i < candidates.vertex_face.size(); ++i) {
    const auto [vertex, face] = candidates.vertex_face[i];
    check_vertex(vertex, "vertex-face", i);
    if (face < 0 || face >= mesh.faces.rows())
      throw std::invalid_argument("mesh_ccd: vertex-face candidate " + std::to_string(i) +
                                  ": face " + std::to_string(face) + " out of range [0, " +
                                  std::to_string(mesh.faces.rows()) + ")");
  }
  for (std::size_t i = 0; i < candidates.edge_edge.size(); ++i)
    for (int id : candidates.edge_edge[i]) check_vertex(id, "edge-edge", i);
}

}  // namespace batchccd

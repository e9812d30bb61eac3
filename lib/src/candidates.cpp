#include "batchccd/candidates.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace batchccd {
namespace {

void check_id(const char* what, int id, std::int64_t count, const char* caller) {
  if (id < 0 || id >= count)
    throw std::invalid_argument(std::string(caller) + ": " + what + " " + std::to_string(id) +
                                " out of range [0, " + std::to_string(count) + ")");
}

void check_positions(const MeshView& mesh, const char* caller) {
  const auto columns = mesh.positions_t0.cols();
  if ((columns != 3 && columns != 2) || mesh.positions_t1.cols() != columns ||
      mesh.positions_t0.rows() != mesh.positions_t1.rows())
    throw std::invalid_argument(std::string(caller) + ": positions must be n x 3 (or n x 2) at t0 and at t1");
}

// Vertices ids[0..3] at t0, then at t1 (z = 0 for a 2D mesh); the ids are
// checked by the caller.
Query query_of(const MeshView& mesh, const std::array<int, 4>& ids) {
  const auto columns = mesh.positions_t0.cols();
  Query query;
  for (std::size_t k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) {
      query.points[k][c] = c < columns ? mesh.positions_t0(ids[k], c) : 0.0;
      query.points[k + 4][c] = c < columns ? mesh.positions_t1(ids[k], c) : 0.0;
    }
  }
  return query;
}

}  // namespace

Eigen::MatrixXi unique_edges(const IdsView& faces) {
  if (faces.rows() > 0 && faces.cols() != 3)
    throw std::invalid_argument("unique_edges: faces must have 3 columns, got " +
                                std::to_string(faces.cols()));
  std::vector<std::array<int, 2>> edges;
  edges.reserve(3 * static_cast<std::size_t>(faces.rows()));
  for (std::int64_t f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      if (a < 0 || b < 0)
        throw std::invalid_argument("unique_edges: face " + std::to_string(f) +
                                    " has a negative vertex id");
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Eigen::MatrixXi matrix(static_cast<Eigen::Index>(edges.size()), 2);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    matrix(static_cast<Eigen::Index>(e), 0) = edges[e][0];
    matrix(static_cast<Eigen::Index>(e), 1) = edges[e][1];
  }
  return matrix;
}

Query vertex_face_query(const MeshView& mesh, const std::array<int, 2>& candidate) {
  constexpr const char* caller = "vertex_face_query";
  check_positions(mesh, caller);
  const auto [vertex, face] = candidate;
  const std::int64_t vertices = mesh.positions_t0.rows();
  check_id("vertex", vertex, vertices, caller);
  check_id("face", face, mesh.faces.cols() == 3 ? mesh.faces.rows() : 0, caller);
  const std::array<int, 4> ids{vertex, mesh.faces(face, 0), mesh.faces(face, 1), mesh.faces(face, 2)};
  for (std::size_t k = 1; k < 4; ++k) check_id("face's vertex", ids[k], vertices, caller);
  return query_of(mesh, ids);
}

Query edge_edge_query(const MeshView& mesh, const std::array<int, 4>& candidate) {
  constexpr const char* caller = "edge_edge_query";
  check_positions(mesh, caller);
  for (const int id : candidate) check_id("vertex", id, mesh.positions_t0.rows(), caller);
  return query_of(mesh, candidate);
}

}  // namespace batchccd

#pragma once

// A mesh whose contacts come at falling times, one at the start of each
// batch of the lane filters (simd::kFilterBatch candidates), the rest of
// each batch far apart: an earliest-TOI-only call filters each batch over
// the part of the step the contacts before it left open (horizons of 1,
// 16^-1, 16^-2 and 16^-3, scheduler/horizons.hpp) and must still find the
// next, earlier contact. Every kind, in the order the calls take the lists.

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "batchccd/batch.hpp"

namespace batchccd::testing {

// Contact times by list (vertex-face, edge-edge, vertex-edge,
// vertex-vertex), each 0.6 of the one before from 0.6: the windows they
// leave cross every horizon, and each contact lies less than half a window
// before the end of the window it is filtered in.
inline std::vector<std::vector<double>> falling_contact_times() {
  std::vector<std::vector<double>> times(4);
  double time = 0.6;
  for (auto& list : times)
    for (int k = 0; k < 5; ++k, time *= 0.6) list.push_back(time);
  return times;
}

struct FallingContacts {
  Eigen::MatrixXd x0, x1;
  Eigen::MatrixXi faces;
  Candidates candidates;
  MeshView view() const { return {x0, x1, faces}; }
};

// The contacts of falling_contact_times() up to contact `last` of list
// `last_list` (the earliest then), each moving part starting 0.5 above its
// static part and meeting it at its time.
inline FallingContacts falling_contacts(std::size_t last_list, std::size_t last) {
  constexpr std::size_t batch = 2048;  // simd::kFilterBatch
  const std::vector<std::vector<double>> times = falling_contact_times();
  // Vertices 0-4: a static face (0, 1, 2), an edge (3, 4) and a vertex (0)
  // far from vertex 5, the point every filler candidate pairs with them;
  // then each contact's own vertices, 10 apart along x.
  std::vector<Eigen::RowVector3d> start{{-100, 0, 0}, {-99, 0, 0}, {-100, 1, 0}, {-100, 0, 1},
                                        {-99, 1, 1},  {-50, 0, 5}};
  std::vector<double> drop(start.size(), 0);  // how far each vertex falls over the step
  std::vector<std::array<int, 3>> faces{{0, 1, 2}};
  FallingContacts scene;
  Candidates& candidates = scene.candidates;
  const auto add = [&](Eigen::RowVector3d point, double fall) {
    start.push_back(point);
    drop.push_back(fall);
    return static_cast<int>(start.size()) - 1;
  };
  for (std::size_t list = 0; list <= last_list; ++list)
    for (std::size_t k = 0; k < times[list].size() && (list < last_list || k <= last); ++k) {
      const double x = 10.0 * static_cast<double>(start.size()), fall = 0.5 / times[list][k];
      if (list == 0) {
        faces.push_back({add({x, 0, 0}, 0), add({x + 1, 0, 0}, 0), add({x, 1, 0}, 0)});
        candidates.vertex_face.push_back({add({x + 0.25, 0.25, 0.5}, fall), static_cast<int>(faces.size()) - 1});
        candidates.vertex_face.resize(candidates.vertex_face.size() + batch - 1, {5, 0});
      } else if (list == 1) {
        const int a = add({x, -0.5, 0}, 0), b = add({x, 0.5, 0}, 0);
        candidates.edge_edge.push_back({a, b, add({x - 0.5, 0, 0.5}, fall), add({x + 0.5, 0, 0.5}, fall)});
        candidates.edge_edge.resize(candidates.edge_edge.size() + batch - 1, {3, 4, 5, 5});
      } else if (list == 2) {
        const int a = add({x - 0.5, 0, 0}, 0), b = add({x + 0.5, 0, 0}, 0);
        candidates.vertex_edge.push_back({add({x, 0, 0.5}, fall), a, b});
        candidates.vertex_edge.resize(candidates.vertex_edge.size() + batch - 1, {5, 3, 4});
      } else {
        const int a = add({x, 0, 0}, 0);
        candidates.vertex_vertex.push_back({add({x, 0, 0.5}, fall), a});
        candidates.vertex_vertex.resize(candidates.vertex_vertex.size() + batch - 1, {5, 0});
      }
    }
  const auto n = static_cast<Eigen::Index>(start.size());
  scene.x0.resize(n, 3);
  scene.x1.resize(n, 3);
  for (Eigen::Index v = 0; v < n; ++v) {
    scene.x0.row(v) = start[static_cast<std::size_t>(v)];
    scene.x1.row(v) = scene.x0.row(v) - Eigen::RowVector3d(0, 0, drop[static_cast<std::size_t>(v)]);
  }
  scene.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    scene.faces.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  return scene;
}

}  // namespace batchccd::testing

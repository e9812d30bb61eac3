#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "batchccd/batch.hpp"

// A small swept-box broad phase that turns a moving triangle mesh into the
// candidate lists batchccd's narrow phase takes. It exists to feed the
// benchmarks and tests with dense, realistic candidate lists; it is not the
// product, so it stays a plain sort-and-sweep.
namespace batchccd::scenes {

// The mean length of the mesh's unique edges (batchccd::unique_edges) at t0; 0 for a mesh without edges.
double mean_edge_length(const MeshView& mesh);

// Every primitive (vertex, edge, face) gets the box of its vertices at t0 and
// t1, grown by `margin` on every side. Two primitives are candidates when
// their grown boxes overlap (touching counts) on all three axes:
//   vertex_face: vertex v against face f, v not a vertex of f;
//   edge_edge:   two unique edges sharing no vertex, written as
//                (a0, a1, b0, b1) with a0 < a1, b0 < b1 and (a0, a1) < (b0, b1).
// Both lists are sorted, so the output depends on nothing but the input.
// Runs in parallel in the caller's oneTBB arena.
Candidates swept_box_candidates(const MeshView& mesh, double margin);

}  // namespace batchccd::scenes

#pragma once

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

// One query at a time. For many candidates, mesh_ccd / batch_ccd
// (batch.hpp) are faster: they filter in SIMD lanes and run in parallel.
namespace batchccd {

// Vertex p against triangle (a, b, c). Every point moves linearly from its
// _t0 to its _t1 position over t in [0, 1]; the window that counts is
// [0, Options::tmax], and a contact is a distance <= Options::min_distance
// (0: touching). Coordinates in any length unit:
// none is assumed, Options::tolerance is relative to the query's size, and
// in the certified modes scaling all coordinates (and min_distance) by a power of two changes
// no decision and no TOI.
// Returns hit = true when the vertex touches the triangle (edges and
// corners included) at some t in [0, tmax], and its toi (QueryResult); how far
// to trust both is the promise of options.mode (Mode). In the default
// conservative mode: no false negative, and toi is never after the first
// contact (at most Options::toi_tolerance before a clean crossing).
// Options fields that only concern batches (vertex_face, edge_edge,
// per_candidate_results, isa, threads) are ignored.
//
// Bad input: Options that validate() refuses throw std::invalid_argument.
// A NaN or infinite coordinate gives status = invalid_input,
// hit = true, toi = 0 (a caller that ignores status never skips a contact).
// Degenerate geometry (a zero-area triangle, points that do not move,
// coplanar motion) is valid input, decided like any other.
QueryResult vertex_face_ccd(const Vec3& p_t0, const Vec3& a_t0, const Vec3& b_t0,
                            const Vec3& c_t0, const Vec3& p_t1, const Vec3& a_t1,
                            const Vec3& b_t1, const Vec3& c_t1,
                            const Options& options = {});

// Edge (ea0, ea1) against edge (eb0, eb1), moving as in vertex_face_ccd:
// hit = true when the two segments (end points included) touch at some t in
// [0, 1]. Zero-length and parallel edges are valid input. Results and bad
// input as vertex_face_ccd.
QueryResult edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0,
                          const Vec3& eb1_t0, const Vec3& ea0_t1, const Vec3& ea1_t1,
                          const Vec3& eb0_t1, const Vec3& eb1_t1,
                          const Options& options = {});

// Point p against segment (e0, e1): hit = true when the point comes within
// Options::min_distance of the segment (end points included). A zero-length
// edge is valid input (then a point against a point). Results and bad input
// as vertex_face_ccd.
QueryResult vertex_edge_ccd(const Vec3& p_t0, const Vec3& e0_t0, const Vec3& e1_t0,
                            const Vec3& p_t1, const Vec3& e0_t1, const Vec3& e1_t1,
                            const Options& options = {});

// Point p against point q: hit = true when they come within
// Options::min_distance of each other. Results and bad input as
// vertex_face_ccd.
QueryResult vertex_vertex_ccd(const Vec3& p_t0, const Vec3& q_t0, const Vec3& p_t1,
                              const Vec3& q_t1, const Options& options = {});

// One query of any kind, its eight points in the order Query documents
// (the order of the query files). The same as the calls above.
QueryResult query_ccd(Kind kind, const Query& query, const Options& options = {});
// A query of a 2D scene (Query2D) is asked as lifted(query): the plane
// z = 0, where it is decided as planar motion.

// The squared Euclidean distance between the query's closed primitives at
// time t in [0, 1], in plain double arithmetic (closest points by
// projection; not certified): what a simulator takes a per-pair separation
// from, such as ipc-toolkit's fraction of the initial distance.
double squared_distance(Kind kind, const Query& query, double t = 0);

}  // namespace batchccd

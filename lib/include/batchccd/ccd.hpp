#pragma once

#include "batchccd/options.hpp"
#include "batchccd/point_arguments.hpp"
#include "batchccd/query.hpp"

// One query at a time. For many candidates, mesh_ccd / batch_ccd
// (batch.hpp) are faster: they filter in SIMD lanes and run in parallel.
namespace batchccd {

// One query of any kind, its eight points in the order Query documents
// (the order of the query files). The same as the per-kind calls below.
QueryResult query_ccd(Kind kind, const Query& query, const Options& options = {});
// A query of a 2D scene (Query2D) is asked as lifted(query): the plane
// z = 0, where it is decided as planar motion.

// Points: Eigen vectors of doubles (Vec3, a Map, Ref, block, VectorXd, an
// expression such as a + b), or braced lists of three numbers {x, y, z}.
// vertex_face_ccd and edge_edge_ccd take 3D points only; vertex_edge_ccd
// and vertex_vertex_ccd take 2D or 3D points, all of one length: a 2D point
// is the 3D point (x, y, 0), so a 2D call is the call with its points
// lifted (Query2D, lifted) and decided as planar motion (docs/design.md
// §5a). A length fixed at compile time that does not fit (a Vector2d for a
// triangle, a Vector2d beside a Vec3, a Vector4d) does not compile; a
// length known only at run time that does not fit throws
// std::invalid_argument naming the call and the argument
// (point_arguments.hpp). No call reads past a vector's end.

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
// Bad input: a point of the wrong length (above) or Options that validate()
// refuses throw std::invalid_argument.
// A NaN or infinite coordinate gives status = invalid_input,
// hit = true, toi = 0 (a caller that ignores status never skips a contact).
// Degenerate geometry (a zero-area triangle, points that do not move,
// coplanar motion) is valid input, decided like any other.
template <class P0 = detail::BracedPoint, class P1 = detail::BracedPoint, class P2 = detail::BracedPoint,
          class P3 = detail::BracedPoint, class P4 = detail::BracedPoint, class P5 = detail::BracedPoint,
          class P6 = detail::BracedPoint, class P7 = detail::BracedPoint>
  requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
QueryResult vertex_face_ccd(const P0& p_t0, const P1& a_t0, const P2& b_t0, const P3& c_t0, const P4& p_t1,
                            const P5& a_t1, const P6& b_t1, const P7& c_t1, const Options& options = {}) {
  const auto points = detail::read_points({"p_t0", "a_t0", "b_t0", "c_t0", "p_t1", "a_t1", "b_t1", "c_t1"}, p_t0,
                                          a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1);
  return query_ccd(Kind::vertex_face,
                   detail::query_from_points("batchccd::vertex_face_ccd", Kind::vertex_face, points), options);
}

// Edge (ea0, ea1) against edge (eb0, eb1), moving as in vertex_face_ccd:
// hit = true when the two segments (end points included) touch at some t in
// [0, 1]. Zero-length and parallel edges are valid input. Results and bad
// input as vertex_face_ccd.
template <class P0 = detail::BracedPoint, class P1 = detail::BracedPoint, class P2 = detail::BracedPoint,
          class P3 = detail::BracedPoint, class P4 = detail::BracedPoint, class P5 = detail::BracedPoint,
          class P6 = detail::BracedPoint, class P7 = detail::BracedPoint>
  requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
QueryResult edge_edge_ccd(const P0& ea0_t0, const P1& ea1_t0, const P2& eb0_t0, const P3& eb1_t0,
                          const P4& ea0_t1, const P5& ea1_t1, const P6& eb0_t1, const P7& eb1_t1,
                          const Options& options = {}) {
  const auto points =
      detail::read_points({"ea0_t0", "ea1_t0", "eb0_t0", "eb1_t0", "ea0_t1", "ea1_t1", "eb0_t1", "eb1_t1"}, ea0_t0,
                          ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1);
  return query_ccd(Kind::edge_edge, detail::query_from_points("batchccd::edge_edge_ccd", Kind::edge_edge, points),
                   options);
}

// Point p against segment (e0, e1): hit = true when the point comes within
// Options::min_distance of the segment (end points included). A zero-length
// edge is valid input (then a point against a point). 2D or 3D points.
// Results and bad input as vertex_face_ccd.
template <class P0 = detail::BracedPoint, class P1 = detail::BracedPoint, class P2 = detail::BracedPoint,
          class P3 = detail::BracedPoint, class P4 = detail::BracedPoint, class P5 = detail::BracedPoint>
  requires PlanarOrSpatialPoints<P0, P1, P2, P3, P4, P5>
QueryResult vertex_edge_ccd(const P0& p_t0, const P1& e0_t0, const P2& e1_t0, const P3& p_t1, const P4& e0_t1,
                            const P5& e1_t1, const Options& options = {}) {
  const auto points = detail::read_points({"p_t0", "e0_t0", "e1_t0", "p_t1", "e0_t1", "e1_t1"}, p_t0, e0_t0, e1_t0,
                                          p_t1, e0_t1, e1_t1);
  return query_ccd(Kind::vertex_edge,
                   detail::query_from_points("batchccd::vertex_edge_ccd", Kind::vertex_edge, points), options);
}

// Point p against point q: hit = true when they come within
// Options::min_distance of each other. 2D or 3D points. Results and bad
// input as vertex_face_ccd.
template <class P0 = detail::BracedPoint, class P1 = detail::BracedPoint, class P2 = detail::BracedPoint,
          class P3 = detail::BracedPoint>
  requires PlanarOrSpatialPoints<P0, P1, P2, P3>
QueryResult vertex_vertex_ccd(const P0& p_t0, const P1& q_t0, const P2& p_t1, const P3& q_t1,
                              const Options& options = {}) {
  const auto points = detail::read_points({"p_t0", "q_t0", "p_t1", "q_t1"}, p_t0, q_t0, p_t1, q_t1);
  return query_ccd(Kind::vertex_vertex,
                   detail::query_from_points("batchccd::vertex_vertex_ccd", Kind::vertex_vertex, points), options);
}

// The squared Euclidean distance between the query's closed primitives at
// time t in [0, 1], in plain double arithmetic (closest points by
// projection; not certified): what a simulator takes a per-pair separation
// from, such as ipc-toolkit's fraction of the initial distance.
double squared_distance(Kind kind, const Query& query, double t = 0);

}  // namespace batchccd

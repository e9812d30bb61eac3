#pragma once

#include <array>
#include <limits>
#include <span>

#include <Eigen/Core>

namespace batchccd {

// A point. Coordinates in any length unit: none is assumed, and tolerances
// are relative to each query's size.
using Vec3 = Eigen::Vector3d;
// A point of a 2D scene: the 3D point (x, y, 0).
using Vec2 = Eigen::Vector2d;

// The elementary tests: the two of triangle-mesh CCD (docs/design.md §1), and
// point-edge and point-point for rods, particles and codimensional contact
// (docs/design.md §11; mostly useful with Options::min_distance > 0).
enum class Kind { vertex_face, edge_edge, vertex_edge, vertex_vertex };

// "vf", "ee", "ve" or "vv", the command-line tool's names. Never null.
const char* to_string(Kind kind);

// Points a query of this kind names at one time: 4, 4, 3, 2.
int points_per_time(Kind kind);

// One elementary query: eight points, t0 positions first, in the order of
// the query files (docs/design.md §9):
//   vertex_face:   p_t0, a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1
//   edge_edge:     ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1
// A point-edge or point-point query is the edge-edge query of the point as
// a zero-length edge: the same test, so it is stored that way (make_query
// below builds it from the points alone):
//   vertex_edge:   p_t0, p_t0, e0_t0, e1_t0, p_t1, p_t1, e0_t1, e1_t1
//   vertex_vertex: p_t0, p_t0, q_t0, q_t0, p_t1, p_t1, q_t1, q_t1
// Every vertex moves linearly from its t0 to its t1 position over t in [0, 1].
struct Query {
  std::array<Vec3, 8> points;
};

// The query of `kind` whose points at t0 are points_t0 and at t1 points_t1
// (points_per_time(kind) of each, in the order above without repetitions:
// vertex_edge p, e0, e1; vertex_vertex p, q). Throws std::invalid_argument
// when a span has another size.
Query make_query(Kind kind, std::span<const Vec3> points_t0, std::span<const Vec3> points_t1);

// A query of a 2D scene: Query's eight points in the same order, each the
// 3D point (x, y, 0) (lifted). Every call and promise is that of the lifted
// query; motion in a plane is decided there (docs/design.md §5a).
struct Query2D {
  std::array<Vec2, 8> points;
};

// As make_query above, in 2D.
Query2D make_query(Kind kind, std::span<const Vec2> points_t0, std::span<const Vec2> points_t1);

// The query in the plane z = 0.
Query lifted(const Query2D& query);

// Bad input, per query, in every mode and entry point (tests/test_bad_input.cpp):
// - A NaN or infinite coordinate among the eight points: not evaluated;
//   status = invalid_input, hit = true, toi = 0. In a batch only that query
//   is affected; the others get the answers they get alone.
// - Degenerate geometry is valid input, evaluated as the geometry it
//   describes (status ok): a triangle with repeated or collinear corners is a
//   segment or a point, an edge with equal endpoints a point. A vertex that
//   is a corner of its own triangle, or two edges sharing an endpoint (mesh
//   neighbours), touch throughout: a hit at toi = 0. Broad phases usually
//   leave such pairs out.
enum class Status {
  ok,             // evaluated; hit and toi are meaningful
  invalid_input,  // a coordinate is NaN or infinite: not evaluated, hit is true
                  // (toi 0) so that a caller that ignores status never skips
                  // a contact
};

// The answer to one query.
struct QueryResult {
  // The primitives come within Options::min_distance of each other (touch,
  // by default) at some t in [0, Options::tmax], as far as Options::mode
  // promises.
  bool hit = false;
  // Time of impact in [0, tmax], +inf when there is none. Never later than
  // the first contact (a lower bound; how close, Mode in options.hpp).
  double toi = std::numeric_limits<double>::infinity();
  Status status = Status::ok;
};

}  // namespace batchccd

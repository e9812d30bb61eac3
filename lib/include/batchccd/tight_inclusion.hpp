#pragma once

// Per-query calls with Tight Inclusion's names and argument order
// (ticcd::vertexFaceCCD, ticcd::edgeEdgeCCD), so that a port compiles and
// means the same: replace `ticcd::` by `batchccd::ticcd::`. Decided in
// batchccd's conservative mode (Mode::conservative: never a false negative).
//
// Returns true when the primitives come within ms of each other (Euclidean
// distance; Tight Inclusion's own test is the cube [-ms, ms]^3) at some t in
// [0, t_max], with toi a lower bound of the first such time, at most
// Options::toi_tolerance (1e-7) of the step before it; false with
// toi = +infinity otherwise.
// - err: ignored; rounding errors are bounded inside the library per query.
// - tolerance: a distance in the caller's units (Tight Inclusion's delta):
//   pairs that never come within ms are reported only when they come within
//   ms + tolerance. output_tolerance is set to it.
// - max_itr: the solver's box budget (-1: none); a query that exhausts it is
//   reported as a contact, never missed.
// - no_zero_toi and the root-finding method have no counterpart: a contact
//   at t = 0 is reported as toi = 0.
//
// Bad input: std::invalid_argument when ms is negative or not finite, t_max
// is not in (0, 1] or tolerance is not positive and finite. A NaN or
// infinite coordinate returns true with toi = 0.
// Points: Eigen vectors of three doubles (Tight Inclusion's Vector3d, maps,
// expressions, a dynamic vector of length 3); a fixed length other than 3
// does not compile and a dynamic one throws std::invalid_argument naming
// the argument (point_arguments.hpp), so no call reads past a vector.
#include "batchccd/point_arguments.hpp"
#include "batchccd/query.hpp"

namespace batchccd::ticcd {

using Vector3 = Vec3;
using Array3 = Eigen::Array3d;

namespace detail {
// Both calls, once their points are read (t0 points, then t1 points):
// checks the lengths (std::invalid_argument naming `call` and the
// argument), then the other arguments, then decides.
bool decide(const char* call, Kind kind, std::span<const batchccd::detail::PointArgument> points, double ms,
            double& toi, double tolerance, double t_max, long max_itr, double& output_tolerance);
using batchccd::detail::BracedPoint;
using batchccd::detail::read_points;
}  // namespace detail

template <class P0 = detail::BracedPoint, class P1 = detail::BracedPoint, class P2 = detail::BracedPoint,
          class P3 = detail::BracedPoint, class P4 = detail::BracedPoint, class P5 = detail::BracedPoint,
          class P6 = detail::BracedPoint, class P7 = detail::BracedPoint>
  requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
bool vertexFaceCCD(const P0& vertex_start, const P1& face_vertex0_start, const P2& face_vertex1_start,
                   const P3& face_vertex2_start, const P4& vertex_end, const P5& face_vertex0_end,
                   const P6& face_vertex1_end, const P7& face_vertex2_end, const Array3& /*err*/, double ms,
                   double& toi, double tolerance, double t_max, long max_itr, double& output_tolerance) {
  const auto points = detail::read_points(
      {"vertex_start", "face_vertex0_start", "face_vertex1_start", "face_vertex2_start", "vertex_end",
       "face_vertex0_end", "face_vertex1_end", "face_vertex2_end"},
      vertex_start, face_vertex0_start, face_vertex1_start, face_vertex2_start, vertex_end, face_vertex0_end,
      face_vertex1_end, face_vertex2_end);
  return detail::decide("batchccd::ticcd::vertexFaceCCD", Kind::vertex_face, points, ms, toi, tolerance, t_max,
                        max_itr, output_tolerance);
}

template <class P0 = detail::BracedPoint, class P1 = detail::BracedPoint, class P2 = detail::BracedPoint,
          class P3 = detail::BracedPoint, class P4 = detail::BracedPoint, class P5 = detail::BracedPoint,
          class P6 = detail::BracedPoint, class P7 = detail::BracedPoint>
  requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
bool edgeEdgeCCD(const P0& edge0_vertex0_start, const P1& edge0_vertex1_start, const P2& edge1_vertex0_start,
                 const P3& edge1_vertex1_start, const P4& edge0_vertex0_end, const P5& edge0_vertex1_end,
                 const P6& edge1_vertex0_end, const P7& edge1_vertex1_end, const Array3& /*err*/, double ms,
                 double& toi, double tolerance, double t_max, long max_itr, double& output_tolerance) {
  const auto points = detail::read_points(
      {"edge0_vertex0_start", "edge0_vertex1_start", "edge1_vertex0_start", "edge1_vertex1_start",
       "edge0_vertex0_end", "edge0_vertex1_end", "edge1_vertex0_end", "edge1_vertex1_end"},
      edge0_vertex0_start, edge0_vertex1_start, edge1_vertex0_start, edge1_vertex1_start, edge0_vertex0_end,
      edge0_vertex1_end, edge1_vertex0_end, edge1_vertex1_end);
  return detail::decide("batchccd::ticcd::edgeEdgeCCD", Kind::edge_edge, points, ms, toi, tolerance, t_max,
                        max_itr, output_tolerance);
}

}  // namespace batchccd::ticcd

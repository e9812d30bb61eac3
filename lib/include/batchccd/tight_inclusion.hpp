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
#include "batchccd/query.hpp"

namespace batchccd::ticcd {

using Vector3 = Vec3;
using Array3 = Eigen::Array3d;

bool vertexFaceCCD(const Vector3& vertex_start, const Vector3& face_vertex0_start,
                   const Vector3& face_vertex1_start, const Vector3& face_vertex2_start,
                   const Vector3& vertex_end, const Vector3& face_vertex0_end,
                   const Vector3& face_vertex1_end, const Vector3& face_vertex2_end,
                   const Array3& err, double ms, double& toi, double tolerance, double t_max,
                   long max_itr, double& output_tolerance);

bool edgeEdgeCCD(const Vector3& edge0_vertex0_start, const Vector3& edge0_vertex1_start,
                 const Vector3& edge1_vertex0_start, const Vector3& edge1_vertex1_start,
                 const Vector3& edge0_vertex0_end, const Vector3& edge0_vertex1_end,
                 const Vector3& edge1_vertex0_end, const Vector3& edge1_vertex1_end,
                 const Array3& err, double ms, double& toi, double tolerance, double t_max,
                 long max_itr, double& output_tolerance);

}  // namespace batchccd::ticcd

#pragma once

#include "reference/scaled_query.hpp"

namespace batchccd::reference {

// What a query's primitives are, once zero-length edges are taken as the
// points they are (planar_shape).
enum class PlanarShape { triangle_vertex, segments, vertex_segment, segment_vertex, vertices };

// VF, or EE with either edge of zero length at t0 and at t1 (how point-edge
// and point-point queries are stored) as a point.
PlanarShape planar_shape(Kind kind, const Query& query);

// What the planar solver proved on a query projected along one axis.
struct PlanarOutcome {
  // Proven on the projection: a miss, or a contact whose first time lies in
  // [toi, toi_upper]. Not certain: the signs were too close to call (a
  // grazing corner, collinear motion, a root at an interval's end).
  bool certain = false;
  bool hit = false;
  double toi = 0;
  double toi_upper = 0;
};

// Decides a query in the plane orthogonal to coordinate `axis`
// (docs/design.md §5a): the scaled frame's differences with that coordinate
// dropped. A contact in 3D projects to a contact in the plane, so a certain
// miss here is a certain miss of the query whatever its geometry, and the
// projected first contact is never after the 3D one. When all eight points
// lie in one plane that the projection maps one to one (exact_plane_axis),
// the two are the same query: a certain hit is a hit, at the same time.
// Contact conditions are the signs of orientations of three moving points,
// quadratics in t: VF, the vertex on the inner side of all three edges; EE,
// each segment's ends on opposite sides of the other's line. Time intervals
// are searched earliest first over [0, 1], up to tmax (so a TOI does not
// depend on tmax); where a single condition is left to change sign, its
// root is bracketed to toi_width directly.
// A point against a segment is on it where it crosses the segment's line
// between the ends; two points meet only at a time no sign test certifies,
// so those contacts are left to the exact stage (certain misses are not).
PlanarOutcome solve_planar(PlanarShape shape, const ScaledQuery& query, int axis, double tmax, double toi_width);

// The same with a separation (min_distance > 0, `separation` in the scaled
// frame): the first time in [0, tmax] the primitives come within it, when
// the projection along `axis` keeps distances (every point shares that
// coordinate). Certain outcomes are proven: a hit by a time where a vertex
// lies certainly within the separation of the other primitive's segment or
// point (or the primitives meet), a miss by excluding every time; the TOI
// is bracketed to toi_width. Not certain: a tangential approach, a segment
// shrinking to a point, or signs too close to call.
PlanarOutcome solve_planar_within(PlanarShape shape, const ScaledQuery& query, int axis, double separation,
                                  double tmax, double toi_width);

// The same search in 3D for a point against a segment or a point
// (vertex_segment, segment_vertex, vertices), where the pairs say all, at
// any separation >= 0: at 0 it can only prove misses (a contact is an
// equality no sign certifies), which it does where the search over
// (t, u, v) gets lost (nearly planar motion).
PlanarOutcome solve_point_within(PlanarShape shape, const ScaledQuery& query, double separation, double tmax,
                                 double toi_width);

}  // namespace batchccd::reference

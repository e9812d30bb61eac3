#pragma once

#include <cstdint>

#include "reference/scaled_query.hpp"

namespace batchccd::reference {

struct SolverSettings {
  bool certified = true;       // false: plain double, no error bounds (the fast baseline)
  bool need_toi = true;
  double tolerance = 1e-9;     // distance, in the scaled frame (query size ~1)
  double toi_tolerance = 1e-7;
  std::int64_t max_iterations = 1 << 20;
  // Certified hits with need_toi: once a certain root with a certain inside
  // test is found, locate the first contact on the cubic alone down to this
  // width (0: stop at toi_tolerance). Exact mode asks for 2^-40.
  double refined_toi_width = 0;
  // The separation that counts as a contact, in the scaled frame (>= 0;
  // +inf allowed). With > 0 the search looks for the distance, not a root.
  double min_distance = 0;
  // Intervals starting after tmax hold no contact that counts.
  double tmax = 1;
  // Pieces of the step the filters proved free of contact (FilterVerdict):
  // bit j for [j / pieces, (j + 1) / pieces], never searched.
  std::uint8_t free_pieces = 0;
  int pieces = 1;
};

struct SolverOutcome {
  bool hit = false;
  double toi = 0;          // when hit: a lower bound of the first contact
  bool undecided = false;  // ran out of iterations (reported as a hit)
  // Certified mode only: the decision is proven, not just bounded. A miss is
  // certain (every box was excluded with error bounds); a hit is certain when
  // a certain root of the cubic with a certain inside test settled it. A hit
  // within `tolerance`, at the smallest time width or out of iterations is
  // not certain: exact mode settles those exactly.
  bool certain = false;
  // A certain hit's first contact is the cubic's first root in [toi,
  // toi_upper], a dyadic interval; refined_toi_width (or toi_tolerance)
  // wide unless the cubic's signs became too close to call first.
  double toi_upper = 1;
  // A hit because the primitives certainly come within `tolerance` of each
  // other (not proven to touch): the one uncertain hit conservative mode may
  // report as it is. With min_distance > 0: within min_distance + tolerance.
  bool within_tolerance = false;
};

// Decides whether the primitives meet for some t in [0, 1] by bisecting boxes
// of (t, u, v), where u, v are the barycentric (VF) or edge (EE) parameters
// and F(t, u, v) the vector between the two points they name; F vanishes
// exactly at a contact. F is linear in u and v and in t, so its range over a
// box is spanned by the box's 8 corners: a box is excluded when one component
// is certainly nonzero at every corner, or when the coplanarity cubic is
// certainly nonzero over the box's times (root isolation, docs/design.md §5).
// Boxes are taken earliest time first, so the first box that cannot be
// excluded and whose image is within `tolerance` of zero gives the TOI.
// Degenerate triangles, parallel or zero-length edges and coplanar motion
// need no special case: F stays well defined.
// With min_distance > 0 a box is excluded when its image is certainly
// farther than min_distance from zero along some direction (the image lies
// in the convex hull of the corners), and a contact is certain where F at
// a box's centre is certainly within min_distance (a witness); the cubic
// plays no part. Intervals after tmax are never searched.
SolverOutcome solve_inclusion(Kind kind, const ScaledQuery& query, const SolverSettings& settings);

}  // namespace batchccd::reference

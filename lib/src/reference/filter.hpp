#pragma once

#include <cstddef>
#include <cstdint>

#include "batchccd/lab.hpp"
#include "batchccd/options.hpp"
#include "decider.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::reference {

// Which lane filters run, and how (docs/design.md §3-4).
struct FilterSettings {
  bool certified = true;   // cull only when error bounds prove it; else plain signs (the fast baseline)
  bool sign = true;        // the Bernstein sign test on the coplanarity cubic
  bool subdivide = true;   // its V = 2 step (false: DNF-style, the four signs only)
  bool separation = true;  // distance at t = 0 against the largest displacement
  // With the separation filter: both filters over 2, 4 or 8 equal pieces of
  // the step for what they keep (1: the whole step only; docs/design.md §4a).
  int pieces = 4;
  bool swept_box = true;  // the swept boxes in the frame of x1, before the others
  // A call with minimum separations (docs/design.md §11) filters every candidate
  // for one, 0 included: the sign filter as the distance to the plane or
  // line pair (no halves), the separation filter with the separation added.
  bool within = false;
  double min_distance = 0;                 // for every candidate,
  const double* min_distances = nullptr;   // or one per candidate
  // Edge-edge candidates that are a point's (Query's layout): Kind::vertex_edge
  // or vertex_vertex, whose separation filter and pieces take the point's
  // own distances (separation_kind). Kind::edge_edge otherwise.
  Kind point_kind = Kind::edge_edge;
  double separation_of(std::size_t candidate) const {
    return min_distances != nullptr ? min_distances[candidate] : min_distance;
  }
};

// The filters a call asks for (the cubic baseline runs none: callers skip them).
inline FilterSettings filter_settings(const Options& options, const lab::Settings& lab) {
  const int asked = lab.filter_pieces;
  const int pieces = asked == 2 || asked == 4 || asked == 8 ? asked : 1;
  return {decider_of(options, lab) != Decider::fast, lab.sign_filter, lab.sign_filter_subdivision,
          lab.separation_filter, pieces, lab.swept_box_filter, options.min_distance > 0, options.min_distance};
}

// The settings for candidates of `kind`. A point kind's (vertex-edge,
// vertex-vertex: edge-edge queries with a zero-length edge) skip the sign
// filters, which cannot cull them (their cubic and normal vanish), and
// take the separation filter and its pieces with the point's own
// distances (docs/design.md §11).
inline FilterSettings settings_for(Kind kind, FilterSettings settings) {
  if (kind == Kind::vertex_edge || kind == Kind::vertex_vertex) {
    settings.sign = false;
    settings.point_kind = kind;
  }
  return settings;
}

// The kind whose distances the separation filter and its pieces take for
// a source of `kind` (Kind::vertex_face or edge_edge, the queries' layout).
inline Kind separation_kind(Kind kind, const FilterSettings& settings) {
  return kind == Kind::edge_edge ? settings.point_kind : kind;
}

// What each filter said of one query. The swept boxes run first, then the
// sign filter on what they keep; the separation filter only sees what both
// keep, the pieces what all three keep (at most one culls).
struct FilterVerdict {
  bool sign = false;
  bool separation = false;
  bool pieces = false;
  bool swept_box = false;
  // Of a query the pieces kept: bit j when piece j of FilterSettings::pieces
  // is free of contact (0 where the pieces did not run).
  std::uint8_t free_pieces = 0;
  bool culled() const { return sign || separation || pieces || swept_box; }
};

// The filters over [0, 1] for one query (any input: a non-finite or
// coincident one is never culled). The sign filter works on the query's
// differences in its own units when they lie in a window that keeps every
// product of three from overflow and from underflow that matters (the
// direct frame, error_bounds.hpp), else in the scaled frame; the separation
// filter always in the scaled frame. The lane kernels decide the same, lane
// for lane. With `within`, for the separation settings.min_distance.
FilterVerdict run_filters(Kind kind, const Query& query, const FilterSettings& settings);

// The sign filter alone, in the scaled frame.
bool sign_filter_culls(const ScaledQuery& query, bool certified, bool subdivide = true);

// The separation filter's error model: relative bound and absolute floor,
// and whether it applies at all (not when underflow was magnified too much to bound).
struct SeparationErrorModel {
  double relative;
  double floor;
  bool enabled;
};
SeparationErrorModel separation_error(double absolute_error, bool certified);

}  // namespace batchccd::reference

#pragma once

#include <optional>

#include "batchccd/query.hpp"

namespace batchccd::exact {

// Planar motion (docs/design.md §5a): when all eight points of a query lie
// exactly in one plane at t0 and at t1 (so at every t, each point an affine
// combination of its ends), or the points of each time share a coordinate
// (shares_coordinate below), a coordinate axis along which that plane
// projects one to one onto a coordinate plane; nullopt when they do not, or
// when this cheap test cannot tell (all points collinear, or coordinates
// outside the range where expansions are exact: the generic path decides
// those). Exact: axis planes by comparing one coordinate, tilted planes by
// orientation signs in expansion arithmetic (expansion.hpp), after a
// floating-point filter that rejects generic queries in a few operations.
std::optional<int> exact_plane_axis(const Query& query);

// Whether the four points at t0 share their coordinate `axis`, and the four
// at t1 theirs (perhaps another value: a plane moving along that axis, a
// sheet falling flat). Then every difference of points has that coordinate
// 0 at every t, so in the frame of x1 (where the planar path works) the
// motion stays in the axis plane, and dropping the coordinate keeps
// distances too. exact_plane_axis answers such an axis first.
bool shares_coordinate(const Query& query, int axis);

// The first axis whose coordinate the points of each time share, if any
// (exact_plane_axis's answer then), without its exact test for tilted
// planes: a cheap test where only axis planes will do.
std::optional<int> shared_axis(const Query& query);

}  // namespace batchccd::exact

#pragma once

#include <optional>

#include "batchccd/query.hpp"

namespace batchccd::exact {

// Planar motion (docs/design.md §5a): when all eight points of a query lie
// exactly in one plane at t0 and at t1 (so at every t, each point an affine
// combination of its ends), a coordinate axis along which that plane
// projects one to one onto a coordinate plane; nullopt when they do not, or
// when this cheap test cannot tell (all points collinear, or coordinates
// outside the range where expansions are exact: the generic path decides
// those). Exact: axis planes by comparing one coordinate, tilted planes by
// orientation signs in expansion arithmetic (expansion.hpp), after a
// floating-point filter that rejects generic queries in a few operations.
std::optional<int> exact_plane_axis(const Query& query);

}  // namespace batchccd::exact

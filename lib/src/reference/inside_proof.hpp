#pragma once

#include <array>

#include "batchccd/query.hpp"
#include "reference/ball.hpp"
#include "reference/bernstein.hpp"

namespace batchccd::reference {

// The positions x2..x4 relative to x1 over a time interval, each component a
// ball that holds every value it takes there (they move linearly).
using PositionBalls = std::array<Vector3<Ball>, 3>;

// The inside test of docs/design.md §5, certified over a whole time interval:
// true when, at every t of it, the primitives' projections along the common
// normal overlap strictly inside (VF: the vertex inside the triangle, all
// three edge functions positive; EE: both segment parameters strictly in
// (0, 1)). Together with a certified root of the coplanarity cubic in the
// interval, this proves a contact there without refining further.
bool certainly_inside(Kind kind, const PositionBalls& positions);

}  // namespace batchccd::reference

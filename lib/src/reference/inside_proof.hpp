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

// The opposite proof: true when, at every t of the interval, the
// projections certainly miss each other (VF: some edge function negative;
// EE: a segment parameter of the lines' meeting point outside [0, 1]). A
// contact without separation needs coplanarity and an overlap at the same
// time, so an interval where this holds is free of contact whatever the
// cubic's roots there. Degenerate primitives (n = 0) never pass it.
bool certainly_outside(Kind kind, const PositionBalls& positions);

}  // namespace batchccd::reference

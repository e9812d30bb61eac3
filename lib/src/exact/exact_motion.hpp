#pragma once

#include <array>

#include "batchccd/query.hpp"
#include "exact/polynomial.hpp"

namespace batchccd::exact {

// A query's motion without rounding. Every double is a dyadic rational, so
// multiplying all 24 coordinates by one power of two makes them integers;
// scaling and translating change no decision (docs/design.md §1), so the motion is
// taken in the frame of x1 (docs/design.md §1 numbering) and divided by the common
// factor of what remains:
//
//   relative[i](t) = (x_{i+2}(t) - x_1(t)) / g,  i = 0, 1, 2,
//
// each component a polynomial of degree at most 1 in t. Finite input only.
using RelativeMotion = std::array<PolynomialVector, 3>;

RelativeMotion exact_relative_motion(Kind kind, const Query& query);

}  // namespace batchccd::exact

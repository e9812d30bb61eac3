#pragma once

#include <array>
#include <optional>

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

// The query scaled by a power of two so that its largest coordinate lies in
// [1, 2): exact, and the same for the query scaled by any power of two, so
// what is computed from it does not depend on units. nullopt when every
// coordinate is zero or a nonzero one is below 2^floor_exponent of the
// largest: floating-point expansions of products of such coordinates could
// underflow (the callers' bounds say how far down they may reach).
std::optional<Query> normalized(const Query& query, int floor_exponent);

}  // namespace batchccd::exact

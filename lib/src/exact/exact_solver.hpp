#pragma once

#include "batchccd/query.hpp"

namespace batchccd::exact {

// The exact stage locates the first contact in a time interval of width
// 2^-kToiBits = 2^-40 < 1e-12 of the step.
inline constexpr unsigned long kToiBits = 40;

struct ExactOutcome {
  bool hit = false;
  // When hit: a double at most 2^-kToiBits (plus 2^-63) before the first
  // contact and never after it.
  double toi = 0;
  // An iteration bound was reached (the mathematics says it cannot be):
  // reported as a hit at time 0, never a false negative.
  bool bound_reached = false;
};

// Decides one query exactly (docs/design.md §6, mode `exact`): the primitives,
// closed sets, touch at some t in [0, 1]. Candidate times are 0, 1 and the
// roots in (0, 1) of the polynomials the contact condition depends on,
// isolated exactly; the first candidate at which the condition holds is the
// first contact. need_toi = false stops refining once the decision is known.
// Finite input only. Work is bounded by the degrees and bit sizes of the
// polynomials (see root_isolation.hpp).
// Contacts after tmax (in (0, 1]) do not count: the candidates after it are
// compared with it exactly.
// Floating-point expansions decide first where they can
// (expansion_stage.hpp); GMP integers decide the rest.
ExactOutcome solve_exactly(Kind kind, const Query& query, bool need_toi, double tmax = 1.0);

// The same with integers alone.
ExactOutcome solve_with_integers(Kind kind, const Query& query, bool need_toi, double tmax = 1.0);

}  // namespace batchccd::exact

#pragma once

#include <optional>

#include "batchccd/query.hpp"
#include "exact/exact_solver.hpp"

// The exact stage's first try (docs/design.md §6a): the same decisions and
// TOIs as exact integers give, computed with floating-point expansions,
// which are exact too but cost microseconds where GMP costs hundreds. They
// cover the generic case (the coplanarity cubic not identically zero, its
// roots in (0, 1) at least 2^-40 apart) and planar motion in a plane
// exact_plane_axis certifies (the orientations' roots likewise apart, or a
// double root). A contact exactly on an edge or a corner is settled by the
// sign of a remainder sequence at the root. Anything else (other motion with a vanishing cubic, clustered
// roots, a triangle flat or edges parallel at the contact, coordinates
// spread over more than 2^80, a tmax off the 2^-100 grid) answers nullopt,
// and the integers decide.
namespace batchccd::exact {

// What solve_exactly decides, bit for bit (hit, and the TOI on the same
// 2^-40 grid), or nullopt.
std::optional<ExactOutcome> solve_with_expansions(Kind kind, const Query& query, bool need_toi,
                                                  double tmax);

// What first_root_lower_bound answers, or nullopt: a lower bound within
// 2^-40 of the first root of the coplanarity cubic in [low, high] (never
// below low).
std::optional<double> first_root_with_expansions(Kind kind, const Query& query, double low, double high);

}  // namespace batchccd::exact

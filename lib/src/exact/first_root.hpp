#pragma once

#include <optional>

#include "batchccd/query.hpp"

namespace batchccd::exact {

// The TOI of a contact the certified path proved but could not locate to
// 2^-kToiBits in floating point: there the first contact is the first root
// of the coplanarity cubic d(t) (docs/design.md §2) in the dyadic interval
// [low, high] (d certainly changes sign over it, every earlier time is
// excluded, and the primitives certainly overlap wherever d vanishes in it).
// Isolates that root exactly and returns a lower bound within
// 2^-kToiBits of it; nullopt when [low, high] is not a dyadic interval or an
// iteration bound was reached (the full exact stage then decides).
// Floating-point expansions answer first where they can
// (expansion_stage.hpp), GMP integers otherwise.
std::optional<double> first_root_lower_bound(Kind kind, const Query& query, double low,
                                             double high);

// The same with integers alone.
std::optional<double> first_root_with_integers(Kind kind, const Query& query, double low, double high);

}  // namespace batchccd::exact

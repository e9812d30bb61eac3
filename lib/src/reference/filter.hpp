#pragma once

#include "reference/scaled_query.hpp"

namespace batchccd::reference {

// Which lane filters run, and how (DESIGN.md §2).
struct FilterSettings {
  bool certified = true;   // cull only when error bounds prove it; else plain signs (fast mode)
  bool sign = true;        // the Bernstein sign test on the coplanarity cubic
  bool separation = true;  // distance at t = 0 against the largest displacement
};

// What each filter said of one query (both may cull it).
struct FilterVerdict {
  bool sign = false;
  bool separation = false;
  bool culled() const { return sign || separation; }
};

// The filters over [0, 1] for one finite, non-coincident query.
FilterVerdict run_filters(Kind kind, const ScaledQuery& query, const FilterSettings& settings);

// The sign filter alone.
bool sign_filter_culls(const ScaledQuery& query, bool certified);

// The separation filter's error model: relative bound and absolute floor,
// and whether it applies at all (not when underflow was magnified too much to bound).
struct SeparationErrorModel {
  double relative;
  double floor;
  bool enabled;
};
SeparationErrorModel separation_error(double absolute_error, bool certified);

}  // namespace batchccd::reference

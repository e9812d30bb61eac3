#pragma once

#include "reference/scaled_query.hpp"

namespace batchccd::reference {

// The sign filter over [0, 1] for one query (DESIGN.md §2). certified: cull
// only when the error bounds prove no root; otherwise plain signs (fast mode).
bool sign_filter_culls(const ScaledQuery& query, bool certified);

}  // namespace batchccd::reference

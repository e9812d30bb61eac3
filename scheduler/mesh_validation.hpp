#pragma once

#include "batchccd/batch.hpp"

namespace batchccd {

// Throws std::invalid_argument naming the first bad item: matrices that are
// not n x 3 / m x 3 (zero rows: any column count) with positions_t0 and
// positions_t1 of equal row counts, or an index out of range in a face or in
// any candidate list. Runs in the caller's task arena.
void check_mesh(const MeshView& mesh, const Candidates& candidates);

}  // namespace batchccd

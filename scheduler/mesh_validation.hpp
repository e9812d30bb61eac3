#pragma once

#include "batchccd/batch.hpp"

namespace batchccd {

// Throws std::invalid_argument naming the first bad item: matrices that are
// not n x 3 / m x 3 of matching sizes, or an index out of range.
void check_mesh(const MeshView& mesh, const Candidates& candidates);

}  // namespace batchccd

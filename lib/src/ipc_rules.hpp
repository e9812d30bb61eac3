#pragma once

#include "batchccd/query.hpp"

// ipc-toolkit's rules around one narrow-phase query (ipc.hpp), shared by
// the per-query calls and the collision-free step over a mesh.
namespace batchccd::ipc::rules {

// The largest part of a pair's gap the first query keeps free (ipc-toolkit's
// cap on the effective separation above min_distance).
inline constexpr double kLargestRescalingSeparation = 1e-4;

// Throws std::invalid_argument naming `call` and the argument unless
// min_distance >= 0 and finite, tmax in [0, 1], tolerance positive and
// finite, conservative_rescaling in (0, 1].
void require_arguments(const char* call, double min_distance, double tmax, double tolerance,
                       double conservative_rescaling);

// The decision for one query whose arguments were checked: the toi a
// step may take (true), or no contact that counts within [0, tmax]
// (false). toi is written only when true.
bool decide(Kind kind, const Query& query, double& toi, double min_distance, double tmax, double tolerance,
            long max_iterations, double conservative_rescaling);

}  // namespace batchccd::ipc::rules

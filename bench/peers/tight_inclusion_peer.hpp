#pragma once

#include "batchccd/query.hpp"

// Tight Inclusion (Wang et al. 2021, double precision) as a benchmark peer
// for the collision-free step: one query driven as ipc-toolkit's
// TightInclusionCCD drives ticcd::vertexFaceCCD and ticcd::edgeEdgeCCD.
// Built only when the bench is configured with
// -DBATCHCCD_TIGHT_INCLUSION_DIR=<a checkout of its public sources>
// (bench/CMakeLists.txt); its code is never part of this repository. A
// shared library of its own that exports these two calls only: Tight
// Inclusion is compiled with -march=native, and Eigen's inline functions
// compiled so must not stand in for batchccd's (their alignment differs).
#define BATCHCCD_PEER_EXPORT __attribute__((visibility("default")))

namespace batchccd::peers {

// True when this build has Tight Inclusion.
BATCHCCD_PEER_EXPORT bool tight_inclusion_available();

// ipc-toolkit's rules around one query, with Tight Inclusion as the narrow
// phase (the facts ipc.hpp lists, here with ipc-toolkit's own choices): no
// motion -> the initial-distance check; an initial distance at or below
// min_distance -> toi 0; else Tight Inclusion with the effective separation
// min_distance + min((1 - rescaling)(d0 - min_distance), 1e-4), distance
// tolerance min(d0 / 2, tolerance), automatic rounding-error filters and
// max_iterations; a toi below 1e-6 is asked again at min_distance with
// no_zero_toi and no iteration limit, and rescaled. Vertex-edge and
// vertex-vertex queries are the degenerate edge-edge queries they are
// stored as (Query), as ipc-toolkit asks them. `initial_distance`: the
// primitives' distance at t = 0 (ipc-toolkit's own distance functions;
// batchccd::squared_distance gives it). Returns whether there is a contact
// that counts, writing toi only then. Throws std::logic_error when
// !tight_inclusion_available().
BATCHCCD_PEER_EXPORT bool tight_inclusion_ipc_ccd(Kind kind, const Query& query, double initial_distance,
                                                  double& toi, double min_distance, double tmax, double tolerance,
                                                  long max_iterations, double conservative_rescaling);

}  // namespace batchccd::peers

#pragma once

// ipc-toolkit's collision-free step (ipc::compute_collision_free_stepsize)
// as one batch call over the candidates a broad phase found:
//
//   const double step = batchccd::ipc::collision_free_stepsize(
//       {V0, V1, faces}, candidates, min_distance);
//   // V = V0 + step * (V1 - V0) keeps every candidate pair apart
//
// Each candidate is decided as the per-query calls of ipc.hpp decide it
// (ipc-toolkit's rules: the initial-distance check, the effective
// separation, the small-toi retry and its rescaling), with tmax the
// earliest toi found so far, and the call returns the minimum over the
// candidates (1 when none counts). The lane filters first cull, at the
// largest separation any candidate may ask for (min_distance + 1e-4 +
// tolerance), every candidate that certainly stays farther than that over
// the step: those are the candidates the per-query call answers with no
// contact, so the result is the minimum of the per-query calls, at lane
// speed. A 2D mesh (positions n x 2) is read as z = 0, as ipc-toolkit
// reads 2D meshes.
//
// Candidates are filtered and asked batch by batch in a shrinking window:
// tmax just past the earliest step found so far, divided by the rescaling
// (a retried step is rescaled below its contact) plus twice the TOI
// tolerance (a TOI lies up to one before its contact). Once that window is
// below 1/16 of the step, the filters cull over the window's part of the
// step alone (the first 16^-1, 16^-2 or 16^-3), where nearly every
// candidate is culled by the first test. The result does not depend on the
// thread count: a candidate whose step counts (below the earliest so far)
// gets the step it gets over [0, 1] (tests/test_shrinking_window.cpp), so
// the call returns the minimum of the per-candidate answers whichever order
// threads find them in (docs/design.md §12). Once a step of 0 is found (a
// pair within min_distance at the start, or a coordinate not finite) the
// candidates left are not asked, only their ids checked: nothing lowers 0,
// so only the work done depends on order.
//
// Bad input: std::invalid_argument naming the argument, as ipc.hpp's calls
// and mesh_ccd (batch.hpp) refuse it, before anything is evaluated. A NaN
// or infinite coordinate in a candidate makes the step 0.
#include "batchccd/batch.hpp"
#include "batchccd/ipc.hpp"

namespace batchccd::ipc {

// threads: as Options::threads (0: every processor the process may use).
double collision_free_stepsize(const MeshView& mesh, const CandidateLists& candidates, double min_distance = 0.0,
                               double tolerance = DEFAULT_CCD_TOLERANCE,
                               long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                               double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING, int threads = 0);

// With the settings of a NarrowPhase, as ipc-toolkit passes its narrow phase.
inline double collision_free_stepsize(const MeshView& mesh, const CandidateLists& candidates, double min_distance,
                                      const NarrowPhase& narrow_phase, int threads = 0) {
  return collision_free_stepsize(mesh, candidates, min_distance, narrow_phase.tolerance,
                                 narrow_phase.max_iterations, narrow_phase.conservative_rescaling, threads);
}

}  // namespace batchccd::ipc

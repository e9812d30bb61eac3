#pragma once

// Per-query calls shaped like the common CCD interfaces, so that a project
// calling Tight Inclusion (ticcd::vertexFaceCCD / edgeEdgeCCD) or
// ipc-toolkit's narrow phase (ipc::point_triangle_ccd / edge_edge_ccd)
// switches by changing one call: eight points, the time of impact written to
// `toi`, the step limit `tmax`, a distance `tolerance`, an iteration budget;
// true when the primitives may touch in [0, tmax].
//
//   ipc::point_triangle_ccd(p0, a0, b0, c0, p1, a1, b1, c1, toi,
//                           /*min_distance=*/0, tmax, tolerance, max_iterations);
//   ticcd::vertexFaceCCD(p0, a0, b0, c0, p1, a1, b1, c1, err, /*ms=*/0, toi,
//                        tolerance, tmax, max_iterations, output_tolerance);
// become
//   batchccd::compat::vertex_face_ccd(p0, a0, b0, c0, p1, a1, b1, c1, toi,
//                                     tmax, tolerance, max_iterations);
//
// Differences worth knowing when switching:
// - No minimum separation (ipc's min_distance, Tight Inclusion's ms): the
//   contact is at distance 0 (up to `tolerance`). Calls that pass one > 0
//   have no equivalent here.
// - No `err` filter and no output_tolerance: the rounding error is bounded
//   per query inside the library, and the TOI precision is fixed (below).
// - No conservative_rescaling: `toi` is already a lower bound of the first
//   contact time; a caller that wants a safety margin scales it itself.
// - The argument order is ipc-toolkit's (tmax before tolerance); Tight
//   Inclusion's puts tolerance first.
//
// The native calls in ccd.hpp offer every knob (Options); these use the
// defaults of Options except where stated.

#include <cstdint>

#include "batchccd/query.hpp"

namespace batchccd::compat {

// Tight Inclusion's and ipc-toolkit's default distance tolerance.
inline constexpr double default_tolerance = 1e-6;
// Options::max_iterations' default.
inline constexpr std::int64_t default_max_iterations = std::int64_t{1} << 20;
// Pass as max_iterations for no limit (the value both libraries use).
inline constexpr std::int64_t no_max_iterations = -1;

// Vertex p against triangle (a, b, c); every point moves linearly from its
// _t0 to its _t1 position over t in [0, 1]. Decided in conservative mode
// (Mode::conservative): never a false negative.
//
// Returns true when the primitives touch at some t in [0, tmax], and then
// sets `toi` to a lower bound of the first contact time, in the caller's
// time units (the same t as the points', so 0 <= toi <= tmax); returns false
// and sets `toi` to +infinity otherwise.
//
// tmax: the part of the step that counts, in [0, 1] (default 1: the whole
//   step). The query is solved over [0, 1] on the points exactly as given
//   (no rounded intermediate positions, so the answer stays certified) and
//   a contact counts when its lower bound `toi` is <= tmax. A first contact
//   later than tmax but within Options::toi_tolerance (1e-7) of it can still
//   be reported: a false positive, never a false negative.
// tolerance: a distance in the caller's length units, > 0 (default 1e-6).
//   Conservative mode's promise in these units: primitives that never touch
//   are reported as a contact only when they come within `tolerance` of
//   each other (in every coordinate). Smaller is tighter and may cost more
//   iterations. It becomes Options::tolerance = tolerance / extent,
//   rounded down, where extent is the query's largest coordinate spread
//   (max - min of one coordinate over the four points, at t0 or at t1): the
//   relative tolerance Options applies, times the size the query is scaled
//   by, is then <= tolerance.
//   When the four points coincide, Options' default is kept. Unlike Tight
//   Inclusion's tolerance it does not set the TOI precision, which is
//   Options::toi_tolerance (1e-7 of the unit step).
// max_iterations: boxes the floating-point solver may examine for this
//   query (Options::max_iterations; default 2^20; negative: no limit),
//   capping Options::exact_stage_iterations (1,024). A query it cannot
//   settle within them is settled with exact arithmetic (Mode::exact's
//   exact stage), never guessed.
//
// Bad input: throws std::invalid_argument when tmax is not in [0, 1] or
// tolerance is not a positive finite number (NaN included). A NaN or
// infinite coordinate returns true with toi = 0, so that a caller that
// limits its step by toi never steps into a contact.
bool vertex_face_ccd(const Vec3& p_t0, const Vec3& a_t0, const Vec3& b_t0, const Vec3& c_t0,
                     const Vec3& p_t1, const Vec3& a_t1, const Vec3& b_t1, const Vec3& c_t1,
                     double& toi, double tmax = 1.0, double tolerance = default_tolerance,
                     std::int64_t max_iterations = default_max_iterations);

// Edge (ea0, ea1) against edge (eb0, eb1); everything as vertex_face_ccd.
bool edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0,
                   const Vec3& eb1_t0, const Vec3& ea0_t1, const Vec3& ea1_t1,
                   const Vec3& eb0_t1, const Vec3& eb1_t1, double& toi, double tmax = 1.0,
                   double tolerance = default_tolerance,
                   std::int64_t max_iterations = default_max_iterations);

}  // namespace batchccd::compat

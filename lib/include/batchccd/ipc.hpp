#pragma once

// Per-query calls with ipc-toolkit's names, argument order, defaults and
// meaning (ipc::point_point_ccd, point_edge_ccd, edge_edge_ccd,
// point_triangle_ccd in ipc/ccd/ccd.hpp), so that a port compiles and means
// the same: replace `ipc::` by `batchccd::ipc::`.
//
//   bool hit = batchccd::ipc::point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1,
//                                                t2_t1, toi, min_distance, tmax);
//
// Each call does what ipc-toolkit's does around Tight Inclusion, with
// batchccd's conservative mode (Mode::conservative: never a false negative)
// in its place:
// - no motion (every point's t0 equals its t1): false;
// - the initial distance d0 at or below min_distance: true, toi = 0;
// - otherwise it asks for the first time the distance comes down to
//   min_distance + min((1 - conservative_rescaling) d0, 1e-4) within
//   [0, tmax], with the distance tolerance min(tolerance, d0 / 2); when that
//   toi is below 1e-6, it asks again with min_distance alone and scales the
//   toi by conservative_rescaling.
// Returns true when a contact counts, with toi a lower bound of the first
// time the primitives come within min_distance (so a step to toi never
// brings them closer than min_distance); false otherwise, toi unchanged.
//
// Differences from ipc-toolkit worth knowing:
// - The distance is Euclidean. Tight Inclusion tests a box against the cube
//   [-ms, ms]^3 and so may report pairs up to sqrt(3) min_distance apart.
// - tolerance is a distance in the caller's units, as there; it bounds how
//   far beyond min_distance a reported pair can be (Options::tolerance), not
//   how precise toi is: toi lies at most Options::toi_tolerance (1e-7) of
//   the step before the first contact within the tolerance.
// - max_iterations: the solver's box budget (Options::max_iterations); a
//   query that exhausts it is reported as a contact, never missed. -1: none.
//
// Bad input: std::invalid_argument when min_distance is negative or not
// finite, tmax is not in [0, 1], tolerance is not positive and finite or
// conservative_rescaling is not in (0, 1]. A NaN or infinite coordinate
// returns true with toi = 0.
#include "batchccd/query.hpp"

namespace batchccd::ipc {

// ipc-toolkit's defaults.
inline constexpr double DEFAULT_CCD_TOLERANCE = 1e-6;
inline constexpr long DEFAULT_CCD_MAX_ITERATIONS = 10'000'000L;
inline constexpr double DEFAULT_CCD_CONSERVATIVE_RESCALING = 0.8;

bool point_point_ccd(const Vec3& p0_t0, const Vec3& p1_t0, const Vec3& p0_t1, const Vec3& p1_t1,
                     double& toi, double min_distance = 0.0, double tmax = 1.0,
                     double tolerance = DEFAULT_CCD_TOLERANCE,
                     long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                     double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING);

bool point_edge_ccd(const Vec3& p_t0, const Vec3& e0_t0, const Vec3& e1_t0, const Vec3& p_t1,
                    const Vec3& e0_t1, const Vec3& e1_t1, double& toi, double min_distance = 0.0,
                    double tmax = 1.0, double tolerance = DEFAULT_CCD_TOLERANCE,
                    long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                    double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING);

bool edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0, const Vec3& eb1_t0,
                   const Vec3& ea0_t1, const Vec3& ea1_t1, const Vec3& eb0_t1, const Vec3& eb1_t1,
                   double& toi, double min_distance = 0.0, double tmax = 1.0,
                   double tolerance = DEFAULT_CCD_TOLERANCE,
                   long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                   double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING);

bool point_triangle_ccd(const Vec3& p_t0, const Vec3& t0_t0, const Vec3& t1_t0, const Vec3& t2_t0,
                        const Vec3& p_t1, const Vec3& t0_t1, const Vec3& t1_t1, const Vec3& t2_t1,
                        double& toi, double min_distance = 0.0, double tmax = 1.0,
                        double tolerance = DEFAULT_CCD_TOLERANCE,
                        long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                        double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING);

}  // namespace batchccd::ipc

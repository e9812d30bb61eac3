#pragma once

// Per-query calls with the names, argument order and defaults of
// ipc-toolkit's free functions (ipc::point_point_ccd, point_edge_ccd,
// edge_edge_ccd, point_triangle_ccd in ipc/ccd/ccd.hpp, version 1.2) and
// their meaning, which TightInclusionCCD's members keep from 1.3 on (with
// tolerance, max_iterations and conservative_rescaling as its fields), so
// that a port compiles and means the same: replace `ipc::` by
// `batchccd::ipc::`.
//
//   bool hit = batchccd::ipc::point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1,
//                                                t2_t1, toi, min_distance, tmax);
//
// Points: Eigen vectors of doubles (Vector3d, a Map, Ref, block, VectorXd,
// an expression). point_point_ccd and point_edge_ccd take 2D or 3D points,
// all of one length, as ipc-toolkit's VectorMax3d: a 2D point is the 3D
// point with z = 0. edge_edge_ccd and point_triangle_ccd take 3D points
// only. A length fixed at compile time that does not fit (a Vector2d for a
// triangle, a Vector2d with a Vector3d, a Vector4d) does not compile; a
// length known only at run time that does not fit throws
// std::invalid_argument naming the call and the argument. No call reads
// past a vector's end.
//
// Each call does what ipc-toolkit's does around Tight Inclusion, with
// batchccd's conservative mode (Mode::conservative: never a false negative)
// in its place. With d0 the initial distance and s = conservative_rescaling:
// - d0 <= min_distance: true, toi = 0 (with or without motion);
// - no motion (every point's t0 equals its t1), or tmax = 0: false;
// - otherwise it asks for the first time in [0, tmax] the distance comes
//   down to min_distance + min((1 - s)(d0 - min_distance), 1e-4), with the
//   distance tolerance min(tolerance, d0 / 2) and max_iterations;
// - when that toi is below 1e-6, it asks again with min_distance itself and
//   no iteration limit, and returns s times that toi (false if that finds no
//   contact). As d0 > min_distance the first contact comes after 0, and
//   this toi is never 0 (Tight Inclusion's no_zero_toi; at least the
//   smallest positive double): a lower bound of 0 is asked once more with
//   time resolved to 2^-45 of the step (Options::toi_tolerance's floor).
//   When that still returns 0 (the first contact, or a near miss within the
//   tolerance, lies in the first 2^-45 of the step, below what the solver
//   resolves), toi is s (d0 - min_distance) / (2 v), v the largest
//   displacement of one primitive's points plus that of the other's: the
//   distance falls no faster than v, so the first contact comes no earlier
//   than (d0 - min_distance) / v, and half that leaves room for rounding. A
//   lower bound as far as d0, computed in double precision, is exact.
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
//   Point kinds and motion in an axis plane are decided first by a bounded
//   search of their own, which it does not limit.
// - Tight Inclusion's no_zero_toi may shrink min_distance itself to get a
//   toi above 0; here the separation stays the caller's (above).
//
// Bad input: std::invalid_argument when min_distance is negative or not
// finite, tmax is not in [0, 1], tolerance is not positive and finite or
// conservative_rescaling is not in (0, 1]. A NaN or infinite coordinate
// returns true with toi = 0.
//
// NarrowPhase (at the end) holds tolerance, max_iterations and
// conservative_rescaling as TightInclusionCCD does, for code that passes a
// narrow phase around (ipc-toolkit's compute_collision_free_stepsize).
// The whole collision-free step over a mesh's candidates is one batch call:
// collision_free_stepsize (ipc_stepsize.hpp).
#include <span>

#include "batchccd/point_arguments.hpp"
#include "batchccd/query.hpp"

namespace batchccd::ipc {

// ipc-toolkit's defaults.
inline constexpr double DEFAULT_CCD_TOLERANCE = 1e-6;
inline constexpr long DEFAULT_CCD_MAX_ITERATIONS = 10'000'000L;
inline constexpr double DEFAULT_CCD_CONSERVATIVE_RESCALING = 0.8;

// The points of point_point_ccd and point_edge_ccd: all 2D or all 3D; of
// edge_edge_ccd and point_triangle_ccd: 3D (point_arguments.hpp, shared
// with ccd.hpp's calls).
using batchccd::PlanarOrSpatialPoints;
using batchccd::SpatialPoints;

namespace detail {

using batchccd::detail::PointArgument;
using batchccd::detail::read_points;

// The calls below, once their points are read: `points` holds the t0
// points, then the t1 points, in the call's order (make_query's). Checks
// the lengths (std::invalid_argument naming `call` and the argument), then
// the other arguments, then decides.
bool ccd(const char* call, Kind kind, std::span<const PointArgument> points, double& toi, double min_distance,
         double tmax, double tolerance, long max_iterations, double conservative_rescaling);

}  // namespace detail

template <class P0, class P1, class P2, class P3>
  requires PlanarOrSpatialPoints<P0, P1, P2, P3>
bool point_point_ccd(const P0& p0_t0, const P1& p1_t0, const P2& p0_t1, const P3& p1_t1, double& toi,
                     double min_distance = 0.0, double tmax = 1.0, double tolerance = DEFAULT_CCD_TOLERANCE,
                     long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                     double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING) {
  const auto points = detail::read_points({"p0_t0", "p1_t0", "p0_t1", "p1_t1"}, p0_t0, p1_t0, p0_t1, p1_t1);
  return detail::ccd("batchccd::ipc::point_point_ccd", Kind::vertex_vertex, points, toi, min_distance, tmax,
                     tolerance, max_iterations, conservative_rescaling);
}

template <class P0, class P1, class P2, class P3, class P4, class P5>
  requires PlanarOrSpatialPoints<P0, P1, P2, P3, P4, P5>
bool point_edge_ccd(const P0& p_t0, const P1& e0_t0, const P2& e1_t0, const P3& p_t1, const P4& e0_t1,
                    const P5& e1_t1, double& toi, double min_distance = 0.0, double tmax = 1.0,
                    double tolerance = DEFAULT_CCD_TOLERANCE, long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                    double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING) {
  const auto points = detail::read_points({"p_t0", "e0_t0", "e1_t0", "p_t1", "e0_t1", "e1_t1"}, p_t0, e0_t0, e1_t0,
                                          p_t1, e0_t1, e1_t1);
  return detail::ccd("batchccd::ipc::point_edge_ccd", Kind::vertex_edge, points, toi, min_distance, tmax, tolerance,
                     max_iterations, conservative_rescaling);
}

template <class P0, class P1, class P2, class P3, class P4, class P5, class P6, class P7>
  requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
bool edge_edge_ccd(const P0& ea0_t0, const P1& ea1_t0, const P2& eb0_t0, const P3& eb1_t0, const P4& ea0_t1,
                   const P5& ea1_t1, const P6& eb0_t1, const P7& eb1_t1, double& toi, double min_distance = 0.0,
                   double tmax = 1.0, double tolerance = DEFAULT_CCD_TOLERANCE,
                   long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                   double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING) {
  const auto points =
      detail::read_points({"ea0_t0", "ea1_t0", "eb0_t0", "eb1_t0", "ea0_t1", "ea1_t1", "eb0_t1", "eb1_t1"}, ea0_t0,
                          ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1);
  return detail::ccd("batchccd::ipc::edge_edge_ccd", Kind::edge_edge, points, toi, min_distance, tmax, tolerance,
                     max_iterations, conservative_rescaling);
}

template <class P0, class P1, class P2, class P3, class P4, class P5, class P6, class P7>
  requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
bool point_triangle_ccd(const P0& p_t0, const P1& t0_t0, const P2& t1_t0, const P3& t2_t0, const P4& p_t1,
                        const P5& t0_t1, const P6& t1_t1, const P7& t2_t1, double& toi, double min_distance = 0.0,
                        double tmax = 1.0, double tolerance = DEFAULT_CCD_TOLERANCE,
                        long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                        double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING) {
  const auto points = detail::read_points({"p_t0", "t0_t0", "t1_t0", "t2_t0", "p_t1", "t0_t1", "t1_t1", "t2_t1"},
                                          p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1);
  return detail::ccd("batchccd::ipc::point_triangle_ccd", Kind::vertex_face, points, toi, min_distance, tmax,
                     tolerance, max_iterations, conservative_rescaling);
}

// ipc-toolkit's TightInclusionCCD (1.3 on) as a plain object: its
// constructor, defaults and public members, and its four calls, each
// forwarding to the free function of the same name with the members. The
// constructor refuses the tolerance and conservative_rescaling the calls
// refuse (std::invalid_argument naming the member and value); as members
// may change afterwards, each call checks them again.
//
// It is no ipc::NarrowPhaseCCD: batchccd does not depend on ipc-toolkit.
// To pass it to ipc::compute_collision_free_stepsize (its narrow_phase_ccd
// argument), wrap it in a class that forwards each virtual call:
//
//   class BatchccdCCD : public ipc::NarrowPhaseCCD {
//    public:
//     explicit BatchccdCCD(const batchccd::ipc::NarrowPhase& settings = batchccd::ipc::NarrowPhase())
//         : narrow_phase(settings) {}
//
//     bool point_point_ccd(const ipc::VectorMax3d& p0_t0, const ipc::VectorMax3d& p1_t0,
//                          const ipc::VectorMax3d& p0_t1, const ipc::VectorMax3d& p1_t1, double& toi,
//                          const double min_distance = 0.0, const double tmax = 1.0) const override {
//       return narrow_phase.point_point_ccd(p0_t0, p1_t0, p0_t1, p1_t1, toi, min_distance, tmax);
//     }
//     bool point_edge_ccd(const ipc::VectorMax3d& p_t0, const ipc::VectorMax3d& e0_t0,
//                         const ipc::VectorMax3d& e1_t0, const ipc::VectorMax3d& p_t1,
//                         const ipc::VectorMax3d& e0_t1, const ipc::VectorMax3d& e1_t1, double& toi,
//                         const double min_distance = 0.0, const double tmax = 1.0) const override {
//       return narrow_phase.point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, toi, min_distance, tmax);
//     }
//     bool point_triangle_ccd(const Eigen::Vector3d& p_t0, const Eigen::Vector3d& t0_t0,
//                             const Eigen::Vector3d& t1_t0, const Eigen::Vector3d& t2_t0,
//                             const Eigen::Vector3d& p_t1, const Eigen::Vector3d& t0_t1,
//                             const Eigen::Vector3d& t1_t1, const Eigen::Vector3d& t2_t1, double& toi,
//                             const double min_distance = 0.0, const double tmax = 1.0) const override {
//       return narrow_phase.point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, toi,
//                                              min_distance, tmax);
//     }
//     bool edge_edge_ccd(const Eigen::Vector3d& ea0_t0, const Eigen::Vector3d& ea1_t0,
//                        const Eigen::Vector3d& eb0_t0, const Eigen::Vector3d& eb1_t0,
//                        const Eigen::Vector3d& ea0_t1, const Eigen::Vector3d& ea1_t1,
//                        const Eigen::Vector3d& eb0_t1, const Eigen::Vector3d& eb1_t1, double& toi,
//                        const double min_distance = 0.0, const double tmax = 1.0) const override {
//       return narrow_phase.edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1, toi,
//                                         min_distance, tmax);
//     }
//
//     batchccd::ipc::NarrowPhase narrow_phase;
//   };
//
// These are 1.3's parameter types. From 1.4 on ipc-toolkit spells them
// Eigen::ConstRef<ipc::VectorMax3d> and Eigen::ConstRef<Eigen::Vector3d>
// (const Eigen::Ref<const T>&); the bodies stay the same. Where
// NarrowPhaseCCD has a conservative_rescaling field of its own (ipc-toolkit
// after 1.5.0, for plane-vertex CCD), set it from narrow_phase's in the
// constructor. tests/test_ipc.cpp compiles this adapter against stand-ins
// of both bases.
class NarrowPhase {
 public:
  explicit NarrowPhase(double tolerance = DEFAULT_CCD_TOLERANCE, long max_iterations = DEFAULT_CCD_MAX_ITERATIONS,
                       double conservative_rescaling = DEFAULT_CCD_CONSERVATIVE_RESCALING);

  template <class P0, class P1, class P2, class P3>
    requires PlanarOrSpatialPoints<P0, P1, P2, P3>
  bool point_point_ccd(const P0& p0_t0, const P1& p1_t0, const P2& p0_t1, const P3& p1_t1, double& toi,
                       double min_distance = 0.0, double tmax = 1.0) const {
    return batchccd::ipc::point_point_ccd(p0_t0, p1_t0, p0_t1, p1_t1, toi, min_distance, tmax, tolerance,
                                          max_iterations, conservative_rescaling);
  }

  template <class P0, class P1, class P2, class P3, class P4, class P5>
    requires PlanarOrSpatialPoints<P0, P1, P2, P3, P4, P5>
  bool point_edge_ccd(const P0& p_t0, const P1& e0_t0, const P2& e1_t0, const P3& p_t1, const P4& e0_t1,
                      const P5& e1_t1, double& toi, double min_distance = 0.0, double tmax = 1.0) const {
    return batchccd::ipc::point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, toi, min_distance, tmax, tolerance,
                                         max_iterations, conservative_rescaling);
  }

  template <class P0, class P1, class P2, class P3, class P4, class P5, class P6, class P7>
    requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
  bool edge_edge_ccd(const P0& ea0_t0, const P1& ea1_t0, const P2& eb0_t0, const P3& eb1_t0, const P4& ea0_t1,
                     const P5& ea1_t1, const P6& eb0_t1, const P7& eb1_t1, double& toi, double min_distance = 0.0,
                     double tmax = 1.0) const {
    return batchccd::ipc::edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1, toi,
                                        min_distance, tmax, tolerance, max_iterations, conservative_rescaling);
  }

  template <class P0, class P1, class P2, class P3, class P4, class P5, class P6, class P7>
    requires SpatialPoints<P0, P1, P2, P3, P4, P5, P6, P7>
  bool point_triangle_ccd(const P0& p_t0, const P1& t0_t0, const P2& t1_t0, const P3& t2_t0, const P4& p_t1,
                          const P5& t0_t1, const P6& t1_t1, const P7& t2_t1, double& toi, double min_distance = 0.0,
                          double tmax = 1.0) const {
    return batchccd::ipc::point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, toi,
                                             min_distance, tmax, tolerance, max_iterations, conservative_rescaling);
  }

  double tolerance;
  long max_iterations;
  double conservative_rescaling;
};

}  // namespace batchccd::ipc

#include "peers/tight_inclusion_peer.hpp"

#include <algorithm>
#include <stdexcept>

#ifdef BATCHCCD_HAVE_TIGHT_INCLUSION
#include <tight_inclusion/ccd.hpp>
#endif

namespace batchccd::peers {

#ifdef BATCHCCD_HAVE_TIGHT_INCLUSION

bool tight_inclusion_available() { return true; }

bool tight_inclusion_ipc_ccd(Kind kind, const Query& query, double initial_distance, double& toi,
                             double min_distance, double tmax, double tolerance, long max_iterations,
                             double conservative_rescaling) {
  // ipc-toolkit's constants (ipc/ccd/tight_inclusion_ccd.cpp, ipc/ccd/ccd.hpp).
  constexpr double kInitialDistanceToleranceScale = 0.5, kSmallToi = 1e-6, kLargestRescalingSeparation = 1e-4;
  constexpr long kUnlimitedIterations = -1;
  const auto& p = query.points;
  const bool moves = !std::equal(p.begin(), p.begin() + 4, p.begin() + 4);
  if (!moves || initial_distance <= min_distance) {  // the initial-distance check
    if (initial_distance > min_distance) return false;
    toi = 0;
    return true;
  }
  const double distance_tolerance = std::min(kInitialDistanceToleranceScale * initial_distance, tolerance);
  const auto ask = [&](double separation, bool no_zero_toi, double& found) {
    const long iterations = no_zero_toi ? kUnlimitedIterations : max_iterations;
    const Eigen::Array3d automatic_filters = Eigen::Array3d::Constant(-1);
    double output_tolerance = 0;
    if (kind == Kind::vertex_face)
      return ticcd::vertexFaceCCD(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], automatic_filters, separation,
                                  found, distance_tolerance, tmax, iterations, output_tolerance, no_zero_toi);
    return ticcd::edgeEdgeCCD(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], automatic_filters, separation, found,
                              distance_tolerance, tmax, iterations, output_tolerance, no_zero_toi);
  };
  const double effective_separation =
      min_distance +
      std::min((1 - conservative_rescaling) * (initial_distance - min_distance), kLargestRescalingSeparation);
  double found = 0;
  bool hit = ask(effective_separation, false, found);
  if (hit && found < kSmallToi) {
    hit = ask(min_distance, true, found);
    if (hit) found *= conservative_rescaling;
  }
  if (hit) toi = found;
  return hit;
}

#else

bool tight_inclusion_available() { return false; }

bool tight_inclusion_ipc_ccd(Kind, const Query&, double, double&, double, double, double, long, double) {
  throw std::logic_error(
      "batchccd was configured without Tight Inclusion (cmake -DBATCHCCD_TIGHT_INCLUSION_DIR=<its sources>)");
}

#endif

}  // namespace batchccd::peers

#pragma once

#include <algorithm>
#include <atomic>

#include "batchccd/options.hpp"

// The shrinking window of earliest-TOI-only calls and of the collision-free
// step (docs/design.md §12): the earliest contact found so far, which only
// falls. A survivor asked after a contact at t is known is asked over a
// window just past t, where its solver stops.
namespace batchccd {

class ShrinkingWindow {
 public:
  explicit ShrinkingWindow(double earliest) : earliest_(earliest) {}
  double earliest() const { return earliest_.load(std::memory_order_relaxed); }
  void lower_to(double toi) {
    double current = earliest_.load(std::memory_order_relaxed);
    while (toi < current && !earliest_.compare_exchange_weak(current, toi, std::memory_order_relaxed)) {
    }
  }

 private:
  std::atomic<double> earliest_;
};

// The tmax a survivor is asked with once the earliest contact found is at
// `earliest`. A reported TOI lies up to Options::toi_tolerance (at least
// 2^-45; exact mode's 2^-40 is within it) before the contact it reports,
// and a query asked with tmax between the two may rightly answer that the
// contact comes after tmax. Past `earliest` by that much, a survivor whose
// TOI is below `earliest` gets the TOI it gets over [0, options.tmax]
// (tests/test_shrinking_window.cpp), so the minimum does not depend on the
// order in which threads find contacts.
inline double window_tmax(double earliest, const Options& options) {
  return std::min(options.tmax, earliest + std::max(0x1p-45, options.toi_tolerance));
}

// The same for ipc-toolkit's rules (ipc::collision_free_stepsize), whose
// steps are `earliest` so far: a retried step is its toi times the
// rescaling, so its contact may come up to earliest / rescaling, and each
// of the rules' queries (Options' default toi_tolerance) may report a TOI
// up to one toi_tolerance before its contact: two of them past that.
inline double ipc_window_tmax(double earliest, double conservative_rescaling) {
  return std::min(1.0, earliest / conservative_rescaling + 2 * Options{}.toi_tolerance);
}

}  // namespace batchccd

#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "simd/sources.hpp"

// The part of the step a shrinking window still asks about, as packed rows
// the lane filters take (docs/design.md §12): once the earliest step found
// is small, a candidate is filtered over [0, h] instead of [0, 1], where its
// boxes and motion are 1/h times smaller, and nearly every candidate is
// culled by the first, cheapest test.
namespace batchccd {

class Horizons {
 public:
  // The horizons below the whole step, 16^-1, 16^-2 and 16^-3: past 16^-3
  // (2.4e-4) the culls barely grow on the shared scenes' dense lists.
  static constexpr int kLevels = 3;
  static constexpr double kRatio = 0x1p-4;

  struct Rows {
    simd::MeshPositions positions;
    // What the filters add to a separation over these rows: each of a
    // point's coordinates at t1 errs by at most 3u m + 2^-1074 (m the
    // largest coordinate magnitude, PackedPositions::pack_within), a point
    // on a feature between t0 and t1 by at most sqrt(3) of that, and a
    // distance between two features by twice that: below 11u m + 2^-1072.
    // A candidate the filters cull at the separation plus this margin over
    // [0, h] is farther than the separation over [0, h] of its own motion.
    double margin = 0;
  };

  // For a call over `whole`'s rows; forgets the last call's horizons (their
  // storage is kept for the next one).
  void reset(const simd::PackedPositions& whole) {
    whole_ = &whole;
    for (auto& ready : ready_) ready.store(false, std::memory_order_relaxed);
  }

  // Rows over [0, h] for the smallest h of 1, 16^-1, ... no smaller than
  // `tmax`, made by the first caller that asks for them (others wait). The
  // whole step's rows where a coordinate is not finite.
  Rows over(double tmax) {
    const simd::MeshPositions whole = whole_->view();
    if (!whole.finite) return {whole, 0};
    int level = 0;
    double horizon = 1;
    while (level < kLevels && tmax <= horizon * kRatio) horizon *= kRatio, ++level;
    if (level == 0) return {whole, 0};
    const auto slot = static_cast<std::size_t>(level - 1);
    if (!ready_[slot].load(std::memory_order_acquire)) {
      const std::lock_guard<std::mutex> lock(making_);
      if (!ready_[slot].load(std::memory_order_relaxed)) {
        // Room for every horizon not yet made, not just this one: which
        // horizons a call reaches depends on the order threads find
        // contacts, and a frame loop's later calls must not allocate.
        for (std::size_t k = 0; k < rows_.size(); ++k)
          if (!ready_[k].load(std::memory_order_relaxed)) rows_[k].resize(whole.vertices);
        rows_[slot].pack_within(*whole_, horizon, 0, whole.vertices);
        ready_[slot].store(true, std::memory_order_release);
      }
    }
    return {rows_[slot].view(), 0x1p-49 * whole.largest + 0x1p-1000};
  }

 private:
  const simd::PackedPositions* whole_ = nullptr;
  std::array<simd::PackedPositions, kLevels> rows_;
  std::array<std::atomic<bool>, kLevels> ready_{};
  std::mutex making_;
};

}  // namespace batchccd

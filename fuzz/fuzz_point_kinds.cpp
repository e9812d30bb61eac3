// libFuzzer target: point kinds in 3D (vertex-edge and vertex-vertex,
// docs/design.md §5a "Point kinds in 3D"), decided by their vertex-segment
// conditions at any separation d >= 0 (solve_point_within; at d = 0 it only
// proves misses, proves_point_miss). Each input is one query on a 2^-4
// grid whose heights (z) are scaled down by 2^-k, so nearly planar motion,
// where the search over (t, u, v) stays uncertain, comes often; as the input
// asks, the point is moved onto the segment (or the other point) exactly at
// t = 0, 1/4, 1/2 or 1, a real contact at d = 0; then the whole query and d
// are scaled by a power of two.
//
// Invariants, each aborting with its name: at tmax = 1 and at the tmax the
// input picks (often below 1), the checks of pair_search_check.hpp (the
// searches of §5a against the box search with them off, in both certified
// modes, and both against exact truth).
//
// Bytes: flags (kind: bit 0; contact time: bits 1-3, 0 none, 1-4 the times
// above, 5-7 none; contact parameter on the segment: bits 4-6, k/4 for k =
// bits mod 5), tmax (128 or more: 1; else (byte + 1) / 128), separation
// index, flatness (bits 0-3: heights times 2^-k; bit 4: every height equal,
// an axis plane), scale exponent e (the query times 2^(4 int8(e))), then 3
// points (p, e0, e1; vertex-vertex p, q) at t0 and at t1, 3 int8 each.
// Short inputs are zero-padded.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "batchccd/query.hpp"
#include "pair_search_check.hpp"

namespace {

using batchccd::Kind;
using batchccd::Query;
using batchccd::Vec3;

constexpr std::size_t kHeaderBytes = 5;
constexpr std::size_t kInputBytes = kHeaderBytes + 2 * 3 * 3;
constexpr std::array kSeparations{0.0, 0.0, 0x1p-10, 0x1p-6, 0x1p-3, 0.5, 2.0, 8.0};
constexpr std::array kContactTimes{0.0, 0.25, 0.5, 1.0};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::array<std::uint8_t, kInputBytes> bytes{};
  std::copy_n(data, std::min(size, kInputBytes), bytes.begin());
  const Kind kind = bytes[0] & 1 ? Kind::vertex_vertex : Kind::vertex_edge;
  const double tmax = bytes[1] >= 128 ? 1.0 : (bytes[1] + 1) / 128.0;
  double separation = kSeparations[bytes[2] % kSeparations.size()];
  const int flatness = bytes[3] & 15;
  const bool axis_plane = bytes[3] >> 4 & 1;
  const int points = batchccd::points_per_time(kind);
  // start[k], end[k]: p, e0, e1 (or p, q) at t0 and t1.
  std::array<Vec3, 3> start, end;
  for (int k = 0; k < points; ++k)
    for (int tau = 0; tau < 2; ++tau) {
      const auto* c = reinterpret_cast<const std::int8_t*>(&bytes[kHeaderBytes + 9 * tau + 3 * k]);
      const double height = axis_plane ? 0.0 : std::ldexp(c[2] / 16.0, -flatness);
      (tau == 0 ? start : end)[k] = Vec3(c[0] / 16.0, c[1] / 16.0, height);
    }
  const int contact = bytes[0] >> 1 & 7;
  if (contact >= 1 && contact <= 4) {
    // The point on the other primitive at time tau, exactly (small dyadics).
    const double tau = kContactTimes[contact - 1], along = ((bytes[0] >> 4 & 7) % 5) / 4.0;
    const auto at = [&](int k) -> Vec3 { return (1 - tau) * start[k] + tau * end[k]; };
    const Vec3 target = kind == Kind::vertex_vertex ? at(1) : Vec3(at(1) + along * (at(2) - at(1)));
    if (tau == 0) start[0] = target;
    else end[0] = (target - (1 - tau) * start[0]) / tau;
  }
  const double scale = std::ldexp(1.0, 4 * static_cast<std::int8_t>(bytes[4]));
  for (int k = 0; k < points; ++k) {
    start[k] *= scale;
    end[k] *= scale;
  }
  separation *= scale;
  const Query query = batchccd::make_query(kind, std::span<const Vec3>(start.data(), points),
                                           std::span<const Vec3>(end.data(), points));
  const double windows[] = {1.0, tmax};
  batchccd::fuzz::check_at_separation(kind, query, separation, std::span<const double>(windows, tmax < 1 ? 2 : 1));
  return 0;
}

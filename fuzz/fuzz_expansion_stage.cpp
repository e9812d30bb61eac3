// libFuzzer target: the exact stage's expansions (docs/design.md §6a)
// against its integers. Each input is one vertex-face or edge-edge query
// whose coordinates sit on a 2^-6 grid, with a contact placed exactly on an
// edge or a corner at t = 1/q when the input asks for one (where the zero
// test decides), then a few coordinates moved by a few ulps (where the
// filter's bounds and the finer grids decide), and the whole query scaled
// by a power of two. Invariants, each aborting with its name:
//
// - where the expansions answer, their decision equals the integers', at
//   tmax = 1 and at the tmax the input picks;
// - with the TOI asked for, theirs lies within 2^-40 of the integers';
//   without it, it is still no later than the integers' TOI + 2^-40;
// - the first root of the cubic in [k/8, (k+1)/8], located with
//   expansions, is within 2^-40 of the integers' and never below k/8.
//
// With the planar flags, every point's z is replaced by one value per time
// (z = 0, or a plane moving along z): motion where the coplanarity cubic
// vanishes and the expansions decide in the plane; jitters may then make it
// nearly planar.
//
// Bytes: flags (kind, placed contact, q, parameter, planar, moving plane), tmax, scale exponent,
// 24 int8 coordinates (4 points at t0 and t1), then up to 4 jitters of
// (coordinate index, ulps); short inputs are zero-padded.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "batchccd/query.hpp"
#include "exact/exact_solver.hpp"
#include "exact/expansion_stage.hpp"
#include "exact/first_root.hpp"
#include "fuzz_check.hpp"

namespace {

using batchccd::Kind;
using batchccd::Query;
using batchccd::Vec3;
using batchccd::exact::ExactOutcome;
using batchccd::fuzz::require;

constexpr std::size_t kJitters = 4;
constexpr std::size_t kInputBytes = 3 + 24 + 2 * kJitters;
constexpr double kToiWidth = 0x1p-40;

Query make_query(const std::array<std::int8_t, kInputBytes>& bytes, Kind kind) {
  std::array<Vec3, 8> points;
  for (int i = 0; i < 8; ++i)
    points[i] = Vec3(bytes[3 + 3 * i], bytes[4 + 3 * i], bytes[5 + 3 * i]) / 64.0;
  const auto flags = static_cast<std::uint8_t>(bytes[0]);
  if (flags & 2) {  // the mover meets edge a at parameter s at t = 1/q
    const double q = std::array{2.0, 3.0, 5.0, 7.0}[(flags >> 2) % 4];
    const double s = ((flags >> 4) % 3) / 2.0;
    const int a0 = kind == Kind::vertex_face ? 1 : 0, a1 = a0 + 1, mover = kind == Kind::vertex_face ? 0 : 2;
    const Vec3 meet_q = (1 - s) * ((q - 1) * points[a0] + points[a0 + 4]) + s * ((q - 1) * points[a1] + points[a1 + 4]);
    points[mover + 4] = meet_q - (q - 1) * points[mover];
  }
  if (flags & 0x40) {  // planar motion: z = 0, or (flag 0x80) z = 1/4 at t0 and -3/8 at t1
    const bool moving = flags & 0x80;
    for (int i = 0; i < 8; ++i) points[i].z() = moving ? (i < 4 ? 0.25 : -0.375) : 0.0;
  }
  for (std::size_t j = 0; j < kJitters; ++j) {
    const auto index = static_cast<std::uint8_t>(bytes[27 + 2 * j]) % 24;
    double& value = points[index / 3][index % 3];
    for (int ulps = bytes[28 + 2 * j] % 4; ulps != 0; ulps += ulps > 0 ? -1 : 1)
      value = std::nextafter(value, ulps > 0 ? 1e300 : -1e300);
  }
  const double scale = std::ldexp(1.0, bytes[2] * 4);  // 2^-512 .. 2^508
  Query query;
  for (int i = 0; i < 8; ++i) query.points[i] = points[i] * scale;
  return query;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::array<std::int8_t, kInputBytes> bytes{};
  for (std::size_t i = 0; i < size && i < kInputBytes; ++i) bytes[i] = static_cast<std::int8_t>(data[i]);
  const Kind kind = (bytes[0] & 1) ? Kind::edge_edge : Kind::vertex_face;
  const Query query = make_query(bytes, kind);
  for (const Vec3& point : query.points)
    if (!point.allFinite()) return 0;
  const double tmax = (1 + static_cast<double>(static_cast<std::uint8_t>(bytes[1]))) / 256.0;  // in (0, 1]
  for (const double window : {1.0, tmax}) {
    const ExactOutcome integers = batchccd::exact::solve_with_integers(kind, query, true, window);
    for (const bool need_toi : {true, false}) {
      const std::optional<ExactOutcome> expansions =
          batchccd::exact::solve_with_expansions(kind, query, need_toi, window);
      if (!expansions || integers.bound_reached) continue;
      require(expansions->hit == integers.hit, "expansions decide as integers");
      if (!integers.hit) continue;
      require(expansions->toi <= integers.toi + kToiWidth, "expansions' TOI no later than the contact");
      if (need_toi) require(expansions->toi >= integers.toi - kToiWidth, "expansions' TOI within 2^-40");
    }
  }
  for (int k = 0; k < 8; ++k) {
    const double low = k / 8.0, high = (k + 1) / 8.0;
    const std::optional<double> integers = batchccd::exact::first_root_with_integers(kind, query, low, high);
    const std::optional<double> expansions = batchccd::exact::first_root_with_expansions(kind, query, low, high);
    if (!integers || !expansions || *expansions == low) continue;  // integers look in the open interval
    require(*expansions >= low && std::fabs(*expansions - *integers) <= kToiWidth,
            "expansions locate the first root as integers do");
  }
  return 0;
}

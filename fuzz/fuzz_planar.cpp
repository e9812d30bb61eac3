// libFuzzer target: the planar path (docs/design.md §5a) against the exact
// stage. Each input is one query whose eight points lie in one plane by
// construction: origin + s u + t v with small integer u, v, origin and
// in-plane coordinates on a 2^-4 grid, so every coordinate is exact and
// degenerate geometry (repeated points, collinear motion, contacts at a
// corner) comes often. Invariants, each aborting with its name:
//
// - exact mode's planar decision equals the same query decided with the
//   planar path off (lab::Settings::planar_path = false: the generic path,
//   where the exact stage decides coplanar motion), and its TOI lies
//   within 2^-40 of that one's, never after it by more;
// - conservative mode finds every such contact, at a TOI no later;
// - both hold at tmax = 1 and at the tmax the input picks.
//
// Bytes: kind (2 bits), tmax (1 byte), origin, u and v (3 int8 each), then
// 8 points x 2 int8 in-plane coordinates; short inputs are zero-padded.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "fuzz_check.hpp"

namespace {

using batchccd::Kind;
using batchccd::Mode;
using batchccd::Options;
using batchccd::Query;
using batchccd::QueryResult;
using batchccd::Vec3;
using batchccd::fuzz::require;

constexpr std::size_t kInputBytes = 2 + 9 + 16;
constexpr double kExactToiWidth = 0x1p-40;

QueryResult decide(Kind kind, const Query& query, Mode mode, double tmax, bool planar_path) {
  Options options;
  options.mode = mode;
  options.tmax = tmax;
  batchccd::lab::Settings settings;
  settings.planar_path = planar_path;
  return batchccd::lab::query_ccd(kind, query, options, settings);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::array<std::int8_t, kInputBytes> bytes{};
  for (std::size_t i = 0; i < size && i < kInputBytes; ++i) bytes[i] = static_cast<std::int8_t>(data[i]);
  constexpr Kind kKinds[] = {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex};
  const Kind kind = kKinds[static_cast<std::uint8_t>(bytes[0]) % 4];
  const double tmax = (1 + static_cast<double>(static_cast<std::uint8_t>(bytes[1]))) / 256.0;  // in (0, 1]
  const auto vector = [&](std::size_t at) { return Vec3(bytes[at], bytes[at + 1], bytes[at + 2]); };
  const Vec3 origin = vector(2) / 16, u = vector(5), v = vector(8);
  Query query;
  for (int i = 0; i < 8; ++i) {
    const double s = bytes[11 + 2 * i] / 16.0, t = bytes[12 + 2 * i] / 16.0;
    query.points[i] = origin + s * u + t * v;
  }
  // The point kinds' layout: a point is a zero-length edge (query.hpp).
  if (kind == Kind::vertex_edge || kind == Kind::vertex_vertex) {
    query.points[1] = query.points[0];
    query.points[5] = query.points[4];
  }
  if (kind == Kind::vertex_vertex) {
    query.points[3] = query.points[2];
    query.points[7] = query.points[6];
  }
  for (const double window : {1.0, tmax}) {
    const QueryResult truth = decide(kind, query, Mode::exact, window, false);
    const QueryResult exact = decide(kind, query, Mode::exact, window, true);
    const QueryResult conservative = decide(kind, query, Mode::conservative, window, true);
    require(exact.hit == truth.hit, "planar exact decision equals the exact stage's");
    if (truth.hit) {
      require(std::fabs(exact.toi - truth.toi) <= 2 * kExactToiWidth, "planar exact TOI within 2^-40");
      require(conservative.hit, "conservative finds every planar contact");
      require(conservative.toi <= truth.toi + kExactToiWidth, "conservative TOI no later than the contact");
    }
  }
  return 0;
}

// libFuzzer target: the planar path (docs/design.md §5a), with and without
// a separation, and raw 2D batches. Each input is a header and up to four
// queries of one kind whose eight points lie in one plane by construction:
// origin + s u + t v with small integer u, v, origin and in-plane
// coordinates on a 2^-4 grid, so every coordinate is exact and degenerate
// geometry (repeated points, collinear motion, contacts at a corner) comes
// often; the plane is tilted or, as the input asks, an axis plane (one
// coordinate shared by every point: where a separation is decided in the
// plane). Each query has a separation d, 0 or one of a few magnitudes.
//
// Invariants, each aborting with its name:
// - every query, at tmax = 1 and at the tmax the input picks: the checks of
//   pair_search_check.hpp (the planar searches against the box search with
//   them off, in both certified modes, and both against exact truth);
// - the 2D batch of the queries' (x, y) coordinates, with one separation
//   per query (or the first one for all, as the header says), equals the
//   3D batch of the same queries lifted to z = 0 in every result and
//   counter, in the mode and on the instruction set the header picks, and
//   each lifted query's result equals its single-query call's.
//
// Bytes: header (kind: bits 0-1; mode: bit 2; per-query separations: bit 3;
// instruction set: bits 4-5, an index into those available), tmax, then
// records of kRecordBytes: plane (0 tilted, 1-3 the axis plane normal to
// x, y, z), separation index, origin, u and v (3 int8 each), 8 points x 2
// int8 in-plane coordinates. A short last record is zero-padded.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "fuzz_check.hpp"
#include "pair_search_check.hpp"

namespace {

using namespace batchccd;
using batchccd::fuzz::require;

constexpr std::size_t kHeaderBytes = 2;
constexpr std::size_t kRecordBytes = 2 + 9 + 16;
constexpr std::size_t kMaxRecords = 4;
// 0 twice as often as the others: the planar path without a separation.
constexpr std::array kSeparations{0.0, 0.0, 0x1p-8, 0x1p-4, 0.5, 2.0, 8.0, 32.0};

Query planar_query(Kind kind, const std::int8_t* record) {
  const auto vector = [&](std::size_t at) { return Vec3(record[at], record[at + 1], record[at + 2]); };
  Vec3 origin = vector(2) / 16, u = vector(5), v = vector(8);
  const int normal = static_cast<std::uint8_t>(record[0]) % 4 - 1;
  if (normal >= 0) u[normal] = v[normal] = 0;
  Query query;
  for (int i = 0; i < 8; ++i) {
    const double s = record[11 + 2 * i] / 16.0, t = record[12 + 2 * i] / 16.0;
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
  return query;
}

void require_same(const QueryResult& a, const QueryResult& b, const char* invariant) {
  require(a.hit == b.hit && a.status == b.status && (a.toi == b.toi || (std::isnan(a.toi) && std::isnan(b.toi))),
          invariant);
}

// The raw 2D batch against the lifted 3D batch and the single-query calls.
void check_2d_batch(Kind kind, const std::vector<Query>& queries, const std::vector<double>& separations,
                    std::uint8_t header, double tmax) {
  std::vector<Query2D> flat(queries.size());
  std::vector<Query> lifted_queries(queries.size());
  for (std::size_t q = 0; q < queries.size(); ++q) {
    for (int i = 0; i < 8; ++i) flat[q].points[i] = queries[q].points[i].head<2>();
    lifted_queries[q] = lifted(flat[q]);
  }
  Options options;
  options.mode = header >> 2 & 1 ? Mode::exact : Mode::conservative;
  options.tmax = tmax;
  options.threads = 1;
  options.max_iterations = batchccd::fuzz::kBoxBudget;
  const std::vector<Isa> isas = available_isas();
  options.isa = isas[(header >> 4 & 3) % isas.size()];
  const bool per_query = header >> 3 & 1;
  options.min_distance = per_query ? 0 : separations[0];
  const std::span<const double> each = per_query ? std::span<const double>(separations) : std::span<const double>();
  BatchResult in_2d, in_3d;
  lab::batch_ccd(kind, std::span<const Query2D>(flat), each, options, {}, in_2d);
  lab::batch_ccd(kind, std::span<const Query>(lifted_queries), each, options, {}, in_3d);
  require(in_2d.results.size() == queries.size() && in_3d.results.size() == queries.size(), "a result per query");
  for (std::size_t q = 0; q < queries.size(); ++q) {
    require_same(in_2d.results[q], in_3d.results[q], "a 2D batch equals the lifted 3D batch");
    Options alone = options;
    alone.min_distance = per_query ? separations[q] : separations[0];
    require_same(lab::query_ccd(kind, lifted_queries[q], alone, {}), in_3d.results[q],
                 "a lifted batch's result equals its single-query call's");
  }
  const Counters &a = in_2d.counters, &b = in_3d.counters;
  require(a.candidates == b.candidates && a.culled == b.culled && a.culled_by_sign == b.culled_by_sign &&
              a.culled_by_separation == b.culled_by_separation && a.culled_by_pieces == b.culled_by_pieces &&
              a.culled_by_swept_box == b.culled_by_swept_box && a.solved == b.solved && a.hits == b.hits &&
              a.undecided == b.undecided && a.invalid == b.invalid && a.exact_escalations == b.exact_escalations,
          "a 2D batch's counters equal the lifted 3D batch's");
  require(in_2d.earliest_toi == in_3d.earliest_toi, "a 2D batch's earliest TOI equals the lifted batch's");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::size_t records = std::clamp<std::size_t>(
      (std::max(size, kHeaderBytes) - kHeaderBytes + kRecordBytes - 1) / kRecordBytes, 1, kMaxRecords);
  std::vector<std::int8_t> bytes(kHeaderBytes + records * kRecordBytes, 0);
  std::copy_n(data, std::min(size, bytes.size()), reinterpret_cast<std::uint8_t*>(bytes.data()));
  const auto header = static_cast<std::uint8_t>(bytes[0]);
  constexpr Kind kKinds[] = {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex};
  const Kind kind = kKinds[header % 4];
  const double tmax = (1 + static_cast<double>(static_cast<std::uint8_t>(bytes[1]))) / 256.0;  // in (0, 1]
  std::vector<Query> queries;
  std::vector<double> separations;
  for (std::size_t r = 0; r < records; ++r) {
    const std::int8_t* record = bytes.data() + kHeaderBytes + r * kRecordBytes;
    queries.push_back(planar_query(kind, record));
    separations.push_back(kSeparations[static_cast<std::uint8_t>(record[1]) % kSeparations.size()]);
    const double windows[] = {1.0, tmax};
    batchccd::fuzz::check_at_separation(kind, queries.back(), separations.back(),
                                        std::span<const double>(windows, tmax < 1 ? 2 : 1));
  }
  check_2d_batch(kind, queries, separations, header, tmax);
  return 0;
}

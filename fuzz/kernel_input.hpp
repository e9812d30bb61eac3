#pragma once

// How the query-kernel fuzz target reads its bytes: one setup byte, then a
// sequence of records, one query each (at most kMaxRecords; a short last
// record is zero-padded).
//
// The setup byte picks the one configuration this input also runs through
// the batch entry points and scaled (every check on every input made the
// target 5 times slower; the fuzzer varies the byte like any other):
//   bits 0-1 mode or baseline (index into the checked ones, modulo their count)
//   bits 2-3 instruction set (index into those available, modulo)
//   bit 4    entry point: 0 batch_ccd, 1 mesh_ccd
//   bits 5-6 separation: 0 none; 1-3 each query at 2^-20, 2^-6 or 2^-1
//            of its size (fuzz_query_kernels.cpp; none with the cubic
//            baseline, which refuses one)
//   bit 7    a time window: the next byte b gives tmax = (b + 1) / 256
//            (else tmax = 1)
//
// A record:
//   byte 0  control: bit 0 kind (0 vertex-face, 1 edge-edge)
//                    bit 1 coordinates: 0 raw (24 little-endian doubles,
//                          any bit pattern: NaN, inf, subnormals), 1 grid
//                          (24 int8 and one int8 exponent e: n * 2^(8e),
//                          small integers that make degenerate geometry
//                          likely)
//                    bits 2-3 forced contact: 0 none, 1 at t0, 2 at t1,
//                          3 at both; a vertex of one primitive is copied
//                          onto one of the other (bits 4-5 pick which), so
//                          the exact answer is a contact at that time
//                    bit 6 need_toi = false (decision only)
//                    bit 7 unused
//   byte 1  scale: the query is also run scaled by 2^(8 * int8(byte 1))
//   then    192 bytes (raw) or 25 bytes (grid)
//
// The seed tool writes records of this shape from the sample queries.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include "batchccd/query.hpp"

namespace batchccd::fuzz {

constexpr std::size_t kMaxRecords = 8;
constexpr std::size_t kRawPayload = 24 * sizeof(double);
constexpr std::size_t kGridPayload = 25;

enum class ForcedContact { none, at_t0, at_t1, at_both };

struct KernelSetup {
  unsigned mode_index = 0;
  unsigned isa_index = 0;
  bool mesh = false;
  unsigned separation_index = 0;
  double tmax = 1;
};

struct KernelRecord {
  Kind kind = Kind::vertex_face;
  Query query;
  ForcedContact contact = ForcedContact::none;
  bool need_toi = true;
  int scale_exponent = 0;
};

namespace detail {

inline double raw_double(const std::uint8_t* bytes) {
  std::uint64_t bits = 0;
  for (int i = 7; i >= 0; --i) bits = (bits << 8) | bytes[i];
  return std::bit_cast<double>(bits);
}

inline int signed_byte(std::uint8_t byte) { return static_cast<int>(static_cast<std::int8_t>(byte)); }

// Copies a vertex of one primitive onto the other at t0 and/or t1:
// vertex-face: p onto a, b or c; edge-edge: ea0 or ea1 onto eb0 or eb1.
inline void force_contact(KernelRecord& record, unsigned which) {
  const bool vertex_face = record.kind == Kind::vertex_face;
  const std::size_t target = vertex_face ? 0 : (which & 1u);
  const std::size_t source = vertex_face ? 1 + (which % 3u) : 2 + ((which >> 1) & 1u);
  auto& points = record.query.points;
  if (record.contact == ForcedContact::at_t0 || record.contact == ForcedContact::at_both)
    points[target] = points[source];
  if (record.contact == ForcedContact::at_t1 || record.contact == ForcedContact::at_both)
    points[target + 4] = points[source + 4];
}

}  // namespace detail

struct KernelInput {
  KernelSetup setup;
  std::vector<KernelRecord> records;
};

inline std::vector<KernelRecord> decode_records(std::span<const std::uint8_t> bytes);

inline KernelInput decode_input(std::span<const std::uint8_t> bytes) {
  KernelInput input;
  if (bytes.empty()) return input;
  input.setup = {bytes[0] & 3u, (bytes[0] >> 2) & 3u, (bytes[0] & 16u) != 0, (bytes[0] >> 5) & 3u};
  std::size_t header = 1;
  if ((bytes[0] & 128u) != 0 && bytes.size() > 1) {
    input.setup.tmax = (bytes[1] + 1) / 256.0;
    header = 2;
  }
  input.records = decode_records(bytes.subspan(header));
  return input;
}

inline std::vector<KernelRecord> decode_records(std::span<const std::uint8_t> bytes) {
  std::vector<KernelRecord> records;
  std::size_t at = 0;
  while (at < bytes.size() && records.size() < kMaxRecords) {
    const std::uint8_t control = bytes[at];
    const bool grid = (control & 2u) != 0;
    const std::size_t length = 2 + (grid ? kGridPayload : kRawPayload);
    std::array<std::uint8_t, 2 + kRawPayload> record_bytes{};  // zero-padded
    const std::size_t available = std::min(length, bytes.size() - at);
    std::memcpy(record_bytes.data(), bytes.data() + at, available);
    at += available;

    KernelRecord record;
    record.kind = (control & 1u) ? Kind::edge_edge : Kind::vertex_face;
    record.contact = static_cast<ForcedContact>((control >> 2) & 3u);
    record.need_toi = (control & 64u) == 0;
    record.scale_exponent = 8 * detail::signed_byte(record_bytes[1]);
    const std::uint8_t* payload = record_bytes.data() + 2;
    const int grid_exponent = 8 * detail::signed_byte(payload[24]);
    for (std::size_t c = 0; c < 24; ++c) {
      record.query.points[c / 3][static_cast<Eigen::Index>(c % 3)] =
          grid ? std::ldexp(detail::signed_byte(payload[c]), grid_exponent) : detail::raw_double(payload + 8 * c);
    }
    detail::force_contact(record, (control >> 4) & 3u);
    records.push_back(record);
  }
  return records;
}

// The bytes of one raw record (the seed tool's side of decode_records; an
// input is a setup byte and records).
inline std::vector<std::uint8_t> encode_raw_record(Kind kind, const Query& query) {
  std::vector<std::uint8_t> bytes{static_cast<std::uint8_t>(kind == Kind::edge_edge ? 1 : 0), 0};
  for (const Vec3& point : query.points)
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      const auto bits = std::bit_cast<std::uint64_t>(point[axis]);
      for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
    }
  return bytes;
}

// The query scaled by 2^exponent when that is exact for every finite
// coordinate and stays finite (non-finite ones stay as they are); nothing
// otherwise.
inline std::optional<Query> exactly_scaled(const Query& query, int exponent) {
  Query scaled = query;
  for (Vec3& point : scaled.points)
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      const double x = point[axis];
      if (!std::isfinite(x)) continue;
      const double y = std::ldexp(x, exponent);
      if (!std::isfinite(y) || std::ldexp(y, -exponent) != x) return std::nullopt;
      point[axis] = y;
    }
  return scaled;
}

}  // namespace batchccd::fuzz

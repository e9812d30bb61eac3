#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#include "batchccd/query.hpp"
#include "batchccd/views.hpp"
#include "reference/scaled_query.hpp"

// Where a batch's candidates come from: raw queries, or a mesh and its
// candidate index lists. Plain views (no xsimd types), shared by the lane
// kernels, which gather from them, and the scheduler, which hands survivors
// to the scalar solver.
namespace batchccd::simd {

struct RawQueries {
  Kind kind;
  const Query* queries;
  bool stream = false;  // too many to stay in cache: the lanes prefetch ahead
};
// The lanes read a query as 24 contiguous doubles, point k at 3 k.
static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Query) == 8 * sizeof(Vec3));

// Raw queries of one kind, fixed at compile time as a mesh source's is: the
// lane kernels take them so (a query's point order depends on its kind).
template <Kind K>
struct RawQueriesOf {
  static constexpr Kind kind = K;
  const Query* queries;
  bool stream;
};

// A view of `count` raw queries. Those that fit in a core's second-level
// cache (1 MiB on the processors we target, 5,461 queries) come from there
// fast enough for the lanes on their own; prefetching them costs the
// instructions (24 a group of eight) and gains nothing.
inline RawQueries raw_queries(Kind kind, const Query* queries, std::size_t count) {
  constexpr std::size_t kCacheResidentBytes = std::size_t{1} << 20;
  return {kind, queries, count * sizeof(Query) > kCacheResidentBytes};
}

// Vertex positions, one row of kRowDoubles per vertex: x, y, z at t0, x, y,
// z at t1, two zeros. A row is one 64-byte cache line, so a lane loads a
// vertex's six coordinates at once (and transposes) instead of gathering
// them one by one.
inline constexpr int kRowDoubles = 8;
struct MeshPositions {
  const double* rows;  // 64-byte aligned
  std::int64_t vertices;
  bool finite;  // no coordinate is a NaN or infinite: no difference is a NaN
  // The same rows coarse, as many floats a row at the same offsets (for
  // coarse_boxes.hpp): x, y, z at t0 and t1 rounded to floats, a bound on
  // each one's rounding, a zero. nullptr unless every coordinate is finite
  // and below 2^100 in magnitude.
  const float* coarse = nullptr;  // 64-byte aligned
  // The largest coordinate magnitude of all rows; infinity unless finite.
  double largest = std::numeric_limits<double>::infinity();
};

// Where vertex v's row starts among MeshPositions::rows. Always inlined:
// the lane kernels, compiled with other flags, call it.
[[gnu::always_inline]] inline std::int64_t row_start(std::int64_t vertex) { return kRowDoubles * vertex; }

// Owns the packed rows of a mesh, made from the caller's positions (any
// layout, double or float) once per call: O(vertices), where the work is
// O(candidates).
class PackedPositions {
 public:
  // Room for `vertices` rows; pack() fills them.
  explicit PackedPositions(std::int64_t vertices = 0) { resize(vertices); }
  // All rows at once.
  PackedPositions(const PositionsView& t0, const PositionsView& t1) : PackedPositions(t0.rows()) {
    pack(t0, t1, 0, t0.rows());
  }

  // Room for `vertices` rows again, to be packed anew: the storage is kept
  // when it is large enough (a frame loop packs every call).
  void resize(std::int64_t vertices) {
    if (vertices > capacity_ || !rows_) {
      capacity_ = std::max<std::int64_t>(vertices, 1);
      rows_ = allocate<double>(capacity_);
      coarse_ = allocate<float>(capacity_);
    }
    vertices_ = vertices;
    finite_.store(true, std::memory_order_relaxed);
    coarse_usable_.store(true, std::memory_order_relaxed);
    largest_bits_.store(0, std::memory_order_relaxed);
  }

  // Rows [begin, end): callers may fill disjoint ranges in parallel.
  void pack(const PositionsView& t0, const PositionsView& t1, std::int64_t begin, std::int64_t end) {
    const auto columns = t0.cols();  // 2: a 2D mesh, in the plane z = 0
    t0.visit([&](const auto& start) {
      t1.visit([&](const auto& stop) {
        fill(begin, end, [&](std::int64_t v, double* row) {
          for (int c = 0; c < 3; ++c) {
            row[c] = c < columns ? start(v, c) : 0.0;
            row[c + 3] = c < columns ? stop(v, c) : 0.0;
          }
        });
      });
    });
  }

  // Rows [begin, end) of the first part of `whole`'s step, [0, horizon]
  // read as a step of its own: x at t0, then x0 + horizon (x1 - x0). For a
  // power of two `horizon` <= 1, each coordinate at t1 errs by at most 3u of
  // `whole`'s largest coordinate magnitude plus 2^-1074: the subtraction's
  // rounding, the product's (exact unless subnormal) and the sum's. Callers
  // may fill disjoint ranges in parallel.
  void pack_within(const PackedPositions& whole, double horizon, std::int64_t begin, std::int64_t end) {
    fill(begin, end, [&](std::int64_t v, double* row) {
      const double* from = whole.rows_.get() + row_start(v);
      for (int c = 0; c < 3; ++c) {
        row[c] = from[c];
        row[c + 3] = from[c] + horizon * (from[c + 3] - from[c]);
      }
    });
  }

  // The rows, once pack() has filled them all.
  MeshPositions view() const {
    const bool finite = finite_.load(std::memory_order_relaxed);
    const bool coarse = finite && coarse_usable_.load(std::memory_order_relaxed);
    const double largest = finite ? std::bit_cast<double>(largest_bits_.load(std::memory_order_relaxed))
                                  : std::numeric_limits<double>::infinity();
    return {rows_.get(), vertices_, finite, coarse ? coarse_.get() : nullptr, largest};
  }

 private:
  static constexpr double kCoarseLimit = 0x1p100;

  // Rows [begin, end), each's six coordinates written by set(v, row), then
  // its zeros, coarse row and what view() tells of all rows.
  template <class Set>
  void fill(std::int64_t begin, std::int64_t end, const Set& set) {
    bool finite = true, coarse = true;
    double range_largest = 0;
    for (std::int64_t v = begin; v < end; ++v) {
      double* row = rows_.get() + row_start(v);
      set(v, row);
      row[6] = row[7] = 0;
      // x - x is 0 for finite x and a NaN otherwise, and so is the sum
      // of a row's: one test a row, no branch per coordinate.
      double zero = 0, largest = 0;
      for (int c = 0; c < 6; ++c) zero += row[c] - row[c], largest = std::max(largest, std::fabs(row[c]));
      finite &= zero == 0;
      coarse &= largest <= kCoarseLimit;  // a NaN passes here, but not `finite`
      range_largest = std::max(range_largest, largest);
      pack_coarse(row, largest, coarse_.get() + row_start(v));
    }
    if (!finite) finite_.store(false, std::memory_order_relaxed);
    if (!coarse) coarse_usable_.store(false, std::memory_order_relaxed);
    // Non-negative doubles order as their bits do.
    const auto bits = std::bit_cast<std::uint64_t>(range_largest);
    std::uint64_t seen = largest_bits_.load(std::memory_order_relaxed);
    while (seen < bits && !largest_bits_.compare_exchange_weak(seen, bits, std::memory_order_relaxed)) {
    }
  }
  // A row's floats, and e >= 2^-24 |x| + 2^-149 for its largest |x|: float
  // rounding to nearest errs by at most 2^-24 |x|, or 2^-150 below the
  // normal range. e rounded up. Beyond the limit (the coarse rows unused
  // then) zeros: such a double may not fit a float.
  static void pack_coarse(const double* row, double largest, float* coarse) {
    const bool fits = largest <= kCoarseLimit;
    for (int c = 0; c < 6; ++c) coarse[c] = fits ? static_cast<float>(row[c]) : 0.0F;
    const double bound = 0x1p-24 * (fits ? largest : 0.0) + 0x1p-149;
    float e = static_cast<float>(bound);
    if (static_cast<double>(e) < bound) e = std::nextafter(e, 1.0F);
    coarse[6] = e;
    coarse[7] = 0;
  }

  struct Free {
    void operator()(void* p) const { ::operator delete[](p, std::align_val_t(64)); }
  };
  template <class T>
  static std::unique_ptr<T[], Free> allocate(std::int64_t vertices) {
    const auto rows = static_cast<std::size_t>(vertices);
    return {static_cast<T*>(::operator new[](sizeof(T) * kRowDoubles * rows, std::align_val_t(64))), Free{}};
  }
  std::int64_t vertices_ = 0;
  std::int64_t capacity_ = 0;  // rows the storage holds
  std::unique_ptr<double[], Free> rows_;
  std::unique_ptr<float[], Free> coarse_;
  std::atomic<bool> finite_{true};
  std::atomic<bool> coarse_usable_{true};
  std::atomic<std::uint64_t> largest_bits_{0};  // MeshPositions::largest's
};

// Faces, one row of four per face: where its three corners' rows start
// among MeshPositions::rows (vertex id times kRowDoubles), and a zero.
struct MeshFaces {
  const std::int64_t* rows;
  std::int64_t count;
};

// Owns the rows of MeshFaces, made from the caller's m x 3 faces once per
// call: a lane reads its face's corners from one place, and finds their rows
// without a multiplication (vertex-face lanes 1.01x to 1.02x).
class PackedFaces {
 public:
  PackedFaces() = default;
  // The first `count` faces.
  PackedFaces(const IdsView& faces, std::int64_t count) { assign(faces, count); }
  // The same anew, keeping the storage (a frame loop packs every call).
  void assign(const IdsView& faces, std::int64_t count) {
    rows_.resize(static_cast<std::size_t>(count));
    for (std::int64_t f = 0; f < count; ++f)
      rows_[static_cast<std::size_t>(f)] = {row_start(faces(f, 0)), row_start(faces(f, 1)),
                                            row_start(faces(f, 2)), 0};
  }
  MeshFaces view() const {
    return {rows_.empty() ? nullptr : rows_.front().data(), static_cast<std::int64_t>(rows_.size())};
  }

 private:
  std::vector<std::array<std::int64_t, 4>> rows_;
};

struct MeshVertexFace {
  static constexpr Kind kind = Kind::vertex_face;
  MeshPositions positions;
  MeshFaces faces;
  const std::array<int, 2>* pairs;  // vertex, face
};

struct MeshEdgeEdge {
  static constexpr Kind kind = Kind::edge_edge;
  MeshPositions positions;
  const std::array<int, 4>* pairs;  // a0, a1, b0, b1
};

// Thrown where a candidate names a vertex or face the mesh does not have.
// The filters meet every candidate's ids before anything reads the mesh, so
// they check them on the way (row_starts, or whole lane groups at once)
// instead of a pass over the lists of its own; the scheduler then names the
// first bad one (check_mesh) before it writes anything. The faces' own
// entries are checked before (O(faces)).
struct IndexOutOfRange {};

[[gnu::always_inline]] inline std::int64_t checked(int id, std::int64_t count) {
  if (static_cast<std::uint64_t>(static_cast<std::int64_t>(id)) >= static_cast<std::uint64_t>(count))
    throw IndexOutOfRange{};
  return id;
}

// Where the rows of candidate i's vertices start among MeshPositions::rows,
// in the order x1..x4 of docs/design.md §1 (VF: a, b, c, p), ids checked unless the
// caller has (check = false). Always inlined, as the lane kernels compiled
// with other flags call them.
template <bool check = true>
[[gnu::always_inline]] inline std::array<std::int64_t, 4> row_starts(const MeshVertexFace& mesh, std::size_t i) {
  const auto [vertex, face] = mesh.pairs[i];
  if constexpr (check) {
    const std::int64_t* f = mesh.faces.rows + 4 * checked(face, mesh.faces.count);
    return {f[0], f[1], f[2], row_start(checked(vertex, mesh.positions.vertices))};
  } else {
    const std::int64_t* f = mesh.faces.rows + 4 * static_cast<std::int64_t>(face);
    return {f[0], f[1], f[2], row_start(vertex)};
  }
}
template <bool check = true>
[[gnu::always_inline]] inline std::array<std::int64_t, 4> row_starts(const MeshEdgeEdge& mesh, std::size_t i) {
  const auto& e = mesh.pairs[i];
  const std::int64_t n = mesh.positions.vertices;
  const auto start = [n](int v) { return row_start(check ? checked(v, n) : v); };
  return {start(e[0]), start(e[1]), start(e[2]), start(e[3])};
}

template <class MeshSource>
Query query_at(const MeshSource& mesh, std::size_t i) {
  const std::array<std::int64_t, 4> starts = row_starts(mesh, i);
  Query query;
  for (int k = 1; k <= 4; ++k) {
    const double* row = mesh.positions.rows + starts[k - 1];
    const int slot = reference::point_index(MeshSource::kind, k);
    query.points[slot] = Vec3(row[0], row[1], row[2]);
    query.points[slot + 4] = Vec3(row[3], row[4], row[5]);
  }
  return query;
}

inline const Query& query_at(const RawQueries& raw, std::size_t i) { return raw.queries[i]; }

}  // namespace batchccd::simd

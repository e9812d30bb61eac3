#pragma once

// The lane filter, written once over xsimd's batch type and instantiated per
// instruction set by the kernel_*.cpp files (each compiled with its own
// flags). It mirrors the scalar reference path operation for operation —
// reference::run_filters, its frames and filters — so both make the same
// cull decision bit for bit (tests/test_simd.cpp holds them
// together). Include only from those translation units.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>

// The few instructions xsimd does not offer (transposes, lane masks as
// bits, compress-store, range), per processor family.
#if defined(__x86_64__) || defined(__i386__)
#define BATCHCCD_X86_LANES 1
#include <immintrin.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif

#include <xsimd/xsimd.hpp>

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/filter.hpp"
#include "reference/piecewise_filter.hpp"
#include "reference/separation_filter.hpp"
#include "reference/scaled_query.hpp"
#include "reference/sign_filter.hpp"
#include "reference/swept_box_filter.hpp"
#ifdef BATCHCCD_X86_LANES
#include "simd/coarse_boxes.hpp"
#endif
#include "simd/filter.hpp"
#include "simd/sources.hpp"

#ifdef __aarch64__
// The filters' max and min of doubles are a > b ? a : b and a < b ? a : b
// (reference::max_of, x86's maxpd and minpd). xsimd's on NEON are fmax and
// fmin, which return a NaN operand and +0 for zeros of either sign; these
// overloads, preferred to xsimd's templates wherever the filters call max
// or min on NEON's doubles, make its lanes decide as the reference does.
namespace xsimd {
inline batch<double, neon64> max(const batch<double, neon64>& a, const batch<double, neon64>& b) {
  return vbslq_f64(vcgtq_f64(a, b), a, b);
}
inline batch<double, neon64> min(const batch<double, neon64>& a, const batch<double, neon64>& b) {
  return vbslq_f64(vcltq_f64(a, b), a, b);
}
}  // namespace xsimd
#endif

namespace batchccd::simd {

template <class Arch>
struct Lanes {
  using Double = xsimd::batch<double, Arch>;
  using Mask = xsimd::batch_bool<double, Arch>;
  using Index = xsimd::batch<std::int64_t, Arch>;
  using Vector = reference::Vector3<Double>;
  static constexpr std::size_t size = Double::size;

  // 2^-ilogb(m) for positive m, as two factors whose product is exact to
  // apply (scaling up) or a single factor (scaling down): x * first * second
  // equals std::ldexp(x, -ilogb(m)) bit for bit, subnormals included.
  struct PowerOfTwo {
    Double first, second;
    Double apply(const Double& x) const { return x * first * second; }
    void scale(Vector* v, std::size_t n) const {
      for (std::size_t i = 0; i < n; ++i) v[i] = {apply(v[i].x), apply(v[i].y), apply(v[i].z)};
    }
  };
  static PowerOfTwo inverse_power_of_two(const Double& m) {
    using Bits = xsimd::batch<std::uint64_t, Arch>;
    const Mask subnormal = m < Double(0x1p-1022);
    const Double normal = xsimd::select(subnormal, m * Double(0x1p64), m);
    // 2^e has biased exponent E = e + 1023 in [1, 2046]; 2^-e has 2046 - E,
    // an integer subtraction instead of a division. Only 2^1023 (E = 2046)
    // has a subnormal inverse, 2^-1023.
    const Bits leading = xsimd::bitwise_cast<Bits>(normal) & Bits(0x7ff0000000000000ull);
    const Double inverse =
        xsimd::select(xsimd::bitwise_cast<Double>(leading) == Double(0x1p1023), Double(0x1p-1023),
                      xsimd::bitwise_cast<Double>(Bits(0x7fe0000000000000ull) - leading));
    return {inverse, xsimd::select(subnormal, Double(0x1p64), Double(1.0))};
  }
};

// Asks for the cache line at `address` (prefetcht0 on x86, prfm pldl1keep
// on ARM); never a fault, wherever it points.
[[gnu::always_inline]] inline void prefetch(std::uintptr_t address) {
  __builtin_prefetch(reinterpret_cast<const void*>(address), 0, 3);
}

// Which candidate each lane of a group evaluates: group[j] for lane j. A
// group of consecutive candidates (the first pass's full groups) says so in
// its type: raw queries then load whole rows and transpose, and a mesh's ids
// lie at fixed offsets. Any other group lists its candidates (a partial
// group's spare lanes repeat its last one, so the ends of a list tell
// nothing about what lies between them).
template <class Arch>
struct ListedGroup {
  std::int64_t candidate[Lanes<Arch>::size];
  std::int64_t operator[](std::size_t j) const { return candidate[j]; }
};
template <class Arch>
struct ConsecutiveGroup {
  std::int64_t first;
  std::int64_t operator[](std::size_t j) const { return first + static_cast<std::int64_t>(j); }
};

// A consecutive group as a list: the rare scaled frame takes lists only
// (one copy of its code, not one per kind of group).
template <class Arch>
ListedGroup<Arch> listed(const ConsecutiveGroup<Arch>& group) {
  ListedGroup<Arch> list;
  for (std::size_t j = 0; j < Lanes<Arch>::size; ++j) list.candidate[j] = group[j];
  return list;
}

// Loads candidate group[j] of a source into lane j of x[k][tau] (docs/design.md §1:
// x_{k+1} at t = tau).
template <class Arch>
struct Gather {
  using L = Lanes<Arch>;
  using Double = typename L::Double;
  using Vector = typename L::Vector;

  static constexpr std::size_t kPrefetchQueries = 32;  // 6 KB
  static constexpr int kQueryDoubles = 24;

  // Raw queries: each lane's row (one query) loaded and transposed, for
  // any group (a gather per coordinate, 24 a group, took the second pass
  // longer than the first).
  template <Kind K, class Group>
  static void from(const RawQueriesOf<K>& raw, const Group& group, Vector (&x)[4][2]) {
    Double coordinate[kQueryDoubles];
    transposed_queries(query_rows(raw, group), 0, coordinate);
    points(raw.kind, coordinate, x);
  }

  // rows(j): lane j's row. Consecutive queries lie in one block of rows
  // from the group's first. Streamed ones: ask for those kPrefetchQueries
  // ahead now, so their cache lines arrive while these compute (the
  // hardware's prefetcher alone left half the read bandwidth unused). An
  // address, never dereferenced: past the end of the queries it is harmless.
  template <Kind K>
  static auto query_rows(const RawQueriesOf<K>& raw, const ConsecutiveGroup<Arch>& group) {
    const double* first = raw.queries[0].points[0].data() + group.first * kQueryDoubles;
    if (raw.stream) {
      const std::uintptr_t ahead =
          reinterpret_cast<std::uintptr_t>(first) + kPrefetchQueries * kQueryDoubles * sizeof(double);
      for (std::size_t line = 0; line < L::size * kQueryDoubles * sizeof(double); line += 64)
        prefetch(ahead + line);
    }
    return [first](std::size_t j) { return first + j * kQueryDoubles; };
  }
  template <Kind K>
  static auto query_rows(const RawQueriesOf<K>& raw, const ListedGroup<Arch>& group) {
    const double* data = raw.queries[0].points[0].data();
    return [data, &group](std::size_t j) { return data + group[j] * kQueryDoubles; };
  }

  // Doubles [begin, begin + n) of each lane's row, transposed: lane j of
  // coordinate[c] is double begin + c of rows(j).
  template <std::size_t n, class Rows>
  static void transposed_queries(const Rows& rows, std::size_t begin, Double (&coordinate)[n]) {
    static_assert(n % L::size == 0);
    transpose_blocks<n>([&](std::size_t j, std::size_t block) {
      return Double::load_unaligned(rows(j) + begin + block);
    }, coordinate);
  }

  // A query's coordinates in its points' order into x.
  static void points(Kind kind, const Double (&coordinate)[kQueryDoubles], Vector (&x)[4][2]) {
    for (int k = 1; k <= 4; ++k)
      for (int tau = 0; tau < 2; ++tau) {
        const Double* c = coordinate + 3 * (reference::point_index(kind, k) + 4 * tau);
        x[k - 1][tau] = {c[0], c[1], c[2]};
      }
  }

  template <class MeshSource, class Group>
  static void from(const MeshSource& mesh, const Group& group, Vector (&x)[4][2]) {
    with_rows(mesh, group, [&](const auto& row) {
      for (int k = 0; k < 4; ++k)
        transposed([&](std::size_t j, std::size_t part) { return row(j, k, part); }, x[k]);
    });
  }

  // The differences x_{i+2}(tau) - x_1(tau) alone, taken row by row before
  // the transposes: three rows a lane to transpose instead of four. The
  // same operations on the same operands, so the same values.
  template <class MeshSource, class Group>
  static void differences(const MeshSource& mesh, const Group& group, Vector (&relative)[3][2]) {
    with_rows(mesh, group, [&](const auto& row) {
      for (int i = 0; i < 3; ++i)
        transposed([&](std::size_t j, std::size_t part) { return row(j, i + 1, part) - row(j, 0, part); },
                   relative[i]);
    });
  }

  // Lane j's row of kRowDoubles (x, y, z at t0, then at t1), L::size
  // doubles at a time from row(j, part), transposed into v[0] and v[1].
  template <class Row>
  static void transposed(const Row& row, Vector (&v)[2]) {
    Double coordinate[kRowDoubles];
    transpose_blocks<6>(row, coordinate);  // the row's six coordinates
    v[0] = {coordinate[0], coordinate[1], coordinate[2]};
    v[1] = {coordinate[3], coordinate[4], coordinate[5]};
  }

  template <Kind K, class Group>
  static void differences(const RawQueriesOf<K>& raw, const Group& group, Vector (&relative)[3][2]) {
    constexpr std::size_t kTimeDoubles = kQueryDoubles / 2;  // a query's four points at one time
    if constexpr (kTimeDoubles % L::size == 0) {
      // One time after the other: 12 coordinates live instead of 24, which
      // AVX2's 16 registers could not hold.
      const auto rows = query_rows(raw, group);
      for (int tau = 0; tau < 2; ++tau) {
        Double coordinate[kTimeDoubles];
        transposed_queries(rows, kTimeDoubles * tau, coordinate);
        const auto point = [&](int k) {
          const Double* c = coordinate + 3 * reference::point_index(raw.kind, k);
          return Vector{c[0], c[1], c[2]};
        };
        for (int i = 0; i < 3; ++i) relative[i][tau] = point(i + 2) - point(1);
      }
    } else {
      Vector x[4][2];
      from(raw, group, x);
      for (int i = 0; i < 3; ++i)
        for (int tau = 0; tau < 2; ++tau) relative[i][tau] = x[i + 1][tau] - x[0][tau];
    }
  }

  // f(row): row(j, k, part) loads part (L::size doubles from double
  // `part` on) of the packed row of lane j's vertex k. Ids unchecked:
  // filter_range checked them (check_ids) before the group.
  template <class MeshSource, class F>
  static void with_rows(const MeshSource& mesh, const ListedGroup<Arch>& group, const F& f) {
    f(rows_of(mesh, [&](std::size_t j) { return static_cast<std::size_t>(group[j]); }));
  }
  template <class MeshSource, class F>
  static void with_rows(const MeshSource& mesh, const ConsecutiveGroup<Arch>& group, const F& f) {
    // Lane j's candidate is pair j of the list from `first` on: its ids lie
    // at a fixed offset from one pointer.
    MeshSource from_first = mesh;
    from_first.pairs += group.first;
    // Opaque to the optimiser, which otherwise folds the offset back into
    // each lane's index and computes eight addresses (24 instructions).
    asm("" : "+r"(from_first.pairs));
    f(rows_of(from_first, [](std::size_t j) { return j; }));
  }
  // Lane j's candidate at mesh.pairs[pair(j)].
  template <class MeshSource, class Pair>
  static auto rows_of(const MeshSource& mesh, const Pair& pair) {
    return [mesh, pair](std::size_t j, int k, std::size_t part) {
      return Double::load_unaligned(mesh.positions.rows + row_starts<false>(mesh, pair(j))[k] + part);
    };
  }

  // Blocks of L::size columns, those from 0 to below `used`: lane j of
  // out[b + c] is element c of row(j, b), lane j's block from column b.
  template <std::size_t used, class Row>
  static void transpose_blocks(const Row& row, Double* out) {
    for (std::size_t block = 0; block < used; block += L::size) {
      Double rows[L::size];
      for (std::size_t j = 0; j < L::size; ++j) rows[j] = row(j, block);
      transpose(rows, out + block);
    }
  }

  // out[c] lane j = row[j] lane c, for c below the lane count (8, 4 or 2).
  static void transpose(const Double (&row)[L::size], Double* out) {
#ifdef __aarch64__
    out[0] = vzip1q_f64(row[0], row[1]);
    out[1] = vzip2q_f64(row[0], row[1]);
#else
    if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
      __m512d t[8], u[8];
      for (int i = 0; i < 8; i += 2) {
        t[i] = _mm512_unpacklo_pd(row[i], row[i + 1]);      // columns 0, 2, 4, 6 of rows i, i+1
        t[i + 1] = _mm512_unpackhi_pd(row[i], row[i + 1]);  // columns 1, 3, 5, 7
      }
      for (int i = 0; i < 8; i += 4)
        for (int odd = 0; odd < 2; ++odd) {
          u[i + odd] = _mm512_shuffle_f64x2(t[i + odd], t[i + 2 + odd], 0x88);      // columns 0|4 (1|5)
          u[i + 2 + odd] = _mm512_shuffle_f64x2(t[i + odd], t[i + 2 + odd], 0xdd);  // columns 2|6 (3|7)
        }
      for (int c = 0; c < 4; ++c) {
        out[c] = _mm512_shuffle_f64x2(u[c], u[c + 4], 0x88);
        out[c + 4] = _mm512_shuffle_f64x2(u[c], u[c + 4], 0xdd);
      }
    } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
      const __m256d t0 = _mm256_unpacklo_pd(row[0], row[1]), t1 = _mm256_unpackhi_pd(row[0], row[1]);
      const __m256d t2 = _mm256_unpacklo_pd(row[2], row[3]), t3 = _mm256_unpackhi_pd(row[2], row[3]);
      out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
      out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
      out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
      out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
    } else {
      out[0] = _mm_unpacklo_pd(row[0], row[1]);
      out[1] = _mm_unpackhi_pd(row[0], row[1]);
    }
#endif
  }
};

// op over values[0..n) as a balanced tree, unrolled at compile time: a
// chain of n - 1 dependent operations would be the kernel's critical path.
template <std::size_t n, class T, class Op>
[[gnu::always_inline]] inline T pairwise(const T* values, Op op) {
  if constexpr (n == 1) {
    return values[0];
  } else {
    return op(pairwise<n / 2>(values, op), pairwise<n - n / 2>(values + n / 2, op));
  }
}

// Bit k set where lane k of the mask is true.
template <class Arch>
std::uint32_t lane_bits(const xsimd::batch_bool<double, Arch>& mask) {
#ifdef __aarch64__
  // Each lane all ones or all zeros: its top bit, shifted into place.
  const uint64x2_t top = vshrq_n_u64(mask.data, 63);
  return static_cast<std::uint32_t>(vgetq_lane_u64(top, 0) | (vgetq_lane_u64(top, 1) << 1));
#else
  if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
    return static_cast<std::uint32_t>(mask.data);
  } else if constexpr (std::is_base_of_v<xsimd::avx, Arch>) {
    return static_cast<std::uint32_t>(_mm256_movemask_pd(mask.data));
  } else {
    return static_cast<std::uint32_t>(_mm_movemask_pd(mask.data));
  }
#endif
}

// Eight values compressed to those of the set bits of `keep` in a register
// and stored whole (AVX-512 only): the compress-store to memory is slow on
// some processors (microcoded on AMD Zen 4). Other sets write one value
// per set bit (compress).
#ifdef BATCHCCD_X86_LANES
template <class Arch, class Values>
std::size_t store_compressed(std::uint32_t keep, const Values& values, std::uint32_t* out) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_maskz_compress_epi32(static_cast<__mmask8>(keep), values));
  return static_cast<std::size_t>(__builtin_popcount(keep));
}
#endif

// Writes values[k] for every set bit k of `keep` (k < 8), in order; returns
// how many. `room`: out has room for all eight, which it may then write (a
// full group's, where what follows is yet to be written or already read).
template <class Arch>
std::size_t compress(std::uint32_t keep, const std::uint32_t* values, std::uint32_t* out,
                     [[maybe_unused]] bool room) {
#ifdef BATCHCCD_X86_LANES
  if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
    if (room) return store_compressed<Arch>(keep, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(values)), out);
  }
#endif
  std::uint32_t loaded[8];
  std::copy(values, values + 8, loaded);  // out may overlap values
  std::size_t n = 0;
  for (; keep != 0; keep &= keep - 1) out[n++] = loaded[__builtin_ctz(keep)];
  return n;
}

// The same for values first, first + 1, ..., first + 7.
template <class Arch>
std::size_t compress(std::uint32_t keep, std::uint32_t first, std::uint32_t* out, [[maybe_unused]] bool room) {
#ifdef BATCHCCD_X86_LANES
  if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
    if (room)
      return store_compressed<Arch>(keep,
                                    _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(first)),
                                                     _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)),
                                    out);
  }
#endif
  std::size_t n = 0;
  for (; keep != 0; keep &= keep - 1) out[n++] = first + static_cast<std::uint32_t>(__builtin_ctz(keep));
  return n;
}

// Largest component magnitudes, exact for vectors without a NaN. With a NaN
// component `largest` may miss it on AVX-512 (the range instruction passes
// over a quiet NaN): harmless where the value only bounds an expression
// that holds the NaN itself (the cubic's coefficients are NaN then, and
// no comparison with them culls). Where a NaN must show, as in a test of
// finiteness, `largest_or_nan` (bit patterns, as
// reference::largest_magnitude: their order agrees with that of
// non-negative doubles and puts a NaN above infinity).
template <class Arch>
struct Magnitudes {
  using L = Lanes<Arch>;
  using Index = typename L::Index;
  using Double = typename L::Double;
  using Vector = typename L::Vector;

  static Double largest(const Vector& v) {
    if constexpr (kRange) {
      return larger(larger(v.x, v.y), v.z);
    } else {
      return largest_or_nan(v);
    }
  }
  // Of two magnitudes (non-negative values).
  static Double larger(const Double& a, const Double& b) {
#ifdef BATCHCCD_X86_LANES
    if constexpr (kRange) {
      return _mm512_range_pd(a, b, 0b1011);  // max(|a|, |b|), sign cleared
    } else {
      return larger_or_nan(a, b);
    }
#else
    return larger_or_nan(a, b);
#endif
  }

  static Double largest_or_nan(const Vector& v) {
    return xsimd::bitwise_cast<Double>(xsimd::max(xsimd::max(bits(v.x), bits(v.y)), bits(v.z)));
  }
  static Double larger_or_nan(const Double& a, const Double& b) {
    return xsimd::bitwise_cast<Double>(xsimd::max(xsimd::bitwise_cast<Index>(a), xsimd::bitwise_cast<Index>(b)));
  }

 private:
  static constexpr bool kRange = std::is_base_of_v<xsimd::avx512dq, Arch>;
  static Index bits(const Double& x) { return xsimd::bitwise_cast<Index>(x) & Index(0x7fffffffffffffffll); }
};

// reference::scale_query, lane by lane, from loaded positions.
template <class Arch>
struct ScaledFrame {
  using L = Lanes<Arch>;
  using Double = typename L::Double;
  using Mask = typename L::Mask;
  using Vector = typename L::Vector;

  Vector relative[3][2];
  Double absolute_error;
  Mask evaluable;  // finite and not coincident: the filters may cull

  // reference::to_scaled_length, lane by lane.
  Double scaled_length(const Double& length) const {
    return xsimd::max(length_scale.apply(length * input_factor), Double(0x1p-1022));
  }

  // A group's positions loaded again (the kernels keep only differences).
  template <class Source>
  ScaledFrame(const Source& source, const ListedGroup<Arch>& group) {
    Vector x[4][2];
    Gather<Arch>::from(source, group, x);
    scale(x);
  }

 private:
  void scale(Vector (&x)[4][2]) {
    Double magnitude[8];
    for (int j = 0; j < 8; ++j) magnitude[j] = Magnitudes<Arch>::largest_or_nan((&x[0][0])[j]);
    const Double largest = pairwise<8>(magnitude, Magnitudes<Arch>::larger_or_nan);
    const Mask finite = largest <= Double(std::numeric_limits<double>::max());
    // Inputs near overflow quartered first. That is rare, so a group of
    // lanes without one skips the multiplications.
    const Mask huge = largest >= Double(reference::kHugeInput);
    input_factor = xsimd::select(huge, Double(0.25), Double(1.0));
    if (xsimd::any(huge)) {
      for (auto& point : x)
        for (Vector& p : point) p = {p.x * input_factor, p.y * input_factor, p.z * input_factor};
    }
    Double difference[6];
    for (int tau = 0; tau < 2; ++tau)
      for (int i = 0; i < 3; ++i) {
        relative[i][tau] = x[i + 1][tau] - x[0][tau];
        difference[2 * i + tau] = Magnitudes<Arch>::largest(relative[i][tau]);
      }
    const Double largest_difference = pairwise<6>(difference, Magnitudes<Arch>::larger);
    const Mask distinct = largest_difference > Double(0.0);
    const auto scale = L::inverse_power_of_two(xsimd::select(distinct, largest_difference, Double(1.0)));
    scale.scale(&relative[0][0], 6);
    length_scale = scale;
    // ScaledQuery::absolute_error: a quartered input's underflow floor
    // (twice 2^-1074), scaled with the differences, plus the scaling's own.
    absolute_error = xsimd::select(huge, scale.apply(Double(0x1p-1073)), Double(0.0)) + Double(0x1p-1074);
    evaluable = finite & distinct;
  }

  Double input_factor;
  typename L::PowerOfTwo length_scale;
};

// Whether a source's coordinates are all finite, known before its lanes
// run: a mesh's packed rows say so (PackedPositions); raw queries do not.
template <class Source>
constexpr bool kPacked = true;  // may know: a mesh's packed rows
template <Kind K>
constexpr bool kPacked<RawQueriesOf<K>> = false;
template <class Source>
bool known_finite(const Source& source) {
  if constexpr (kPacked<Source>) {
    return source.positions.finite;
  } else {
    return false;
  }
}

// A group's differences x_{i+2}(tau) - x_1(tau) in the input's units, each
// one's largest component magnitude, and the largest of all: the filters'
// direct frames (reference::run_filters).
template <class Arch>
struct DirectDifferences {
  using L = Lanes<Arch>;
  using Double = typename L::Double;

  typename L::Vector relative[3][2];
  Double largest[3][2];
  Double overall;
  bool finite_input;  // no coordinate of the source is a NaN or infinite

  template <class Source, class Group>
  DirectDifferences(const Source& source, const Group& group) : finite_input(known_finite(source)) {
    // Only the differences: the positions, kept for the rare scaled frame,
    // spilled to the stack throughout (it loads them again).
    Gather<Arch>::differences(source, group, relative);
    measure();
  }
  // Differences already taken.
  DirectDifferences(const typename L::Vector (&taken)[3][2], bool finite) : finite_input(finite) {
    std::copy(&taken[0][0], &taken[0][0] + 6, &relative[0][0]);
    measure();
  }

  // Lanes whose largest lies in [lowest, highest], so finite but for a NaN
  // `largest` may miss (Magnitudes): the sign filter's coefficients hold it
  // and cull nothing; other filters ask for within_without_nan.
  typename L::Mask within(double lowest, double highest) const {
    return (overall >= Double(lowest)) & (overall <= Double(highest));
  }
  // The same without a NaN. Within a window the differences are finite
  // and their sum cannot overflow, so it is NaN only through a NaN; of
  // finite coordinates no difference is a NaN at all.
  typename L::Mask within_without_nan(double lowest, double highest) const {
    if (finite_input) return within(lowest, highest);
    Double component[18];
    for (int v = 0; v < 6; ++v) {
      const auto& d = (&relative[0][0])[v];
      component[3 * v] = d.x, component[3 * v + 1] = d.y, component[3 * v + 2] = d.z;
    }
    const Double sum = pairwise<18>(component, [](const Double& a, const Double& b) { return a + b; });
    return within(lowest, highest) & (sum == sum);
  }

 private:
  void measure() {
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) largest[i][tau] = Magnitudes<Arch>::largest(relative[i][tau]);
    overall = pairwise<6>(&largest[0][0], Magnitudes<Arch>::larger);
  }
};

// Each lane's minimum separation (FilterSettings::separation_of).
template <class Arch, class Group>
typename Lanes<Arch>::Double lane_separations(const reference::FilterSettings& settings, const Group& group) {
  using Double = typename Lanes<Arch>::Double;
  if (settings.min_distances == nullptr) return Double(settings.min_distance);
  alignas(64) double values[Lanes<Arch>::size];
  for (std::size_t j = 0; j < Lanes<Arch>::size; ++j) values[j] = settings.min_distances[group[j]];
  return Double::load_aligned(values);
}

// What the first pass culls, bit k for lane k.
struct FirstCulls {
  std::uint32_t swept_box = 0;  // by the swept boxes
  std::uint32_t sign = 0;       // by the sign filter, of the lanes the boxes keep
};

// The first pass's verdicts in the scaled frame (reference::run_filters):
// the swept boxes, then the sign filter, whole step and halves. Rare, so
// out of line, where it costs the common path no registers; it loads the
// positions again.
template <class Arch, class Source>
[[gnu::noinline, gnu::flatten]] FirstCulls first_culled_in_scaled_frame(
    const Source& source, const ListedGroup<Arch>& group, const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  using Mask = typename Lanes<Arch>::Mask;
  const ScaledFrame<Arch> frame(source, group);
  const Double separation =
      settings.within ? frame.scaled_length(lane_separations<Arch>(settings, group)) : Double(0.0);
  FirstCulls culled;
  if (settings.swept_box && settings.within) {
    culled.swept_box = lane_bits<Arch>(
        frame.evaluable &
        reference::swept_boxes_apart(source.kind, frame.relative, true, separation, frame.absolute_error));
  } else if (settings.swept_box) {
    // Without a separation the direct frame's boxes, for finite input.
    typename Lanes<Arch>::Vector relative[3][2];
    Gather<Arch>::differences(source, group, relative);
    culled.swept_box =
        lane_bits<Arch>(frame.evaluable & reference::swept_boxes_apart(source.kind, relative, false, Double(0.0)));
  }
  if (!settings.sign) return culled;
  Double largest[3][2];
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau)
      largest[i][tau] = Magnitudes<Arch>::largest(frame.relative[i][tau]);
  const Double floor = reference::coefficient_floor(frame.absolute_error);
  const Mask sign = settings.within ? Mask(reference::plane_distance_culls(source.kind, frame.relative, largest, floor,
                                                                          settings.certified, separation))
                                    : Mask(reference::sign_filter_culls(frame.relative, largest, floor,
                                                                        settings.certified, settings.subdivide));
  culled.sign = lane_bits<Arch>(sign & frame.evaluable) & ~culled.swept_box;
  return culled;
}

// A consecutive group's list made in here, out of the common path (made
// there, its values stayed live across the whole kernel, on the stack).
template <class Arch, class Source>
[[gnu::noinline]] FirstCulls first_culled_in_scaled_frame(const Source& source, const ConsecutiveGroup<Arch>& group,
                                                          const reference::FilterSettings& settings) {
  return first_culled_in_scaled_frame<Arch>(source, listed(group), settings);
}

// The separation filter's, likewise.
template <class Arch, class Source>
[[gnu::noinline, gnu::flatten]] std::uint32_t separation_culled_in_scaled_frame(
    const Source& source, const ListedGroup<Arch>& group, const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  using Mask = typename Lanes<Arch>::Mask;
  const ScaledFrame<Arch> frame(source, group);
  // reference::separation_error, lane by lane.
  const reference::SeparationErrorModel error = reference::separation_error(0.0, settings.certified);
  const Mask enabled = settings.certified ? Mask(frame.absolute_error <= Double(0x1p-900)) : Mask(true);
  const Mask culled =
      settings.within
          ? Mask(reference::separation_filter_culls_within(
                reference::separation_kind(source.kind, settings), frame.relative, Double(error.relative),
                Double(error.floor),
                frame.scaled_length(lane_separations<Arch>(settings, group))))
          : Mask(reference::separation_filter_culls(reference::separation_kind(source.kind, settings), frame.relative,
                                                    Double(error.relative),
                                                    Double(error.floor)));
  return lane_bits<Arch>(culled & enabled & frame.evaluable);
}

// The first pass, over every candidate of a group (`count` <= lane count of
// them in use): the swept boxes, then the sign filter certainly (or,
// uncertified, plainly) on the whole interval. Lanes past count are never
// culled. Frames as in reference::run_filters: direct where the differences
// lie in its window; elsewhere (rare: only groups with such a lane pay) the
// scaled frame's, the sign filter's halves included there.
// Within: a call with separations (FilterSettings::within), the sign
// filter as the distance to the plane or line pair.
template <class Arch, bool within, class Source, class Group>
[[gnu::flatten]] FirstCulls whole_interval_culled_lanes(const Source& source, const Group& group, std::size_t count,
                                                        const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  const DirectDifferences<Arch> differences(source, group);
  const auto direct = differences.within(reference::kDirectLowest, reference::kDirectHighest);
  const std::uint32_t lanes_in_use = (1u << count) - 1;
  const Double separation = within ? lane_separations<Arch>(settings, group) : Double(0.0);
  FirstCulls culled;
  // A NaN may pass `direct` (Magnitudes): the boxes, which would not see
  // it, ask for none.
  if (settings.swept_box)
    culled.swept_box =
        lanes_in_use & lane_bits<Arch>(differences.within_without_nan(reference::kDirectLowest,
                                                                      reference::kDirectHighest) &
                                       reference::swept_boxes_apart(source.kind, differences.relative, within,
                                                                    separation));
  // On a padded list the boxes alone settle most groups: the sign test
  // only where a lane is left.
  if (settings.sign && culled.swept_box != lanes_in_use) {
    const Double floor(reference::direct_coefficient_error().floor);
    if constexpr (within) {
      culled.sign = lane_bits<Arch>(direct & reference::plane_distance_culls(source.kind, differences.relative,
                                                                             differences.largest, floor,
                                                                             settings.certified, separation));
    } else {
      const auto test =
          reference::sign_test(differences.relative, differences.largest, floor, settings.certified);
      culled.sign = lane_bits<Arch>(direct & test.whole());
    }
  }
  const std::uint32_t scaled_lanes = ~lane_bits<Arch>(direct) & lanes_in_use;
  if (scaled_lanes != 0) {
    const FirstCulls scaled = first_culled_in_scaled_frame<Arch>(source, group, settings);
    culled.swept_box |= scaled_lanes & scaled.swept_box;
    culled.sign |= scaled_lanes & scaled.sign;
  }
  culled.sign &= lanes_in_use & ~culled.swept_box;
  return culled;
}

// A bound of the boxes' threshold at a separation (SweptBoxes::threshold,
// direct frame) for every candidate of a mesh whose coordinates are at most
// m in magnitude (MeshPositions::largest): a lane whose widest gap exceeds
// it is culled by the exact test too, which it need not measure. Each
// coordinate of the frame is one rounded difference of two of the mesh's,
// so at most fl(2m) = 2m in magnitude, and so is `largest`; the threshold
// is rounded sums and products of `largest` and the separation, each
// monotonic in its operands, so the same expression of 2m is at least the
// lane's. Such a lane lies in the direct frame's window as well: its
// `largest` is at most 2m, below 2^200 for m at most 2^199 (beyond, the
// bound is infinite and no lane passes), and at least half its widest gap
// (a rounded difference of two coordinates, at most 2 `largest`), so
// above 2^-200 once the bound is at least 2^-199. A NaN separation keeps
// its NaN bound, which no gap exceeds, as none exceeds its threshold.
template <class Arch, class Source>
typename Lanes<Arch>::Double threshold_bound(const Source& source, const typename Lanes<Arch>::Double& separation) {
  using Double = typename Lanes<Arch>::Double;
  const double m = source.positions.largest;
  if (!(m <= 0x1p199)) return Double(std::numeric_limits<double>::infinity());
  const Double bound = reference::SweptBoxes<Double>{Double(0.0), Double(2 * m)}.threshold(true, separation);
  return xsimd::select(bound < Double(0x1p-199), Double(0x1p-199), bound);
}

// The first pass on a source known finite (a mesh's packed rows say so):
// the boxes on the differences alone, before anything is measured, and
// the sign filter, its frame's window and the scaled frame only for groups
// with a lane left. Without a separation the boxes hold in the direct frame
// whatever the magnitudes (reference::run_filters); with one only in its
// window, which the boxes' own largest magnitude tells (SweptBoxes::largest:
// for finite input DirectDifferences::overall, bit for bit). `shared_bound`:
// threshold_bound for a separation shared by every candidate, taken once a
// call (nullptr with one per candidate).
template <class Arch, bool within, class Source, class Group>
[[gnu::flatten]] FirstCulls finite_whole_interval_culled_lanes(const Source& source, const Group& group,
                                                               std::size_t count,
                                                               const reference::FilterSettings& settings,
                                                               const typename Lanes<Arch>::Double* shared_bound) {
  using Double = typename Lanes<Arch>::Double;
  const auto in_window = [](const Double& largest) {
    return (largest >= Double(reference::kDirectLowest)) & (largest <= Double(reference::kDirectHighest));
  };
  // The bound before the loads: a branch between them and the boxes kept
  // the differences on the stack.
  const Double bound = !within                 ? Double(0.0)
                       : shared_bound != nullptr ? *shared_bound
                                                 : threshold_bound<Arch>(source, lane_separations<Arch>(settings, group));
  typename Lanes<Arch>::Vector relative[3][2];
  Gather<Arch>::differences(source, group, relative);
  const std::uint32_t lanes_in_use = (1u << count) - 1;
  FirstCulls culled;
  if (settings.swept_box) {
    if constexpr (within) {
      // Most groups settle on the mesh's bound alone (threshold_bound);
      // the others take the exact test.
      const auto boxes = reference::swept_boxes(source.kind, relative);
      culled.swept_box = lanes_in_use & lane_bits<Arch>(boxes.widest > bound);
      if (culled.swept_box != lanes_in_use)
        culled.swept_box = lanes_in_use & lane_bits<Arch>(in_window(boxes.largest) &
                                                          boxes.apart(true, lane_separations<Arch>(settings, group)));
    } else {
      culled.swept_box = lanes_in_use & lane_bits<Arch>(reference::swept_boxes_apart(source.kind, relative, false,
                                                                                     Double(0.0)));
    }
    if (culled.swept_box == lanes_in_use) return culled;
  }
  // With a separation the scaled frame's boxes too, for lanes outside the window.
  if (!settings.sign && !within) return culled;
  const DirectDifferences<Arch> differences(relative, true);
  const auto direct = in_window(differences.overall);
  if (settings.sign) {
    const Double floor(reference::direct_coefficient_error().floor);
    if constexpr (within) {
      culled.sign = lane_bits<Arch>(direct & reference::plane_distance_culls(
                                                 source.kind, differences.relative, differences.largest, floor,
                                                 settings.certified, lane_separations<Arch>(settings, group)));
    } else {
      const auto test = reference::sign_test(differences.relative, differences.largest, floor, settings.certified);
      culled.sign = lane_bits<Arch>(direct & test.whole());
    }
  }
  const std::uint32_t scaled_lanes = ~lane_bits<Arch>(direct) & lanes_in_use & ~culled.swept_box;
  if (scaled_lanes != 0) {
    const FirstCulls scaled = first_culled_in_scaled_frame<Arch>(source, group, settings);
    if constexpr (within) culled.swept_box |= scaled_lanes & scaled.swept_box;
    culled.sign |= scaled_lanes & scaled.sign;
  }
  culled.sign &= lanes_in_use & ~culled.swept_box;
  return culled;
}

// What the second pass culls, bit k for lane k.
struct LaterCulls {
  std::uint32_t sign = 0;        // by the sign filter's halves
  std::uint32_t separation = 0;  // by the separation filter, of the lanes the halves keep
};

// The second pass, over the first one's survivors: the sign filter's halves
// in its direct frame (lanes in the scaled frame had the whole filter in the
// first pass), then the separation filter in its own frames.
template <class Arch, class Source>
[[gnu::flatten]] LaterCulls later_culled_lanes(const Source& source, const ListedGroup<Arch>& group,
                                               std::size_t count, const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  const DirectDifferences<Arch> differences(source, group);
  const std::uint32_t lanes_in_use = (1u << count) - 1;
  LaterCulls culled;
  if (settings.sign && settings.subdivide && !settings.within) {
    const auto direct = differences.within(reference::kDirectLowest, reference::kDirectHighest);
    const auto test = reference::sign_test(differences.relative, differences.largest,
                                           Double(reference::direct_coefficient_error().floor),
                                           settings.certified);
    culled.sign = lane_bits<Arch>(direct & test.halves()) & lanes_in_use;
  }
  if (settings.separation) {
    const auto direct = differences.within_without_nan(reference::kSeparationDirectLowest,
                                                       reference::kSeparationDirectHighest);
    const reference::SeparationErrorModel error = reference::separation_error(0.0, settings.certified);
    const std::uint32_t kept = ~culled.sign & lanes_in_use;
    const auto culls =
        settings.within
            ? reference::separation_filter_culls_within(reference::separation_kind(source.kind, settings),
                                                        differences.relative, Double(error.relative),
                                                        Double(error.floor), lane_separations<Arch>(settings, group))
            : reference::separation_filter_culls(reference::separation_kind(source.kind, settings),
                                                 differences.relative, Double(error.relative),
                                                 Double(error.floor));
    culled.separation = kept & lane_bits<Arch>(direct & culls);
    const std::uint32_t scaled_lanes = ~lane_bits<Arch>(direct) & kept;
    if (scaled_lanes != 0)
      culled.separation |= scaled_lanes & separation_culled_in_scaled_frame<Arch>(source, group, settings);
  }
  return culled;
}

// What the third pass says: bit k of `culled` set when the pieces cull lane
// k, and free[k] lane k's pieces free of contact (bit j for piece j; 0 for
// a lane the pieces do not take).
struct PiecesCulls {
  std::uint32_t culled = 0;
  std::uint8_t free[8] = {};
};

// The pieces over one frame's differences, for the lanes `open` (bits):
// `error` the separation filter's error model there, `sign_floor` the sign
// test's floor, `separation` in the frame's units.
template <class Arch, class Source>
[[gnu::always_inline]] inline PiecesCulls pieces_of(
    const Source& source, std::uint32_t open, const typename Lanes<Arch>::Vector (&relative)[3][2],
    const typename Lanes<Arch>::Double (&largest)[3][2], const reference::SeparationErrorModel& error,
    typename Lanes<Arch>::Double sign_floor, typename Lanes<Arch>::Double separation,
    const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  const Kind kind = reference::separation_kind(source.kind, settings);
  const reference::SeparationMeasures<Double> measured =
      reference::separation_measures(kind, relative, Double(error.relative), Double(error.floor));
  reference::SignTest<Double> test{};
  if (settings.sign) test = reference::sign_test(relative, largest, sign_floor, settings.certified);
  const auto verdicts = reference::piece_verdicts(settings.pieces, kind, relative, measured, Double(error.relative),
                                                 Double(error.floor), settings.sign ? &test : nullptr, largest,
                                                 settings.certified, settings.within, separation);
  PiecesCulls culls;
  culls.culled = open;
  for (int j = 0; j < verdicts.count; ++j) {
    const std::uint32_t free = open & lane_bits<Arch>(verdicts.free[j]);
    culls.culled &= free;
    for (std::uint32_t lanes = free; lanes != 0; lanes &= lanes - 1)
      culls.free[__builtin_ctz(lanes)] |= static_cast<std::uint8_t>(1u << j);
  }
  return culls;
}

// The pieces for lanes outside the separation filter's direct window, in
// the scaled frame, as that filter takes them (rare: only groups with such
// a lane pay).
template <class Arch, class Source>
[[gnu::noinline, gnu::flatten]] PiecesCulls pieces_in_scaled_frame(const Source& source,
                                                                    const ListedGroup<Arch>& group,
                                                                    std::uint32_t lanes,
                                                                    const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  using Mask = typename Lanes<Arch>::Mask;
  const ScaledFrame<Arch> frame(source, group);
  // reference::separation_error, lane by lane.
  const Mask enabled = settings.certified ? Mask(frame.absolute_error <= Double(0x1p-900)) : Mask(true);
  const std::uint32_t open = lanes & lane_bits<Arch>(frame.evaluable & enabled);
  if (open == 0) return {};
  Double largest[3][2];
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau) largest[i][tau] = Magnitudes<Arch>::largest(frame.relative[i][tau]);
  const Double separation =
      settings.within ? frame.scaled_length(lane_separations<Arch>(settings, group)) : Double(0.0);
  return pieces_of<Arch>(source, open, frame.relative, largest, reference::separation_error(0.0, settings.certified),
                         reference::coefficient_floor(frame.absolute_error), separation, settings);
}

// The third pass, over the second one's survivors, in the frames the
// separation filter took (reference::run_filters). A pass of its own, in
// full lanes: run on the second pass's groups, nearly half of them had a
// lane left to test (of eight), and paid for all eight. The whole-step
// bounds are computed again, as the filters compute them.
template <class Arch, class Source>
[[gnu::flatten]] PiecesCulls pieces_culled_lanes(const Source& source, const ListedGroup<Arch>& group,
                                                 std::size_t count, const reference::FilterSettings& settings) {
  using Double = typename Lanes<Arch>::Double;
  const DirectDifferences<Arch> differences(source, group);
  const std::uint32_t in_use = (1u << count) - 1;
  const std::uint32_t direct = in_use & lane_bits<Arch>(differences.within_without_nan(
                                            reference::kSeparationDirectLowest, reference::kSeparationDirectHighest));
  PiecesCulls culls;
  if (direct != 0)
    culls = pieces_of<Arch>(source, direct, differences.relative, differences.largest,
                            reference::separation_error(0.0, settings.certified),
                            Double(reference::direct_coefficient_error().floor),
                            settings.within ? lane_separations<Arch>(settings, group) : Double(0.0), settings);
  if (const std::uint32_t scaled = in_use & ~direct; scaled != 0) {
    const PiecesCulls other = pieces_in_scaled_frame<Arch>(source, group, scaled, settings);
    culls.culled |= other.culled;
    for (std::size_t lane = 0; lane < count; ++lane) culls.free[lane] |= other.free[lane];
  }
  return culls;
}

// Candidates [first, first + count) checked for ids the mesh does not have
// (sources.hpp, IndexOutOfRange). A full group in vector lanes straight
// from the candidate list (ids as unsigned: negative ones are huge), a
// scalar test per id costing the kernel a fifth of its speed; a batch's
// last, partial group id by id. Inlined into the batch loop: a call per
// group cost 1 to 5 % (./dev ab, 7 rounds).
template <class Arch, Kind K>
void check_ids(const RawQueriesOf<K>&, std::size_t, std::size_t) {}  // nothing to index

// Ids are ints: below count when, as unsigned, below count capped at 2^31.
// Always inlined, like every non-template here: the kernel files are
// compiled with different instruction sets, and one out-of-line copy would
// be shared by all of them.
[[gnu::always_inline]] inline std::uint32_t id_limit(std::int64_t count) {
  return static_cast<std::uint32_t>(std::min<std::int64_t>(count, std::int64_t{1} << 31));
}

template <class Arch>
[[gnu::always_inline]] inline void check_ids(const MeshEdgeEdge& mesh, std::size_t first,
                                             std::size_t count) {
  using Ids = xsimd::batch<std::uint32_t, Arch>;  // two candidates' four ids each
  static_assert(4 * Lanes<Arch>::size == 2 * Ids::size);
  if (count < Lanes<Arch>::size) {
    for (std::size_t i = first; i < first + count; ++i) row_starts(mesh, i);
    return;
  }
  const auto* ids = reinterpret_cast<const std::uint32_t*>(mesh.pairs[first].data());
  const Ids limit(id_limit(mesh.positions.vertices));
  if (xsimd::any((Ids::load_unaligned(ids) >= limit) | (Ids::load_unaligned(ids + Ids::size) >= limit)))
    throw IndexOutOfRange{};
}

template <class Arch>
[[gnu::always_inline]] inline void check_ids(const MeshVertexFace& mesh, std::size_t first,
                                             std::size_t count) {
  using Pairs = xsimd::batch<std::uint64_t, Arch>;  // a candidate's (vertex, face)
  static_assert(Lanes<Arch>::size == Pairs::size);
  if (count < Lanes<Arch>::size) {
    for (std::size_t i = first; i < first + count; ++i) row_starts(mesh, i);
    return;
  }
  const Pairs pair = Pairs::load_unaligned(reinterpret_cast<const std::uint64_t*>(mesh.pairs[first].data()));
  if (xsimd::any(((pair & Pairs(0xffffffffu)) >= Pairs(id_limit(mesh.positions.vertices))) |
                 ((pair >> 32) >= Pairs(id_limit(mesh.faces.count)))))
    throw IndexOutOfRange{};
}

// The candidate list read ahead: a mesh's id lists stream from memory (16
// bytes a candidate, edge pairs), and the hardware's prefetcher alone left
// the first pass waiting on them. An address, never dereferenced: past the
// end of the list it is harmless. Raw queries prefetch their own rows
// (Gather::query_rows).
template <class Arch, Kind K>
void prefetch_candidates(const RawQueriesOf<K>&, std::size_t) {}
template <class Arch, class MeshSource>
[[gnu::always_inline]] inline void prefetch_candidates(const MeshSource& mesh, std::size_t first) {
  constexpr std::size_t kAhead = 256;  // candidates: 4 KB of edge pairs
  constexpr std::size_t kBytes = Lanes<Arch>::size * sizeof(mesh.pairs[0]);
  const auto ahead = reinterpret_cast<std::uintptr_t>(mesh.pairs + first + kAhead);
  for (std::size_t line = 0; line < kBytes; line += 64)
    prefetch(ahead + line);
}

// The first pass over candidates [begin, end), compacting its survivors:
// `finite` for a source known finite.
template <class Arch, bool within, bool finite, class Source>
std::size_t first_pass(const Source& source, std::size_t begin, std::size_t end,
                       const reference::FilterSettings& settings, std::uint32_t* survivors, FilterCounts& counts) {
  constexpr std::size_t lanes = Lanes<Arch>::size;
  using Double = typename Lanes<Arch>::Double;
  Double shared_bound_value(0.0);
  const Double* shared_bound = nullptr;
  if constexpr (finite && within) {
    if (settings.min_distances == nullptr) {
      shared_bound_value = threshold_bound<Arch>(source, Double(settings.min_distance));
      shared_bound = &shared_bound_value;
    }
  }
  const auto culled_lanes = [&](const auto& group, std::size_t count) {
    if constexpr (finite) {
      return finite_whole_interval_culled_lanes<Arch, within>(source, group, count, settings, shared_bound);
    } else {
      return whole_interval_culled_lanes<Arch, within>(source, group, count, settings);
    }
  };
  std::size_t kept = 0;
  const auto keep = [&](const FirstCulls& culls, std::size_t first, std::size_t count) {
    counts.swept_box += static_cast<std::size_t>(__builtin_popcount(culls.swept_box));
    counts.sign += static_cast<std::size_t>(__builtin_popcount(culls.sign));
    const std::uint32_t culled = culls.swept_box | culls.sign;
    const auto offset = static_cast<std::uint32_t>(first - begin);
    kept += compress<Arch>(~culled & ((1u << count) - 1), offset, survivors + kept, count == lanes);
  };
  std::size_t first = begin;
#ifdef BATCHCCD_X86_LANES
  if constexpr (kPacked<Source> && kCoarseBoxes<Arch>) {
    // Two groups at a time through the coarse boxes first (sixteen
    // candidates on AVX-512, eight on AVX2): a group they settle needs
    // nothing more (coarse_boxes.hpp). They pay only where they settle
    // most groups (a padded list: nine in ten), so a batch's first sixteen
    // groups try them, and where they settle fewer than half of those (a
    // tight list) the rest of the batch goes without.
    if (settings.swept_box && source.positions.coarse != nullptr) {
      using Coarse = CoarseBoxes<Arch, Source>;
      static_assert(Coarse::size == 2 * lanes);
      constexpr std::uint32_t all = (1u << lanes) - 1;
      const typename Coarse::Float separation = Coarse::separations(nullptr, within ? settings.min_distance : 0.0);
      // The groups at `at` and at + lanes; how many of them it settled.
      const auto coarse_pair = [&](std::size_t at) {
        for (std::size_t half = 0; half < 2; ++half) {
          prefetch_candidates<Arch>(source, at + half * lanes);
          check_ids<Arch>(source, at + half * lanes, lanes);
        }
        const bool each = within && settings.min_distances != nullptr;
        const std::uint32_t apart =
            Coarse::apart(source, at, each ? Coarse::separations(settings.min_distances + at, 0) : separation);
        int settled = 0;
        for (std::size_t half = 0; half < 2; ++half) {
          const std::size_t group = at + half * lanes;
          const bool settles = ((apart >> (half * lanes)) & all) == all;
          settled += settles;
          keep(settles ? FirstCulls{.swept_box = all}
                       : culled_lanes(ConsecutiveGroup<Arch>{static_cast<std::int64_t>(group)}, lanes),
               group, lanes);
        }
        return settled;
      };
      constexpr int kTrial = 8;  // pairs of groups
      int tried = 0, settled = 0;
      for (; tried < kTrial && first + 2 * lanes <= end; ++tried, first += 2 * lanes) settled += coarse_pair(first);
      if (settled >= kTrial)
        for (; first + 2 * lanes <= end; first += 2 * lanes) coarse_pair(first);
    }
  }
#endif
  for (; first < end; first += lanes) {
    const std::size_t count = std::min(end - first, lanes);
    prefetch_candidates<Arch>(source, first);
    check_ids<Arch>(source, first, count);  // every candidate passes here first, whatever the settings
    FirstCulls culls;
    if ((settings.sign || settings.swept_box) && count == lanes) {
      culls = culled_lanes(ConsecutiveGroup<Arch>{static_cast<std::int64_t>(first)}, count);
    } else if (settings.sign || settings.swept_box) {
      ListedGroup<Arch> group;  // the last few; spare lanes repeat the last
      for (std::size_t j = 0; j < lanes; ++j)
        group.candidate[j] = static_cast<std::int64_t>(first + std::min(j, count - 1));
      culls = culled_lanes(group, count);
    }
    keep(culls, first, count);
  }
  return kept;
}

// The filters over candidates [begin, end): see FilterFunction. The first
// pass runs over all of them and compacts its survivors; the second runs
// over those alone, in full lanes, and compacts them again; the third
// (pieces, swept boxes) likewise over the second's.
template <class Arch, bool within, class Source>
std::size_t filter_range_of(const Source& source, std::size_t begin, std::size_t end,
                            const reference::FilterSettings& settings, std::uint32_t* survivors,
                            std::uint8_t* free_pieces, FilterCounts& counts) {
  constexpr std::size_t lanes = Lanes<Arch>::size;
  std::size_t kept = 0;
  if constexpr (kPacked<Source>) {
    kept = known_finite(source) ? first_pass<Arch, within, true>(source, begin, end, settings, survivors, counts)
                                : first_pass<Arch, within, false>(source, begin, end, settings, survivors, counts);
  } else {
    kept = first_pass<Arch, within, false>(source, begin, end, settings, survivors, counts);
  }
  // Survivors regrouped into full lanes, pass after pass: `cull` culls
  // lanes of a group (counting them) and writes the others from
  // survivors + kept on, returning how many. In place: a group is read
  // before anything is written over it.
  const auto pass = [&](const auto& cull) {
    const std::size_t given = kept;
    kept = 0;
    std::uint32_t offsets[8] = {};  // survivors' indices relative to begin, lane by lane
    for (std::size_t first = 0; first < given; first += lanes) {
      const std::size_t count = std::min(given - first, lanes);
      ListedGroup<Arch> group;
      for (std::size_t j = 0; j < lanes; ++j) {
        offsets[j] = survivors[first + std::min(j, count - 1)];
        group.candidate[j] = static_cast<std::int64_t>(begin + offsets[j]);
      }
      kept += cull(group, offsets, count);
    }
  };
  if ((settings.sign && settings.subdivide && !within) || settings.separation)
    pass([&](const ListedGroup<Arch>& group, const std::uint32_t* offsets, std::size_t count) {
      const LaterCulls culled = later_culled_lanes<Arch>(source, group, count, settings);
      counts.sign += static_cast<std::size_t>(__builtin_popcount(culled.sign));
      counts.separation += static_cast<std::size_t>(__builtin_popcount(culled.separation));
      const std::uint32_t keep = ~(culled.sign | culled.separation) & ((1u << count) - 1);
      return compress<Arch>(keep, offsets, survivors + kept, count == lanes);
    });
  if (!(settings.separation && settings.pieces > 1)) {
    std::fill(free_pieces, free_pieces + kept, std::uint8_t{0});
    return kept;
  }
  // The pieces' survivors (few) keep their free pieces beside them.
  pass([&](const ListedGroup<Arch>& group, const std::uint32_t* offsets, std::size_t count) {
    const PiecesCulls culls = pieces_culled_lanes<Arch>(source, group, count, settings);
    counts.pieces += static_cast<std::size_t>(__builtin_popcount(culls.culled));
    std::size_t stored = 0;
    for (std::uint32_t keep = ~culls.culled & ((1u << count) - 1); keep != 0; keep &= keep - 1, ++stored) {
      const int lane = __builtin_ctz(keep);
      survivors[kept + stored] = offsets[lane];
      free_pieces[kept + stored] = culls.free[lane];
    }
    return stored;
  });
  return kept;
}

// A kernel for calls with separations and one for those without, each
// compiled for its own: the common one keeps its instructions.
template <class Arch, class Source>
std::size_t filter_range(const Source& source, std::size_t begin, std::size_t end,
                         const reference::FilterSettings& settings, std::uint32_t* survivors,
                         std::uint8_t* free_pieces, FilterCounts& counts) {
  if (settings.within)
    return filter_range_of<Arch, true>(source, begin, end, settings, survivors, free_pieces, counts);
  return filter_range_of<Arch, false>(source, begin, end, settings, survivors, free_pieces, counts);
}

// Raw queries: the kind picked once a call, so that each kernel knows it.
template <class Arch>
std::size_t filter_range_raw(const RawQueries& raw, std::size_t begin, std::size_t end,
                             const reference::FilterSettings& settings, std::uint32_t* survivors,
                             std::uint8_t* free_pieces, FilterCounts& counts) {
  if (raw.kind == Kind::vertex_face)
    return filter_range<Arch>(RawQueriesOf<Kind::vertex_face>{raw.queries, raw.stream}, begin, end, settings,
                              survivors, free_pieces, counts);
  return filter_range<Arch>(RawQueriesOf<Kind::edge_edge>{raw.queries, raw.stream}, begin, end, settings,
                            survivors, free_pieces, counts);
}

template <class Arch>
FilterKernels make_kernels(Isa isa) {
  return {isa, &filter_range_raw<Arch>, &filter_range<Arch, MeshVertexFace>,
          &filter_range<Arch, MeshEdgeEdge>};
}

}  // namespace batchccd::simd

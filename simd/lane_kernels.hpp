#pragma once

// The lane filter, written once over xsimd's batch type and instantiated per
// instruction set by the kernel_*.cpp files (each compiled with its own
// flags). It mirrors the scalar reference path operation for operation —
// reference::scale_query, then reference::sign_filter_culls — so both make
// the same cull decision bit for bit (tests/test_simd.cpp holds them
// together). Include only from those translation units.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <immintrin.h>

#include <xsimd/xsimd.hpp>

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/filter.hpp"
#include "reference/separation_filter.hpp"
#include "reference/scaled_query.hpp"
#include "reference/sign_filter.hpp"
#include "simd/filter.hpp"
#include "simd/sources.hpp"

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

// Loads candidate `candidate[j]` of a source into lane j of x[k][tau]
// (DESIGN.md's x_{k+1} at t = tau).
template <class Arch>
struct Gather {
  using L = Lanes<Arch>;
  using Double = typename L::Double;
  using Index = typename L::Index;
  using Vector = typename L::Vector;
  using Candidates = std::int64_t[L::size];

  // The processor's gather instruction where it has one (xsimd 8.1 loads
  // lane by lane).
  static Double gather(const double* base, const Index& index) {
    if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
      return _mm512_i64gather_pd(index, base, 8);
    } else if constexpr (std::is_base_of_v<xsimd::avx2, Arch>) {
      return _mm256_i64gather_pd(base, index, 8);
    } else {
      return Double::gather(base, index);
    }
  }

  using Rows = const double* [L::size];

  static void from(const RawQueries& raw, const Candidates& candidate, Vector (&x)[4][2]) {
    const double* data = raw.queries[0].points[0].data();
    constexpr int doubles_per_query = 24;
    Double coordinate[doubles_per_query];
    // Consecutive queries (indices only ever increase) lie in one block of
    // rows: loads and transposes. Otherwise gathers.
    if (candidate[L::size - 1] - candidate[0] == static_cast<std::int64_t>(L::size - 1)) {
      for (std::size_t block = 0; block < doubles_per_query; block += L::size) {
        Rows rows;
        for (std::size_t j = 0; j < L::size; ++j) rows[j] = data + (candidate[0] + j) * doubles_per_query + block;
        transpose(rows, coordinate + block);
      }
    } else {
      alignas(64) std::int64_t offset[L::size];
      for (std::size_t j = 0; j < L::size; ++j) offset[j] = candidate[j] * doubles_per_query;
      const Index index = Index::load_aligned(offset);
      for (int c = 0; c < doubles_per_query; ++c) coordinate[c] = gather(data + c, index);
    }
    for (int k = 1; k <= 4; ++k)
      for (int tau = 0; tau < 2; ++tau) {
        const Double* c = coordinate + 3 * (reference::point_index(raw.kind, k) + 4 * tau);
        x[k - 1][tau] = {c[0], c[1], c[2]};
      }
  }

  template <class MeshSource>
  static void from(const MeshSource& mesh, const Candidates& candidate, Vector (&x)[4][2]) {
    alignas(64) std::int64_t ids[4][L::size];
    for (std::size_t j = 0; j < L::size; ++j) {
      const auto vertices = vertex_ids(mesh, static_cast<std::size_t>(candidate[j]));
      for (int k = 0; k < 4; ++k) ids[k][j] = vertices[k];
    }
    const double* packed = mesh.positions.rows;
    for (int k = 0; k < 4; ++k) {
      Double coordinate[kRowDoubles];
      for (std::size_t part = 0; part < 6; part += L::size) {  // the row's six coordinates
        Rows rows;
        for (std::size_t j = 0; j < L::size; ++j) rows[j] = packed + kRowDoubles * ids[k][j] + part;
        transpose(rows, coordinate + part);
      }
      x[k][0] = {coordinate[0], coordinate[1], coordinate[2]};
      x[k][1] = {coordinate[3], coordinate[4], coordinate[5]};
    }
  }

  // out[c] lane j = rows[j][c] for c below the lane count (8, 4 or 2).
  static void transpose(const Rows& rows, Double* out) {
    if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
      __m512d r[8], t[8], u[8];
      for (int i = 0; i < 8; ++i) r[i] = _mm512_loadu_pd(rows[i]);
      for (int i = 0; i < 8; i += 2) {
        t[i] = _mm512_unpacklo_pd(r[i], r[i + 1]);      // columns 0, 2, 4, 6 of rows i, i+1
        t[i + 1] = _mm512_unpackhi_pd(r[i], r[i + 1]);  // columns 1, 3, 5, 7
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
      __m256d r[4];
      for (int i = 0; i < 4; ++i) r[i] = _mm256_loadu_pd(rows[i]);
      const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
      const __m256d t2 = _mm256_unpacklo_pd(r[2], r[3]), t3 = _mm256_unpackhi_pd(r[2], r[3]);
      out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
      out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
      out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
      out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
    } else {
      const __m128d r0 = _mm_loadu_pd(rows[0]), r1 = _mm_loadu_pd(rows[1]);
      out[0] = _mm_unpacklo_pd(r0, r1);
      out[1] = _mm_unpackhi_pd(r0, r1);
    }
  }
};

// op over all n values as a balanced tree: a chain of n - 1 dependent
// operations would be the kernel's critical path. Overwrites `values`.
template <class T, std::size_t n, class Op>
T pairwise(T (&values)[n], Op op) {
  for (std::size_t width = n; width > 1; width = (width + 1) / 2) {
    for (std::size_t i = 0; i < width / 2; ++i) values[i] = op(values[2 * i], values[2 * i + 1]);
    if (width % 2 == 1) values[width / 2] = values[width - 1];
  }
  return values[0];
}

// Bit k set where lane k of the mask is true.
template <class Arch>
std::uint32_t lane_bits(const xsimd::batch_bool<double, Arch>& mask) {
  if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
    return static_cast<std::uint32_t>(mask.data);
  } else if constexpr (std::is_base_of_v<xsimd::avx, Arch>) {
    return static_cast<std::uint32_t>(_mm256_movemask_pd(mask.data));
  } else {
    return static_cast<std::uint32_t>(_mm_movemask_pd(mask.data));
  }
}

// Writes values[k] for every set bit k of `keep` (k < 8), in order; returns
// how many.
template <class Arch>
std::size_t compress(std::uint32_t keep, const std::uint32_t* values, std::uint32_t* out) {
  if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
    // A compress-store: no branch per survivor.
    const __m256i loaded = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(values));
    _mm256_mask_compressstoreu_epi32(out, static_cast<__mmask8>(keep), loaded);
    return static_cast<std::size_t>(__builtin_popcount(keep));
  } else {
    std::uint32_t loaded[8];
    std::copy(values, values + 8, loaded);
    std::size_t n = 0;
    for (; keep != 0; keep &= keep - 1) out[n++] = loaded[__builtin_ctz(keep)];
    return n;
  }
}

enum class LaneFilter { sign, separation };

// One filter over the candidates of `candidate`, `count` (<= lane count) of
// them in use: bit k set when lane k is certainly (or, uncertified, plainly)
// free of contact. Lanes past count are never culled.
template <class Arch, LaneFilter filter, class Source>
[[gnu::flatten]] std::uint32_t culled_lanes(const Source& source,
                                            const typename Gather<Arch>::Candidates& candidate,
                                            std::size_t count, const reference::FilterSettings& settings) {
  const bool certified = settings.certified;
  using L = Lanes<Arch>;
  using Double = typename L::Double;
  using Mask = typename L::Mask;
  using Vector = typename L::Vector;

  // x[k][tau]: DESIGN.md's x_{k+1} at t = tau, loaded.
  Vector x[4][2];
  Gather<Arch>::from(source, candidate, x);

  // The largest magnitude as the largest bit pattern of |x| (the orders
  // agree for non-negative doubles), which also makes a NaN or infinite
  // coordinate show as a non-finite maximum: one integer max a coordinate.
  using Index = typename L::Index;
  Index magnitude_bits[24];
  for (int j = 0; j < 8; ++j) {
    const Vector& p = (&x[0][0])[j];
    const Double coordinates[3] = {p.x, p.y, p.z};
    for (int c = 0; c < 3; ++c)
      magnitude_bits[3 * j + c] =
          xsimd::bitwise_cast<Index>(coordinates[c]) & Index(0x7fffffffffffffffll);
  }
  const Double largest = xsimd::bitwise_cast<Double>(
      pairwise(magnitude_bits, [](Index a, Index b) { return xsimd::max(a, b); }));
  const Mask finite = largest <= Double(std::numeric_limits<double>::max());
  // reference::scale_query: inputs near overflow quartered first. That is
  // rare, so a group of lanes without one skips the multiplications.
  const Mask huge = largest >= Double(reference::kHugeInput);
  if (xsimd::any(huge)) {
    const Double factor = xsimd::select(huge, Double(0.25), Double(1.0));
    for (auto& point : x)
      for (Vector& p : point) p = {p.x * factor, p.y * factor, p.z * factor};
  }
  Vector relative[3][2];
  Double difference_magnitude[18];
  for (int tau = 0; tau < 2; ++tau)
    for (int i = 0; i < 3; ++i) {
      const Vector d = x[i + 1][tau] - x[0][tau];
      relative[i][tau] = d;
      Double* m = difference_magnitude + 3 * (2 * i + tau);
      m[0] = xsimd::abs(d.x), m[1] = xsimd::abs(d.y), m[2] = xsimd::abs(d.z);
    }
  const Double largest_difference =
      pairwise(difference_magnitude, [](Double a, Double b) { return xsimd::max(a, b); });
  const Mask distinct = largest_difference > Double(0.0);
  const auto scale = L::inverse_power_of_two(xsimd::select(distinct, largest_difference, Double(1.0)));
  scale.scale(&relative[0][0], 6);

  // ScaledQuery::absolute_error: a quartered input's underflow floor (twice
  // 2^-1074), scaled with the differences, plus the scaling's own.
  const Double absolute_error =
      xsimd::select(huge, scale.apply(Double(0x1p-1073)), Double(0.0)) + Double(0x1p-1074);
  const Mask evaluable = finite & distinct;
  const std::uint32_t lanes_in_use = (1u << count) - 1;

  if constexpr (filter == LaneFilter::sign) {
    reference::BernsteinCubic<Double> cubic =
        reference::bernstein_cubic(relative[0][0], relative[0][1], relative[1][0],
                                   relative[1][1], relative[2][0], relative[2][1]);
    Double relative_error(0.0), floor(0.0), half_relative_error(0.0), half_floor(0.0);
    if (certified) {
      reference::bernstein_magnitude_bounds(cubic, relative[0][0], relative[0][1], relative[1][0],
                                            relative[1][1], relative[2][0], relative[2][1]);
      // reference::coefficient_error and half_coefficient_error, lane by lane.
      const reference::ErrorModel whole = reference::coefficient_error(0.0);
      const reference::ErrorModel half = reference::half_coefficient_error(whole);
      relative_error = Double(whole.relative);
      floor = Double(256.0) * absolute_error + Double(reference::kUnderflowFloor);
      half_relative_error = Double(half.relative);
      half_floor = Double(8.0) * floor;
    } else {
      for (Double& m : cubic.magnitude) m = Double(0.0);
    }
    const Mask culled = reference::sign_filter_culls(cubic, relative_error, floor, half_relative_error,
                                                     half_floor, settings.subdivide);
    return lane_bits<Arch>(culled & evaluable) & lanes_in_use;
  } else {
    // reference::separation_error, lane by lane.
    const reference::SeparationErrorModel error = reference::separation_error(0.0, certified);
    const Mask enabled = certified ? Mask(absolute_error <= Double(0x1p-900)) : Mask(true);
    const Mask culled = reference::separation_filter_culls(source.kind, relative,
                                                           Double(error.relative), Double(error.floor));
    return lane_bits<Arch>(culled & enabled & evaluable) & lanes_in_use;
  }
}

// The filters over candidates [begin, end): see FilterFunction. The sign
// filter runs over all of them and compacts its survivors; the separation
// filter then runs over those alone, in full lanes, and compacts them again.
template <class Arch, class Source>
std::size_t filter_range(const Source& source, std::size_t begin, std::size_t end,
                         const reference::FilterSettings& settings, std::uint32_t* survivors,
                         FilterCounts& counts) {
  constexpr std::size_t lanes = Lanes<Arch>::size;
  typename Gather<Arch>::Candidates candidate;
  std::uint32_t offsets[8] = {};  // survivors' indices relative to begin, lane by lane
  std::size_t kept = 0;
  for (std::size_t first = begin; first < end; first += lanes) {
    const std::size_t count = std::min(end - first, lanes);
    for (std::size_t j = 0; j < lanes; ++j) {
      const std::size_t i = first + std::min(j, count - 1);  // spare lanes repeat the last
      candidate[j] = static_cast<std::int64_t>(i);
      offsets[j] = static_cast<std::uint32_t>(i - begin);
    }
    const std::uint32_t culled =
        settings.sign ? culled_lanes<Arch, LaneFilter::sign>(source, candidate, count, settings) : 0;
    counts.sign += static_cast<std::size_t>(__builtin_popcount(culled));
    kept += compress<Arch>(~culled & ((1u << count) - 1), offsets, survivors + kept);
  }
  if (!settings.separation) return kept;
  const std::size_t sign_survivors = kept;
  kept = 0;
  for (std::size_t first = 0; first < sign_survivors; first += lanes) {
    const std::size_t count = std::min(sign_survivors - first, lanes);
    for (std::size_t j = 0; j < lanes; ++j) {
      offsets[j] = survivors[first + std::min(j, count - 1)];
      candidate[j] = static_cast<std::int64_t>(begin + offsets[j]);
    }
    const std::uint32_t culled =
        culled_lanes<Arch, LaneFilter::separation>(source, candidate, count, settings);
    counts.separation += static_cast<std::size_t>(__builtin_popcount(culled));
    kept += compress<Arch>(~culled & ((1u << count) - 1), offsets, survivors + kept);
  }
  return kept;
}

template <class Arch>
FilterKernels make_kernels(Isa isa) {
  return {isa, &filter_range<Arch, RawQueries>, &filter_range<Arch, MeshVertexFace>,
          &filter_range<Arch, MeshEdgeEdge>};
}

}  // namespace batchccd::simd

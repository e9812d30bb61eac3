#pragma once

// The lane filter, written once over xsimd's batch type and instantiated per
// instruction set by the kernel_*.cpp files (each compiled with its own
// flags). It mirrors the scalar reference path operation for operation —
// reference::scale_query, then reference::sign_filter_culls — so both make
// the same cull decision bit for bit (tests/test_simd.cpp holds them
// together). Include only from those translation units.

#include <algorithm>
#include <cstdint>
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

  static Double bits(std::uint64_t pattern) {
    return xsimd::bitwise_cast<Double>(xsimd::batch<std::uint64_t, Arch>(pattern));
  }

  // 2^-ilogb(m) for positive m, as two factors whose product is exact to
  // apply (scaling up) or a single factor (scaling down): x * first * second
  // equals std::ldexp(x, -ilogb(m)) bit for bit, subnormals included.
  struct PowerOfTwo {
    Double first, second;
    Double apply(const Double& x) const { return x * first * second; }
  };
  static PowerOfTwo inverse_power_of_two(const Double& m) {
    const Mask subnormal = m < Double(0x1p-1022);
    const Double normal = xsimd::select(subnormal, m * Double(0x1p64), m);
    const Double leading = normal & bits(0x7ff0000000000000ull);  // 2^floor(log2)
    return {Double(1.0) / leading, xsimd::select(subnormal, Double(0x1p64), Double(1.0))};
  }
};

// Loads lanes first .. first + count - 1 of a source into x[k][tau] (DESIGN.md's
// x_{k+1} at t = tau); lanes past count repeat the last candidate.
template <class Arch>
struct Gather {
  using L = Lanes<Arch>;
  using Double = typename L::Double;
  using Index = typename L::Index;
  using Vector = typename L::Vector;

  static Vector at(const double* x, const double* y, const double* z, const Index& index) {
    return {Double::gather(x, index), Double::gather(y, index), Double::gather(z, index)};
  }

  static void from(const RawQueries& raw, std::size_t first, std::size_t count, Vector (&x)[4][2]) {
    alignas(64) std::int64_t offset[L::size];
    for (std::size_t j = 0; j < L::size; ++j)
      offset[j] = static_cast<std::int64_t>((first + (j < count ? j : count - 1)) * 24);
    const Index index = Index::load_aligned(offset);
    const double* data = raw.queries[0].points[0].data();
    for (int k = 1; k <= 4; ++k)
      for (int tau = 0; tau < 2; ++tau) {
        const double* p = data + 3 * (reference::point_index(raw.kind, k) + 4 * tau);
        x[k - 1][tau] = at(p, p + 1, p + 2, index);
      }
  }

  template <class MeshSource>
  static void from(const MeshSource& mesh, std::size_t first, std::size_t count, Vector (&x)[4][2]) {
    alignas(64) std::int64_t ids[4][L::size];
    for (std::size_t j = 0; j < L::size; ++j) {
      const auto vertices = vertex_ids(mesh, first + (j < count ? j : count - 1));
      for (int k = 0; k < 4; ++k) ids[k][j] = vertices[k];
    }
    const MeshPositions& p = mesh.positions;
    for (int k = 0; k < 4; ++k) {
      const Index index = Index::load_aligned(ids[k]);
      x[k][0] = at(p.t0, p.t0 + p.rows, p.t0 + 2 * p.rows, index);
      x[k][1] = at(p.t1, p.t1 + p.rows, p.t1 + 2 * p.rows, index);
    }
  }
};

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

// Writes base + k for every set bit k of `keep`, in order; returns how many.
template <class Arch>
std::size_t compress_indices(std::uint32_t keep, std::uint32_t base, std::uint32_t* out) {
  if constexpr (std::is_base_of_v<xsimd::avx512f, Arch>) {
    // A compress-store: no branch per survivor.
    const __m256i indices = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(base)),
                                             _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    _mm256_mask_compressstoreu_epi32(out, static_cast<__mmask8>(keep), indices);
    return static_cast<std::size_t>(__builtin_popcount(keep));
  } else {
    std::size_t n = 0;
    for (; keep != 0; keep &= keep - 1) out[n++] = base + static_cast<std::uint32_t>(__builtin_ctz(keep));
    return n;
  }
}

// Which lanes each filter culls: bit k set when lane k is certainly (or,
// uncertified, plainly) free of contact.
struct LaneCulls {
  std::uint32_t sign = 0;
  std::uint32_t separation = 0;
};

// The filters for `count` (<= lane count) queries whose 24 coordinates per
// lane the source gathers. Lanes past count are never culled.
template <class Arch, class Source>
[[gnu::flatten]] LaneCulls filter_lanes(const Source& source, std::size_t first, std::size_t count,
                       const reference::FilterSettings& settings) {
  const bool certified = settings.certified;
  using L = Lanes<Arch>;
  using Double = typename L::Double;
  using Mask = typename L::Mask;
  using Vector = typename L::Vector;

  // x[k][tau]: DESIGN.md's x_{k+1} at t = tau, gathered.
  Vector x[4][2];
  Gather<Arch>::from(source, first, count, x);

  // Non-finite input: x - x is NaN.
  Double finite_check(0.0);
  Double largest(0.0);
  for (auto& point : x)
    for (Vector& p : point)
      for (Double* c : {&p.x, &p.y, &p.z}) {
        finite_check = finite_check + (*c - *c);
        largest = xsimd::max(largest, xsimd::abs(*c));
      }
  const Mask finite = finite_check == Double(0.0);
  const Mask nonzero = largest > Double(0.0);
  const auto input_scale = L::inverse_power_of_two(xsimd::select(nonzero, largest, Double(1.0)));

  Vector relative[3][2];
  Double largest_difference(0.0);
  for (int tau = 0; tau < 2; ++tau) {
    const Vector origin{input_scale.apply(x[0][tau].x), input_scale.apply(x[0][tau].y),
                        input_scale.apply(x[0][tau].z)};
    for (int i = 0; i < 3; ++i) {
      const Vector& p = x[i + 1][tau];
      Vector& d = relative[i][tau];
      d = {input_scale.apply(p.x) - origin.x, input_scale.apply(p.y) - origin.y,
           input_scale.apply(p.z) - origin.z};
      largest_difference = xsimd::max(
          largest_difference, xsimd::max(xsimd::abs(d.x), xsimd::max(xsimd::abs(d.y), xsimd::abs(d.z))));
    }
  }
  const Mask distinct = largest_difference > Double(0.0);
  const auto scale = L::inverse_power_of_two(xsimd::select(distinct, largest_difference, Double(1.0)));
  for (auto& pair : relative)
    for (Vector& d : pair) d = {scale.apply(d.x), scale.apply(d.y), scale.apply(d.z)};

  // ScaledQuery::absolute_error: when the input normalisation scaled down
  // (largest >= 2) and the second scaled up, its underflow floor, magnified.
  const Mask magnified = (largest >= Double(2.0)) & (largest_difference < Double(2.0));
  const Double absolute_error =
      xsimd::select(magnified, scale.apply(Double(0x1p-1074)), Double(0.0)) + Double(0x1p-1074);
  const Mask evaluable = finite & distinct;
  const std::uint32_t lanes_in_use = (1u << count) - 1;

  LaneCulls culls;
  if (settings.sign) {
    reference::BernsteinCubic<Double> cubic =
        reference::bernstein_cubic(relative[0][0], relative[0][1], relative[1][0],
                                   relative[1][1], relative[2][0], relative[2][1]);
    Double relative_error(0.0), floor(0.0), half_relative_error(0.0), half_floor(0.0);
    if (certified) {
      reference::bernstein_magnitudes(
          cubic, reference::absolute(relative[0][0]), reference::absolute(relative[0][1]),
          reference::absolute(relative[1][0]), reference::absolute(relative[1][1]),
          reference::absolute(relative[2][0]), reference::absolute(relative[2][1]));
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
    const Mask culled = reference::sign_filter_culls(cubic, relative_error, floor,
                                                     half_relative_error, half_floor);
    culls.sign = lane_bits<Arch>(culled & evaluable) & lanes_in_use;
  }
  if (settings.separation) {
    // reference::separation_error, lane by lane.
    const reference::SeparationErrorModel error = reference::separation_error(0.0, certified);
    const Mask enabled = certified ? Mask(absolute_error <= Double(0x1p-900)) : Mask(true);
    const Mask culled = reference::separation_filter_culls(source.kind, relative,
                                                           Double(error.relative), Double(error.floor));
    culls.separation = lane_bits<Arch>(culled & enabled & evaluable) & lanes_in_use;
  }
  return culls;
}

// The filter over candidates [begin, end): see FilterFunction.
template <class Arch, class Source>
std::size_t filter_range(const Source& source, std::size_t begin, std::size_t end,
                         const reference::FilterSettings& settings, std::uint32_t* survivors,
                         FilterCounts& counts) {
  constexpr std::size_t lanes = Lanes<Arch>::size;
  std::size_t kept = 0;
  for (std::size_t first = begin; first < end; first += lanes) {
    const std::size_t count = end - first < lanes ? end - first : lanes;
    const LaneCulls culls = filter_lanes<Arch>(source, first, count, settings);
    counts.sign += static_cast<std::size_t>(__builtin_popcount(culls.sign));
    counts.separation += static_cast<std::size_t>(__builtin_popcount(culls.separation));
    const std::uint32_t keep = ~(culls.sign | culls.separation) & ((1u << count) - 1);
    kept += compress_indices<Arch>(keep, static_cast<std::uint32_t>(first - begin), survivors + kept);
  }
  return kept;
}

template <class Arch>
FilterKernels make_kernels(Isa isa) {
  return {isa, &filter_range<Arch, RawQueries>, &filter_range<Arch, MeshVertexFace>,
          &filter_range<Arch, MeshEdgeEdge>};
}

}  // namespace batchccd::simd

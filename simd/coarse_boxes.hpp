#pragma once

// The swept boxes in single precision, twice a group of lanes at once
// (AVX-512: sixteen candidates in a zmm; AVX2: eight in a ymm), ahead of
// the first pass's boxes in double: a coarse test whose culls the exact one
// makes too, so a group of lanes it settles skips the double path and
// decides the same (docs/design.md §2a).
//
// Each vertex has a coarse row (PackedPositions): its six coordinates
// rounded to floats, then e >= 2^-24 |x| + 2^-149 for its largest |x|,
// which bounds each coordinate's rounding. With S the largest e_k + e_1 over
// a candidate's points, every float difference x_k - x_1 errs by at most
// 2.01 S + 2^-150, and a box gap computed from them by at most
// 6.03 S + 2^-148 (the gap's own rounding included). A float gap above 8 S
// thus leaves an exact gap above 0.96 S >= 2^-25 of every coordinate's
// magnitude: far above what the double test's rounding can take from it,
// so the double test culls the candidate too. With a separation s the
// float threshold is 8 S plus s grown by 2^-20 and rounded up, beyond the
// double test's growth of s (8 u) and its margin of 8 u of the largest
// difference. Only where the coordinates stay below 2^100 (the mesh has no
// coarse rows otherwise): no float overflows. The argument does not depend
// on the width: both instruction sets run the same code but for the loads,
// the transpose's last step and the separations' rounding.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <xsimd/xsimd.hpp>

#include "simd/sources.hpp"

namespace batchccd::simd {

// Whether the first pass takes the coarse boxes: AVX-512 and AVX2, whose
// float registers hold a coarse row (eight floats) and twice a group's
// candidates. Templates only, instantiated by those kernels alone, whose
// flags their instructions need.
template <class Arch>
constexpr bool kCoarseBoxes = std::is_base_of_v<xsimd::avx512dq, Arch> || std::is_base_of_v<xsimd::avx2, Arch>;

template <class Arch, class MeshSource>
struct CoarseBoxes {
  using Float = xsimd::batch<float, Arch>;
  static constexpr std::size_t size = Float::size;  // candidates a test: 16 or 8
  static constexpr bool kWide = size == 16;         // AVX-512

  // Lane j of out[c] is coordinate c of candidate j's row, columns 0 to 6,
  // from the rows in[j] (row()'s). AVX-512: in[j] holds the rows of
  // candidates a(j) (low half) and a(j) + 4 (high half), a(j) = j for j < 4
  // and j + 4 from there, so that the lanes come out in the candidates'
  // order. AVX2: in[j] is candidate j's row. The first two steps work
  // within 128-bit quarters alike.
  [[gnu::always_inline]] static void transpose(const Float (&in)[8], Float (&out)[7]) {
    Float t[8], u[8];
    for (int i = 0; i < 8; i += 2) {
      t[i] = unpack<false>(in[i], in[i + 1]);     // columns 0, 1 (4, 5) of rows i, i + 1
      t[i + 1] = unpack<true>(in[i], in[i + 1]);  // columns 2, 3 (6, 7)
    }
    for (int i = 0; i < 8; i += 4) {
      u[i] = shuffle<0x44>(t[i], t[i + 2]);  // column 0 (4) of rows i to i + 3
      u[i + 1] = shuffle<0xee>(t[i], t[i + 2]);  // column 1 (5)
      u[i + 2] = shuffle<0x44>(t[i + 1], t[i + 3]);
      u[i + 3] = shuffle<0xee>(t[i + 1], t[i + 3]);
    }
    // Column c (c < 4) lies in the even quarters (AVX2: the low halves) of
    // u[c] and u[c + 4], column c + 4 in their odd quarters.
    for (int c = 0; c < 4; ++c) out[c] = quarters<false>(u[c], u[c + 4]);
    for (int c = 4; c < 7; ++c) out[c] = quarters<true>(u[c - 4], u[c]);
  }

  // Bit j set where the coarse boxes of candidate first + j lie apart by
  // more than lane j of `separation` (j < size; the separations grown and
  // rounded up, as separations() makes them). The mesh has coarse rows;
  // ids checked by the caller.
  [[gnu::noinline]] static std::uint32_t apart(const MeshSource& mesh, std::size_t first, const Float& separation) {
    // Candidate j's ids at a fixed offset from one pointer, opaque to the
    // optimiser, which otherwise computes each candidate's address anew
    // (as Gather::with_rows).
    MeshSource from_first = mesh;
    from_first.pairs += first;
    asm("" : "+r"(from_first.pairs));
    // The first box holds x1 (the origin) and the points up to first_other,
    // the second the rest (VF: the face, then the vertex; EE: one edge each).
    constexpr int first_other = MeshSource::kind == Kind::vertex_face ? 2 : 1;
    // x_{i+1} - x1 in columns 0 to 5, e_{i+1} + e_1 in column 6: one
    // fused multiply-add, exact as the subtraction where the factor is -1.
    alignas(64) float signs[size];
    for (std::size_t c = 0; c < size; ++c) signs[c] = c % 8 < 6 ? -1.0F : c % 8 == 6 ? 1.0F : 0.0F;
    const Float sign = Float::load_aligned(signs);
    const Float zero(0.0F);
    Float low[2][3], high[2][3], bound = zero;
#pragma GCC unroll 3
    for (int i = 1; i <= 3; ++i) {
      Float difference[8];
      for (int j = 0; j < 8; ++j) difference[j] = fused(row(from_first, j, 0), sign, row(from_first, j, i));
      Float column[7];
      transpose(difference, column);
      bound = xsimd::max(bound, column[6]);
      const int box = i <= first_other ? 0 : 1;
      for (int axis = 0; axis < 3; ++axis) {
        const Float lo = xsimd::min(column[axis], column[axis + 3]);
        const Float hi = xsimd::max(column[axis], column[axis + 3]);
        const bool opens = i == 1 || i == first_other + 1;
        low[box][axis] = opens ? (box == 0 ? xsimd::min(lo, zero) : lo) : xsimd::min(low[box][axis], lo);
        high[box][axis] = opens ? (box == 0 ? xsimd::max(hi, zero) : hi) : xsimd::max(high[box][axis], hi);
      }
    }
    Float widest = zero;
    for (int axis = 0; axis < 3; ++axis) {
      const Float gap = xsimd::max(low[1][axis] - high[0][axis], low[0][axis] - high[1][axis]);
      widest = axis == 0 ? gap : xsimd::max(widest, gap);
    }
    const auto apart = widest > fused(bound, Float(8.0F), separation);
    if constexpr (kWide) {
      return static_cast<std::uint32_t>(apart.data);
    } else {
      return static_cast<std::uint32_t>(_mm256_movemask_ps(apart));
    }
  }

  // Separations s as the coarse test takes them: s (1 + 2^-20), rounded up
  // to a float (+inf beyond floats). `each`: `size` doubles, else `all`.
  static Float separations(const double* each, double all) {
    if constexpr (kWide) {
      const auto up = [](__m512d s) {
        return _mm512_cvt_roundpd_ps(_mm512_mul_pd(s, _mm512_set1_pd(kGrow)), _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
      };
      if (each == nullptr) return _mm512_broadcast_f32x8(up(_mm512_set1_pd(all)));
      return _mm512_insertf32x8(_mm512_castps256_ps512(up(_mm512_loadu_pd(each))), up(_mm512_loadu_pd(each + 8)), 1);
    } else {
      // No rounding mode in the conversion: to nearest, then one float up
      // (towards +inf whatever the sign) where that fell below.
      const auto up = [](__m256d s) {
        const __m256d grown = _mm256_mul_pd(s, _mm256_set1_pd(kGrow));
        const __m128 nearest = _mm256_cvtpd_ps(grown);
        const __m256i below = _mm256_castpd_si256(_mm256_cmp_pd(_mm256_cvtps_pd(nearest), grown, _CMP_LT_OQ));
        // Each double's mask in its low 32 bits, in the low four lanes.
        const __m128i mask = _mm256_castsi256_si128(
            _mm256_permutevar8x32_epi32(below, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
        const __m128i step = _mm_castps_si128(_mm_blendv_ps(_mm_castsi128_ps(_mm_set1_epi32(1)),
                                                            _mm_castsi128_ps(_mm_set1_epi32(-1)), nearest));
        return _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(nearest), _mm_and_si128(step, mask)));
      };
      if (each == nullptr) {
        const __m128 s = up(_mm256_set1_pd(all));
        return _mm256_set_m128(s, s);
      }
      return _mm256_set_m128(up(_mm256_loadu_pd(each + 4)), up(_mm256_loadu_pd(each)));
    }
  }

 private:
  static constexpr double kGrow = 1 + 0x1p-20;

  // Row j's coarse row of point k (see transpose), the candidates counted
  // from mesh.pairs.
  [[gnu::always_inline]] static Float row(const MeshSource& mesh, int j, int k) {
    const auto load = [&](std::size_t candidate) {
      return _mm256_load_ps(mesh.positions.coarse + row_starts<false>(mesh, candidate)[k]);
    };
    if constexpr (kWide) {
      const auto a = static_cast<std::size_t>(j < 4 ? j : j + 4);
      return _mm512_insertf32x8(_mm512_castps256_ps512(load(a)), load(a + 4), 1);
    } else {
      return load(static_cast<std::size_t>(j));
    }
  }

  [[gnu::always_inline]] static Float fused(const Float& a, const Float& b, const Float& c) {
    if constexpr (kWide) {
      return _mm512_fmadd_ps(a, b, c);
    } else {
      return _mm256_fmadd_ps(a, b, c);
    }
  }
  template <bool high>
  [[gnu::always_inline]] static Float unpack(const Float& a, const Float& b) {
    if constexpr (kWide) {
      return high ? _mm512_unpackhi_ps(a, b) : _mm512_unpacklo_ps(a, b);
    } else {
      return high ? _mm256_unpackhi_ps(a, b) : _mm256_unpacklo_ps(a, b);
    }
  }
  template <int selector>
  [[gnu::always_inline]] static Float shuffle(const Float& a, const Float& b) {
    if constexpr (kWide) {
      return _mm512_shuffle_ps(a, b, selector);
    } else {
      return _mm256_shuffle_ps(a, b, selector);
    }
  }
  // The even (odd) quarters of a, then of b: AVX2's halves.
  template <bool odd>
  [[gnu::always_inline]] static Float quarters(const Float& a, const Float& b) {
    if constexpr (kWide) {
      return _mm512_shuffle_f32x4(a, b, odd ? 0xdd : 0x88);
    } else {
      return _mm256_permute2f128_ps(a, b, odd ? 0x31 : 0x20);
    }
  }
};

}  // namespace batchccd::simd

#pragma once

// The swept boxes in single precision, sixteen candidates of a mesh at once
// (AVX-512 only), ahead of the first pass's boxes in double: a coarse test
// whose culls the exact one makes too, so a group of eight it settles skips
// the double path and decides the same (docs/design.md §2a).
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
// coarse rows otherwise): no float overflows.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "simd/sources.hpp"

namespace batchccd::simd {

// A template, instantiated only by the AVX-512 kernels, whose flags its
// instructions need.
template <class MeshSource>
struct CoarseBoxes {
  // Lane j of out[c] is coordinate c of row j, for the rows of sixteen
  // candidates: in[j] holds the rows of candidates a(j) (low half) and
  // a(j) + 4 (high half), a(j) = j for j < 4 and j + 4 from there, so that
  // the lanes come out in the candidates' order. Columns 0 to 6 only.
  [[gnu::always_inline]] static void transpose(const __m512 (&in)[8], __m512 (&out)[7]) {
    __m512 t[8], u[8];
    for (int i = 0; i < 8; i += 2) {
      t[i] = _mm512_unpacklo_ps(in[i], in[i + 1]);      // columns 0, 1 (4, 5) of rows i, i + 1
      t[i + 1] = _mm512_unpackhi_ps(in[i], in[i + 1]);  // columns 2, 3 (6, 7)
    }
    for (int i = 0; i < 8; i += 4) {
      u[i] = _mm512_shuffle_ps(t[i], t[i + 2], 0x44);      // column 0 (4) of rows i to i + 3
      u[i + 1] = _mm512_shuffle_ps(t[i], t[i + 2], 0xee);  // column 1 (5)
      u[i + 2] = _mm512_shuffle_ps(t[i + 1], t[i + 3], 0x44);
      u[i + 3] = _mm512_shuffle_ps(t[i + 1], t[i + 3], 0xee);
    }
    for (int c = 0; c < 4; ++c) out[c] = _mm512_shuffle_f32x4(u[c], u[c + 4], 0x88);
    for (int c = 4; c < 7; ++c) out[c] = _mm512_shuffle_f32x4(u[c - 4], u[c], 0xdd);
  }

  // Bit j set where the coarse boxes of candidate first + j lie apart by
  // more than lane j of `separation` (j < 16; the separations grown and
  // rounded up, as separations() makes them). The mesh has coarse rows;
  // ids checked by the caller.
  [[gnu::noinline]] static std::uint32_t apart(const MeshSource& mesh, std::size_t first, __m512 separation) {
    const float* coarse = mesh.positions.coarse;
    const auto rows = [&](int j, int k) {
      const std::size_t a = first + static_cast<std::size_t>(j < 4 ? j : j + 4);
      return _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_load_ps(coarse + row_starts<false>(mesh, a)[k])),
                                _mm256_load_ps(coarse + row_starts<false>(mesh, a + 4)[k]), 1);
    };
    // The first box holds x1 (the origin) and the points up to first_other,
    // the second the rest (VF: the face, then the vertex; EE: one edge each).
    constexpr int first_other = MeshSource::kind == Kind::vertex_face ? 2 : 1;
    // x_{i+1} - x1 in columns 0 to 5, e_{i+1} + e_1 in column 6: one
    // fused multiply-add, exact as the subtraction where the factor is -1.
    const __m512 sign = _mm512_setr_ps(-1, -1, -1, -1, -1, -1, 1, 0, -1, -1, -1, -1, -1, -1, 1, 0);
    const __m512 zero = _mm512_setzero_ps();
    __m512 low[2][3], high[2][3], bound = zero;
#pragma GCC unroll 3
    for (int i = 1; i <= 3; ++i) {
      __m512 difference[8];
      for (int j = 0; j < 8; ++j) difference[j] = _mm512_fmadd_ps(rows(j, 0), sign, rows(j, i));
      __m512 column[7];
      transpose(difference, column);
      bound = _mm512_max_ps(bound, column[6]);
      const int box = i <= first_other ? 0 : 1;
      for (int axis = 0; axis < 3; ++axis) {
        const __m512 lo = _mm512_min_ps(column[axis], column[axis + 3]);
        const __m512 hi = _mm512_max_ps(column[axis], column[axis + 3]);
        const bool opens = i == 1 || i == first_other + 1;
        low[box][axis] = opens ? (box == 0 ? _mm512_min_ps(lo, zero) : lo) : _mm512_min_ps(low[box][axis], lo);
        high[box][axis] = opens ? (box == 0 ? _mm512_max_ps(hi, zero) : hi) : _mm512_max_ps(high[box][axis], hi);
      }
    }
    __m512 widest = zero;
    for (int axis = 0; axis < 3; ++axis) {
      const __m512 gap =
          _mm512_max_ps(_mm512_sub_ps(low[1][axis], high[0][axis]), _mm512_sub_ps(low[0][axis], high[1][axis]));
      widest = axis == 0 ? gap : _mm512_max_ps(widest, gap);
    }
    return _mm512_cmp_ps_mask(widest, _mm512_fmadd_ps(bound, _mm512_set1_ps(8.0F), separation), _CMP_GT_OQ);
  }

  // Separations s as the coarse test takes them: s (1 + 2^-20), rounded up
  // to a float (+inf beyond floats). `each`: sixteen doubles, else `all`.
  static __m512 separations(const double* each, double all) {
    const __m512d grow = _mm512_set1_pd(1 + 0x1p-20);
    const auto up = [&](__m512d s) { return _mm512_cvt_roundpd_ps(_mm512_mul_pd(s, grow), kUp); };
    if (each == nullptr) return _mm512_broadcast_f32x8(up(_mm512_set1_pd(all)));
    return _mm512_insertf32x8(_mm512_castps256_ps512(up(_mm512_loadu_pd(each))), up(_mm512_loadu_pd(each + 8)), 1);
  }

 private:
  static constexpr int kUp = _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC;
};

}  // namespace batchccd::simd

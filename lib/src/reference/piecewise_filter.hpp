#pragma once

#include <cmath>

#include "reference/separation_filter.hpp"
#include "reference/sign_filter.hpp"

// The filters over pieces of the step (docs/design.md §4a): the step cut
// into 2, 4 or 8 equal pieces, a piece free of contact when the sign test (or,
// with a separation, the plane bound) or the separation filter rules it out
// there, a query culled when every piece is free. Written once over T
// (double, or an xsimd batch), like the whole-step filters, for the direct
// frame of the separation filter only.
namespace batchccd::reference {

// Pieces' cubic coefficients in Bernstein form, each piece's up to positive
// factors per index (split_at_half's), with the thresholds' weights that
// undo those factors for the plane bound (the weighted Bernstein ones are
// (1, 3, 3, 1) times the plain ones).
template <class T, int pieces>
struct PieceCubics {
  T coefficient[pieces][4];
  T magnitude[pieces][4];
  double weight[pieces][4];
  T relative, floor;
};

// A half from split_at_half ((c'0, 2c'1, 4c'2, 8c'3) on the left, the
// reverse factors on the right, c' the half's weighted coefficients) times
// powers of two, which are exact: 8 c', which split_at_half takes again.
template <class T>
void uniform_half(const T (&half)[4], bool left, T (&out)[4]) {
  for (int k = 0; k < 4; ++k) out[k] = T(double(1 << (left ? 3 - k : k))) * half[k];
}

// Pieces below the halves: each split again after uniform_half. A level
// adds three roundings (halves: 13 with the coefficients' own, bounded by
// 24 u; quarters 16, by 32 u; eighths 19, by 40 u; the rest of each bound
// covers the magnitudes' own rounding). The floor grows by 8 for the
// rescaling and by at most 6 for the split's weights: 64 a level.
inline constexpr double kLevelFloorFactor = 64;

template <int pieces, class T>
PieceCubics<T, pieces> piece_cubics(const SignTest<T>& test) {
  static_assert(pieces == 2 || pieces == 4 || pieces == 8);
  constexpr double left_weight[4] = {1, 6, 12, 8}, right_weight[4] = {8, 12, 6, 1};
  PieceCubics<T, pieces> out;
  // Level by level in place: piece j of a level becomes pieces 2j, 2j + 1.
  split_at_half(test.cubic.coefficient, out.coefficient[0], out.coefficient[1]);
  split_at_half(test.cubic.magnitude, out.magnitude[0], out.magnitude[1]);
  out.relative = test.half_relative, out.floor = test.half_floor;
  double scale = 1;  // of the weights: 8 a level below the halves
  int level = 1;
  for (int count = 2; count < pieces; count *= 2, ++level) {
    for (int j = count - 1; j >= 0; --j) {  // from the last: no piece overwritten before its split
      T uniform[4], uniform_magnitude[4];
      uniform_half(out.coefficient[j], j % 2 == 0, uniform);
      uniform_half(out.magnitude[j], j % 2 == 0, uniform_magnitude);
      split_at_half(uniform, out.coefficient[2 * j], out.coefficient[2 * j + 1]);
      split_at_half(uniform_magnitude, out.magnitude[2 * j], out.magnitude[2 * j + 1]);
    }
    scale *= 8;
    out.floor = out.floor * T(kLevelFloorFactor);
  }
  // test.relative is 16 u certified, 0 plain: 16 u (2 + level) / 2 below the halves.
  if (level > 1) out.relative = test.relative * T(0.5 * (2 + level));
  for (int j = 0; j < pieces; ++j)
    for (int k = 0; k < 4; ++k) out.weight[j][k] = scale * (j % 2 == 0 ? left_weight[k] : right_weight[k]);
  return out;
}

// Piece j's coefficients certainly beyond weight * reach, all of one sign:
// with reach 0, no root of the cubic on the piece; with a separation's
// reach (plane_reach, whose normal bound holds on every piece: the pieces'
// control points of n are convex combinations of the whole step's), no
// point of the piece within the separation of the plane or line pair.
template <int pieces, class T>
auto piece_beyond(const PieceCubics<T, pieces>& cubics, int j, T reach) {
  const auto threshold = [&](int k) {
    return T(cubics.weight[j][k]) * reach + cubics.relative * cubics.magnitude[j][k] + cubics.floor;
  };
  auto positive = cubics.coefficient[j][0] > threshold(0);
  auto negative = cubics.coefficient[j][0] < -threshold(0);
  for (int k = 1; k < 4; ++k) {
    const T bound = threshold(k);
    positive = positive & (cubics.coefficient[j][k] > bound);
    negative = negative & (cubics.coefficient[j][k] < -bound);
  }
  return positive | negative;
}

// Lower bounds of the distance at the pieces' inner ends t = j / pieces,
// in units of 1 / pieces (the positions there times `pieces`), halving
// level by level: at 2 pieces 2 r0, r0 + r1, 2 r1; then a level's point
// 2j is twice the previous one's point j (exact) and point 2j + 1 the sum
// of points j and j + 1, so that only sums round (and a sum that
// underflows is exact). Each inner position errs by at most (level + 2) u
// of the magnitude carried with it (the same sums over absolute values):
// the inputs' own rounding and one sum a level. Against u of its own value
// for a difference of doubles, that is at most 4 roundings more (8 pieces)
// for each of the at most 6 factors of a term, which the doubled relative
// bound (128 u) covers with room for the magnitudes' own rounding.
// Positions stay below 2^43 in the direct window, so
// SeparationErrors::floor still holds.
template <int pieces, class T>
void inner_distance_lower_bounds(Kind kind, const Vector3<T> (&relative)[3][2], T error_relative, T floor,
                                 T (&distance)[pieces + 1]) {
  using std::sqrt;
  const T relative_bound = T(2) * error_relative;
  const T shrink(SeparationErrors::shrink);
  Vector3<T> position[pieces + 1][3], magnitude[pieces + 1][3];
  for (int i = 0; i < 3; ++i) {
    const Vector3<T> start = absolute(relative[i][0]), end = absolute(relative[i][1]);
    position[0][i] = relative[i][0] + relative[i][0], magnitude[0][i] = start + start;
    position[1][i] = relative[i][0] + relative[i][1], magnitude[1][i] = start + end;
    position[2][i] = relative[i][1] + relative[i][1], magnitude[2][i] = end + end;
  }
  for (int count = 2; count < pieces; count *= 2)
    for (int j = count; j >= 0; --j)  // from the last, in place
      for (int i = 0; i < 3; ++i) {
        if (j < count) {
          position[2 * j + 1][i] = position[j][i] + position[j + 1][i];
          magnitude[2 * j + 1][i] = magnitude[j][i] + magnitude[j + 1][i];
        }
        position[2 * j][i] = position[j][i] + position[j][i];
        magnitude[2 * j][i] = magnitude[j][i] + magnitude[j][i];
      }
  for (int j = 1; j < pieces; ++j) {
    const auto& p = position[j];
    const auto& m = magnitude[j];
    T distance2;
    switch (kind) {  // the point kinds' own distances, as distance2_at
      case Kind::vertex_face:
        distance2 = vertex_face_distance2(p[0], m[0], p[1], m[1], p[2], m[2], relative_bound, floor);
        break;
      case Kind::vertex_edge: distance2 = point_edge_distance2(p[1], m[1], p[2], m[2], relative_bound, floor); break;
      case Kind::vertex_vertex: distance2 = point_point_distance2(p[1], m[1], relative_bound, floor); break;
      default: distance2 = edge_edge_distance2(p[0], m[0], p[1], m[1], p[2], m[2], relative_bound, floor);
    }
    distance[j] = sqrt(distance2) * shrink;
  }
}

// The separation filter on piece j of `pieces` (distances in units of
// 1 / pieces, `motion` an upper bound of m in plain units): a contact at t
// in [t_j, t_j+1] needs d(t_j) <= (t - t_j) m + s and
// d(t_j+1) <= (t_j+1 - t) m + s, so pieces (d(t_j) + d(t_j+1)) > m + 2 pieces s,
// or either end alone beyond m + pieces s, rules it out. Multiplying s by a
// power of two is exact; sums and products round by less than the 8 u of
// shrink and grow.
template <class T>
auto piece_apart(T start, T end, T motion, T pieces_separation) {
  const T shrink(SeparationErrors::shrink), grow(SeparationErrors::grow);
  const T one_end = (motion + pieces_separation) * grow;
  return ((start + end) * shrink > (motion + T(2) * pieces_separation) * grow) | (start * shrink > one_end) |
         (end * shrink > one_end);
}

// Which pieces of the step are free of contact, per lane: free[j] for piece
// j of `count`. A query is culled when every piece is; a survivor's free
// pieces need no search (the solver skips them, SolverSettings::free_pieces).
template <class Mask>
struct PieceVerdicts {
  Mask free[8];
  int count = 0;
  Mask all_free() const {
    Mask all = free[0];
    for (int j = 1; j < count; ++j) all = all & free[j];
    return all;
  }
};

// Each piece free by either test. `measured` from the whole-step separation
// filter; `sign`: the sign test of the same differences, or null without
// the sign filter; `within`: a call with separations (the plane bound in
// place of the signs), `separation` in the frame's units.
template <int pieces, class T>
auto piece_verdicts(Kind kind, const Vector3<T> (&relative)[3][2], const SeparationMeasures<T>& measured,
                    T error_relative, T floor, const SignTest<T>* sign, const T (&largest)[3][2], bool certified,
                    bool within, T separation) {
  using std::sqrt;
  const T shrink(SeparationErrors::shrink), grow(SeparationErrors::grow);
  T distance[pieces + 1];
  distance[0] = sqrt(T(double(pieces * pieces)) * measured.start2) * shrink;
  distance[pieces] = sqrt(T(double(pieces * pieces)) * measured.end2) * shrink;
  inner_distance_lower_bounds<pieces>(kind, relative, error_relative, floor, distance);
  const T motion = sqrt(measured.displacement2) * grow;
  const T pieces_separation = T(double(pieces)) * separation;
  PieceVerdicts<decltype(motion > motion)> verdicts;
  verdicts.count = pieces;
  for (int j = 0; j < pieces; ++j)
    verdicts.free[j] = piece_apart(distance[j], distance[j + 1], motion, pieces_separation);
  // Every lane's every piece apart already: the signs would add nothing.
  if (sign == nullptr || all_of(verdicts.all_free())) return verdicts;
  const T reach = within ? plane_reach(kind, relative, largest, *sign, certified, separation) : T(0);
  const PieceCubics<T, pieces> cubics = piece_cubics<pieces>(*sign);
  for (int j = 0; j < pieces; ++j) verdicts.free[j] = verdicts.free[j] | piece_beyond(cubics, j, reach);
  return verdicts;
}

// piece_verdicts for a count of pieces known at run time (2, 4 or 8).
template <class T>
auto piece_verdicts(int pieces, Kind kind, const Vector3<T> (&relative)[3][2], const SeparationMeasures<T>& measured,
                    T error_relative, T floor, const SignTest<T>* sign, const T (&largest)[3][2], bool certified,
                    bool within, T separation) {
  if (pieces == 8)
    return piece_verdicts<8>(kind, relative, measured, error_relative, floor, sign, largest, certified, within,
                             separation);
  if (pieces == 4)
    return piece_verdicts<4>(kind, relative, measured, error_relative, floor, sign, largest, certified, within,
                             separation);
  return piece_verdicts<2>(kind, relative, measured, error_relative, floor, sign, largest, certified, within,
                           separation);
}

}  // namespace batchccd::reference

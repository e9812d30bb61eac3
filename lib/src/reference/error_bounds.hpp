#pragma once

// Forward error bounds of the certified path (docs/design.md §3): a computed value
// v of an expression whose exact value is x satisfies
//   |v - x| <= relative * magnitude + floor,
// where magnitude is the same expression evaluated on absolute values. Each
// `relative` is the count of roundings on one term's path, times the unit
// roundoff u, with room to spare for the rounding of the bound itself; each
// floor covers underflow (absolute errors of at most 2^-1074 per operation,
// and the query's own ScaledQuery::absolute_error per factor).
namespace batchccd::reference {

inline constexpr double kUnitRoundoff = 0x1p-53;
inline constexpr double kUnderflowFloor = 0x1p-1060;

struct ErrorModel {
  double relative = 0;
  double floor = 0;
};

// Coefficients of the cubic from the scaled differences themselves (one
// rounding each): 3 input roundings + 7 on bernstein_coefficients' longest
// path (a product, the cross product's difference, the mixed products' sum,
// the product with c, two in the dot, the coefficient's sum) = 10 u,
// bounded by 16 u. Every term is a product of three factors
// below 2 in magnitude, 6 terms a triple product, 3 products a sum: a factor
// floor e perturbs a coefficient by at most 216 e.
template <class T>  // T: double, or a batch of lanes
[[gnu::always_inline]] inline T coefficient_floor(T factor_floor) {
  return T(256) * factor_floor + T(kUnderflowFloor);
}
[[gnu::always_inline]] inline ErrorModel coefficient_error(double factor_floor) {
  return {16 * kUnitRoundoff, coefficient_floor(factor_floor)};
}

// Coefficients from positions interpolated inside [0, 1] ((1-t) a + t b: 3
// roundings a factor, 9 for three factors) plus 7 in the arithmetic: 16 u,
// bounded by 32 u.
inline ErrorModel interpolated_coefficient_error(double factor_floor) {
  return {32 * kUnitRoundoff, 256 * (factor_floor + 0x1p-1073) + kUnderflowFloor};
}

// The same coefficients from differences in the input's own units (no
// scaled frame), allowed when every difference component is finite and at
// most kDirectHighest and the largest at least kDirectLowest. Relative error
// as above (the scaling is exact, so it changes no relative error). Floor:
// a product that underflows errs by at most 2^-1075 absolute, and later
// factors (each at most 2^200) magnify that: a dot of a cross product with a
// third vector errs by at most 3 (2 * 2^200 + 1) 2^-1075 (1 + u)^2, a
// coefficient (three of those) by less than 2^-870. Products at least
// (2^-200)^3 = 2^-600 make that floor negligible, which is why the window
// has a lower end (below it the scaled frame culls more).
inline constexpr double kDirectLowest = 0x1p-200;
inline constexpr double kDirectHighest = 0x1p200;
[[gnu::always_inline]] inline ErrorModel direct_coefficient_error() {
  return {16 * kUnitRoundoff, 0x1p-860};
}

// Halves after split_at_half: the coefficients' own error (16 u) plus three
// roundings in the combination; the weights of a combination add up to 8.
inline constexpr double kHalfWeightSum = 8;
[[gnu::always_inline]] inline ErrorModel half_coefficient_error(const ErrorModel& whole) {
  return {24 * kUnitRoundoff, kHalfWeightSum * whole.floor};
}

// A point of the collision function F (a weighted sum of three interpolated
// positions, weights at most 1 in magnitude): 3 u a position, 3 u the sum.
inline ErrorModel collision_function_error(double factor_floor) {
  return {16 * kUnitRoundoff, 4 * (factor_floor + 0x1p-1073) + kUnderflowFloor};
}

}  // namespace batchccd::reference

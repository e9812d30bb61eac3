#include "reference/filter.hpp"

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/separation_filter.hpp"
#include "reference/sign_filter.hpp"

namespace batchccd::reference {
namespace {

Vector3<double> as_vector(const Vec3& v) { return {v[0], v[1], v[2]}; }

}  // namespace

bool sign_filter_culls(const ScaledQuery& query, bool certified, bool subdivide) {
  const auto& r = query.relative;
  BernsteinCubic<double> cubic =
      bernstein_cubic(as_vector(r[0][0]), as_vector(r[0][1]), as_vector(r[1][0]),
                      as_vector(r[1][1]), as_vector(r[2][0]), as_vector(r[2][1]));
  ErrorModel whole, half;
  if (certified) {
    bernstein_magnitude_bounds(cubic, as_vector(r[0][0]), as_vector(r[0][1]), as_vector(r[1][0]),
                               as_vector(r[1][1]), as_vector(r[2][0]), as_vector(r[2][1]));
    whole = coefficient_error(query.absolute_error);
    half = half_coefficient_error(whole);
  } else {
    for (double& magnitude : cubic.magnitude) magnitude = 0;
  }
  return sign_filter_culls(cubic, whole.relative, whole.floor, half.relative, half.floor, subdivide);
}

SeparationErrorModel separation_error(double absolute_error, bool certified) {
  if (!certified) return {0.0, 0.0, true};
  // Factors carry absolute_error each; through expressions of degree <= 6 in
  // values below 4 with fewer than 2^10 terms, that stays below 2^-880 as long
  // as absolute_error <= 2^-900, and so does underflow: a floor of 2^-800.
  return {SeparationErrors::relative, 0x1p-800, absolute_error <= 0x1p-900};
}

FilterVerdict run_filters(Kind kind, const ScaledQuery& query, const FilterSettings& settings) {
  FilterVerdict verdict;
  if (settings.sign) verdict.sign = sign_filter_culls(query, settings.certified, settings.subdivide);
  if (settings.separation && !verdict.sign) {
    const SeparationErrorModel error = separation_error(query.absolute_error, settings.certified);
    Vector3<double> relative[3][2];
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) relative[i][tau] = as_vector(query.relative[i][tau]);
    verdict.separation =
        error.enabled && separation_filter_culls(kind, relative, error.relative, error.floor);
  }
  return verdict;
}

}  // namespace batchccd::reference

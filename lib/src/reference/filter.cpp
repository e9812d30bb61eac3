#include "reference/filter.hpp"

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/sign_filter.hpp"

namespace batchccd::reference {
namespace {

Vector3<double> as_vector(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vector3<double> absolute(const Vec3& v) { return as_vector(v.cwiseAbs()); }

}  // namespace

bool sign_filter_culls(const ScaledQuery& query, bool certified) {
  const auto& r = query.relative;
  BernsteinCubic<double> cubic =
      bernstein_cubic(as_vector(r[0][0]), as_vector(r[0][1]), as_vector(r[1][0]),
                      as_vector(r[1][1]), as_vector(r[2][0]), as_vector(r[2][1]));
  ErrorModel whole, half;
  if (certified) {
    bernstein_magnitudes(cubic, absolute(r[0][0]), absolute(r[0][1]), absolute(r[1][0]),
                         absolute(r[1][1]), absolute(r[2][0]), absolute(r[2][1]));
    whole = coefficient_error(query.absolute_error);
    half = half_coefficient_error(whole);
  } else {
    for (double& magnitude : cubic.magnitude) magnitude = 0;
  }
  return sign_filter_culls(cubic, whole.relative, whole.floor, half.relative, half.floor);
}

}  // namespace batchccd::reference

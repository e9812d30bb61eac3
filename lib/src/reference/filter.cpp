#include "reference/filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/separation_filter.hpp"
#include "reference/sign_filter.hpp"

namespace batchccd::reference {
namespace {

Vector3<double> as_vector(const Vec3& v) { return {v[0], v[1], v[2]}; }

// A query's differences in its own units, for the filters' direct frames
// (error_bounds.hpp: direct_coefficient_error; separation_filter.hpp).
struct DirectFrame {
  Vector3<double> relative[3][2];  // x_{i+2}(tau) - x_1(tau)
  double largest[3][2];            // each one's largest_magnitude
  double overall = 0;              // the largest of all (a NaN if there is one)
  // All within [lowest, highest] (so all finite).
  bool within(double lowest, double highest) const { return overall >= lowest && overall <= highest; }
};

DirectFrame direct_frame(Kind kind, const Query& query) {
  DirectFrame frame;
  std::uint64_t largest = 0;  // magnitude_bits: a NaN stays the largest
  for (int tau = 0; tau < 2; ++tau) {
    const Vector3<double> origin = as_vector(query.points[point_index(kind, 1) + 4 * tau]);
    for (int i = 0; i < 3; ++i) {
      frame.relative[i][tau] = as_vector(query.points[point_index(kind, i + 2) + 4 * tau]) - origin;
      frame.largest[i][tau] = largest_magnitude(frame.relative[i][tau]);
      largest = std::max(largest, magnitude_bits(frame.largest[i][tau]));
    }
  }
  frame.overall = std::bit_cast<double>(largest);
  return frame;
}

}  // namespace

bool sign_filter_culls(const ScaledQuery& query, bool certified, bool subdivide) {
  Vector3<double> relative[3][2];
  double largest[3][2];
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau) {
      relative[i][tau] = as_vector(query.relative[i][tau]);
      largest[i][tau] = largest_magnitude(relative[i][tau]);
    }
  return sign_filter_culls(relative, largest, coefficient_error(query.absolute_error).floor, certified,
                           subdivide);
}

SeparationErrorModel separation_error(double absolute_error, bool certified) {
  if (!certified) return {0.0, 0.0, true};
  // Factors carry absolute_error each; through expressions of degree <= 6 in
  // values below 4 with fewer than 2^10 terms, that stays below 2^-880 as long
  // as absolute_error <= 2^-900, and so does underflow: SeparationErrors::floor.
  return {SeparationErrors::relative, SeparationErrors::floor, absolute_error <= 0x1p-900};
}

// The separation filter's window lies within the sign filter's: a query in
// it needs no scaled frame at all.
static_assert(kSeparationDirectLowest >= kDirectLowest && kSeparationDirectHighest <= kDirectHighest);

namespace {

Vector3<double> normal_bound_term(const Vector3<double>& value, const Vector3<double>& magnitude,
                                  double relative, double floor) {
  return {std::fabs(value.x) + relative * magnitude.x + floor,
          std::fabs(value.y) + relative * magnitude.y + floor,
          std::fabs(value.z) + relative * magnitude.z + floor};
}

// Both filters with a minimum separation, in the scaled frame.
FilterVerdict run_filters_within(Kind kind, const Query& query, const FilterSettings& settings) {
  FilterVerdict verdict;
  const ScaledQuery scaled = scale_query(kind, query);
  if (!scaled.finite || scaled.coincident) return verdict;  // for the solver's own checks
  const double separation = to_scaled_length(scaled, settings.min_distance);
  if (settings.sign) verdict.sign = plane_distance_culls(kind, scaled, separation, settings.certified);
  if (settings.separation && !verdict.sign) {
    const SeparationErrorModel error = separation_error(scaled.absolute_error, settings.certified);
    Vector3<double> relative[3][2];
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) relative[i][tau] = as_vector(scaled.relative[i][tau]);
    verdict.separation = error.enabled && separation_filter_culls_within(kind, relative, error.relative,
                                                                         error.floor, separation);
  }
  return verdict;
}

}  // namespace

bool plane_distance_culls(Kind kind, const ScaledQuery& query, double separation, bool certified) {
  Vector3<double> r[3][2], m[3][2];
  for (int i = 0; i < 3; ++i)
    for (int tau = 0; tau < 2; ++tau) {
      r[i][tau] = as_vector(query.relative[i][tau]);
      m[i][tau] = absolute(r[i][tau]);
    }
  BernsteinCubic<double> cubic = bernstein_cubic(r[0][0], r[0][1], r[1][0], r[1][1], r[2][0], r[2][1]);
  bernstein_magnitudes(cubic, m[0][0], m[0][1], m[1][0], m[1][1], m[2][0], m[2][1]);
  // n = a x b, both linear: VF a = x21, b = x31; EE a = x21, b = x43.
  Vector3<double> b[2], b_magnitude[2];
  for (int tau = 0; tau < 2; ++tau) {
    b[tau] = kind == Kind::vertex_face ? r[1][tau] : r[2][tau] - r[1][tau];
    b_magnitude[tau] = kind == Kind::vertex_face ? m[1][tau] : m[2][tau] + m[1][tau];
  }
  const Vector3<double> control[3] = {cross(r[0][0], b[0]),
                                      cross(r[0][0], b[1]) + cross(r[0][1], b[0]),  // twice n_1
                                      cross(r[0][1], b[1])};
  const Vector3<double> control_magnitude[3] = {
      cross_magnitude(m[0][0], b_magnitude[0]),
      cross_magnitude(m[0][0], b_magnitude[1]) + cross_magnitude(m[0][1], b_magnitude[0]),
      cross_magnitude(m[0][1], b_magnitude[1])};
  // Inputs carry 2 roundings (one for EE's b, one from the frame) and the
  // frame's absolute error; a product, a difference and a sum follow: 5 u,
  // bounded by 16 u. Magnitudes below 16 magnify the absolute error by 64.
  const double scale = certified ? 1.0 : 0.0;
  const double normal_relative = scale * 16 * kUnitRoundoff;
  const double normal_floor = scale * (64 * query.absolute_error + kUnderflowFloor);
  double largest_normal = 0;
  for (int j = 0; j < 3; ++j) {
    const Vector3<double> bound = normal_bound_term(control[j], control_magnitude[j], normal_relative, normal_floor);
    const double length = std::sqrt(dot(bound, bound)) * (j == 1 ? 0.5 : 1.0);
    largest_normal = std::max(largest_normal, length);
  }
  const ErrorModel error = coefficient_error(query.absolute_error);
  // The coefficients are the Bernstein ones times (1, 3, 3, 1); rounding of
  // the threshold's products and root is covered by 8 u.
  const double weights[4] = {1, 3, 3, 1};
  bool positive = true, negative = true;
  for (int k = 0; k < 4; ++k) {
    const double threshold = weights[k] * separation * largest_normal * (1 + scale * 8 * kUnitRoundoff) +
                             scale * (error.relative * cubic.magnitude[k] + error.floor);
    positive = positive && cubic.coefficient[k] > threshold;
    negative = negative && cubic.coefficient[k] < -threshold;
  }
  return positive || negative;
}

FilterVerdict run_filters(Kind kind, const Query& query, const FilterSettings& settings) {
  if (settings.min_distance > 0) return run_filters_within(kind, query, settings);
  FilterVerdict verdict;
  // Each filter in its direct frame where that applies (nearly always):
  // most queries end there, without the scaled frame's normalisation.
  const DirectFrame direct = direct_frame(kind, query);
  const bool sign_scaled = settings.sign && !direct.within(kDirectLowest, kDirectHighest);
  if (settings.sign && !sign_scaled)
    verdict.sign = sign_filter_culls(direct.relative, direct.largest, direct_coefficient_error().floor,
                                     settings.certified, settings.subdivide);
  const bool separation_due = settings.separation && !verdict.sign;
  if (separation_due && direct.within(kSeparationDirectLowest, kSeparationDirectHighest)) {
    const SeparationErrorModel error = separation_error(0.0, settings.certified);
    verdict.separation = separation_filter_culls(kind, direct.relative, error.relative, error.floor);
    return verdict;
  }
  if (!sign_scaled && !separation_due) return verdict;
  const ScaledQuery scaled = scale_query(kind, query);
  if (!scaled.finite || scaled.coincident) return verdict;  // for the solver's own checks
  if (sign_scaled) verdict.sign = sign_filter_culls(scaled, settings.certified, settings.subdivide);
  if (settings.separation && !verdict.sign) {
    const SeparationErrorModel error = separation_error(scaled.absolute_error, settings.certified);
    Vector3<double> relative[3][2];
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) relative[i][tau] = as_vector(scaled.relative[i][tau]);
    verdict.separation =
        error.enabled && separation_filter_culls(kind, relative, error.relative, error.floor);
  }
  return verdict;
}

}  // namespace batchccd::reference

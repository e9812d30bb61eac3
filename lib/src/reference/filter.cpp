#include "reference/filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "reference/bernstein.hpp"
#include "reference/error_bounds.hpp"
#include "reference/piecewise_filter.hpp"
#include "reference/separation_filter.hpp"
#include "reference/sign_filter.hpp"
#include "reference/swept_box_filter.hpp"

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

// A scaled query's differences as the filters take them.
struct ScaledDifferences {
  Vector3<double> relative[3][2];
  double largest[3][2];
  explicit ScaledDifferences(const ScaledQuery& scaled) {
    for (int i = 0; i < 3; ++i)
      for (int tau = 0; tau < 2; ++tau) {
        relative[i][tau] = as_vector(scaled.relative[i][tau]);
        largest[i][tau] = largest_magnitude(relative[i][tau]);
      }
  }
};

}  // namespace

bool sign_filter_culls(const ScaledQuery& query, bool certified, bool subdivide) {
  const ScaledDifferences frame(query);
  return sign_filter_culls(frame.relative, frame.largest, coefficient_error(query.absolute_error).floor, certified,
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

// The stage after the whole-step filters (piecewise_filter.hpp), for what
// they kept, in the separation filter's frame: `relative` and `largest`
// its differences, `error` its error model, `sign_floor` the sign test's
// floor there, `separation` in its units, `measured` the bounds the
// separation filter left (it leaves them whenever it keeps the query).
FilterVerdict pieces_stage(Kind kind, const Vector3<double> (&relative)[3][2], const double (&largest)[3][2],
                           const SeparationErrorModel& error, double sign_floor, double separation,
                           const SeparationMeasures<double>& measured, const FilterSettings& settings,
                           FilterVerdict verdict) {
  if (verdict.culled() || !settings.separation || settings.pieces <= 1 || !error.enabled) return verdict;
  const Kind distances = separation_kind(kind, settings);
  SignTest<double> test{};
  if (settings.sign) test = sign_test(relative, largest, sign_floor, settings.certified);
  const PieceVerdicts<bool> pieces =
      piece_verdicts(settings.pieces, distances, relative, measured, error.relative, error.floor,
                     settings.sign ? &test : nullptr, largest, settings.certified, settings.within, separation);
  verdict.pieces = pieces.all_free();
  for (int j = 0; j < pieces.count; ++j) verdict.free_pieces |= static_cast<std::uint8_t>(pieces.free[j] << j);
  return verdict;
}

// run_filters for a call with separations: the same frames, the filters of
// docs/design.md §11.
FilterVerdict run_filters_within(Kind kind, const Query& query, const FilterSettings& settings) {
  FilterVerdict verdict;
  const double separation = settings.min_distance;
  const DirectFrame direct = direct_frame(kind, query);
  const bool in_window = direct.within(kDirectLowest, kDirectHighest);
  verdict.swept_box = settings.swept_box && in_window &&
                      swept_boxes_apart(kind, direct.relative, true, separation);
  if (verdict.swept_box) return verdict;
  const bool sign_scaled = settings.sign && !in_window;
  const bool boxes_scaled = settings.swept_box && !in_window;
  if (settings.sign && !sign_scaled)
    verdict.sign = plane_distance_culls(kind, direct.relative, direct.largest, direct_coefficient_error().floor,
                                        settings.certified, separation);
  const bool separation_due = settings.separation && !verdict.sign;
  const bool later = direct.within(kSeparationDirectLowest, kSeparationDirectHighest);
  if (separation_due && later) {
    const SeparationErrorModel error = separation_error(0.0, settings.certified);
    SeparationMeasures<double> measured{};
    verdict.separation = separation_filter_culls_within(separation_kind(kind, settings), direct.relative,
                                                        error.relative, error.floor, separation, &measured);
    return pieces_stage(kind, direct.relative, direct.largest, error, direct_coefficient_error().floor, separation,
                        measured, settings, verdict);
  }
  if (!sign_scaled && !boxes_scaled && !separation_due) return verdict;
  const ScaledQuery scaled = scale_query(kind, query);
  if (!scaled.finite || scaled.coincident) return verdict;  // for the solver's own checks
  const double scaled_separation = to_scaled_length(scaled, separation);
  const ScaledDifferences frame(scaled);
  verdict.swept_box = boxes_scaled && swept_boxes_apart(kind, frame.relative, true, scaled_separation,
                                                        scaled.absolute_error);
  if (verdict.swept_box) return verdict;
  if (sign_scaled)
    verdict.sign = plane_distance_culls(kind, frame.relative, frame.largest, coefficient_floor(scaled.absolute_error),
                                        settings.certified, scaled_separation);
  if (settings.separation && !verdict.sign) {
    const SeparationErrorModel error = separation_error(scaled.absolute_error, settings.certified);
    SeparationMeasures<double> measured{};
    verdict.separation = error.enabled && separation_filter_culls_within(separation_kind(kind, settings),
                                                                         frame.relative, error.relative, error.floor,
                                                                         scaled_separation, &measured);
    return pieces_stage(kind, frame.relative, frame.largest, error, coefficient_floor(scaled.absolute_error),
                        scaled_separation, measured, settings, verdict);
  }
  return verdict;
}

}  // namespace

FilterVerdict run_filters(Kind kind, const Query& query, const FilterSettings& settings) {
  if (settings.within) return run_filters_within(kind, query, settings);
  FilterVerdict verdict;
  // Each filter in its direct frame where that applies (nearly always):
  // most queries end there, without the scaled frame's normalisation. The
  // swept boxes first, in the sign filter's frames: comparisons only, and
  // on a broad phase's padded list they rule out most candidates alone.
  const DirectFrame direct = direct_frame(kind, query);
  const bool in_window = direct.within(kDirectLowest, kDirectHighest);
  // Without a separation the boxes' comparisons are exact in any frame
  // (swept_box_filter.hpp): the direct one serves every finite query, in
  // its window or not (a window implies finite input).
  verdict.swept_box = settings.swept_box && (in_window || all_finite(query)) &&
                      swept_boxes_apart(kind, direct.relative, false, 0.0);
  if (verdict.swept_box) return verdict;
  const bool sign_scaled = settings.sign && !in_window;
  if (settings.sign && !sign_scaled)
    verdict.sign = sign_filter_culls(direct.relative, direct.largest, direct_coefficient_error().floor,
                                     settings.certified, settings.subdivide);
  const bool separation_due = settings.separation && !verdict.sign;
  const bool later = direct.within(kSeparationDirectLowest, kSeparationDirectHighest);
  if (separation_due && later) {
    const SeparationErrorModel error = separation_error(0.0, settings.certified);
    SeparationMeasures<double> measured{};
    verdict.separation = separation_filter_culls(separation_kind(kind, settings), direct.relative, error.relative,
                                                 error.floor, &measured);
    return pieces_stage(kind, direct.relative, direct.largest, error, direct_coefficient_error().floor, 0.0, measured,
                        settings, verdict);
  }
  if (!sign_scaled && !separation_due) return verdict;
  const ScaledQuery scaled = scale_query(kind, query);
  if (!scaled.finite || scaled.coincident) return verdict;  // for the solver's own checks
  const ScaledDifferences frame(scaled);
  if (sign_scaled)
    verdict.sign = sign_filter_culls(frame.relative, frame.largest, coefficient_floor(scaled.absolute_error),
                                     settings.certified, settings.subdivide);
  if (settings.separation && !verdict.sign) {
    const SeparationErrorModel error = separation_error(scaled.absolute_error, settings.certified);
    SeparationMeasures<double> measured{};
    verdict.separation = error.enabled && separation_filter_culls(separation_kind(kind, settings), frame.relative,
                                                                  error.relative, error.floor, &measured);
    return pieces_stage(kind, frame.relative, frame.largest, error, coefficient_floor(scaled.absolute_error), 0.0,
                        measured, settings, verdict);
  }
  return verdict;
}

}  // namespace batchccd::reference

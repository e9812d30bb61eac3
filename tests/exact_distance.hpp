#pragma once

// The exact squared distance between a query's primitives at a rational
// time, in GMP rationals (every double is one): a value <= min_distance^2
// proves a contact there.
#include <array>

#include <gmpxx.h>

#include "batchccd/query.hpp"
#include "reference/closest_distance.hpp"

namespace batchccd::testing {

using Rational = mpq_class;

inline Rational squared_distance_at(Kind kind, const Query& query, const Rational& t) {
  std::array<reference::Point<Rational>, 4> x;
  for (int k = 0; k < 4; ++k)
    for (int axis = 0; axis < 3; ++axis) {
      const Rational start(query.points[k][axis]), end(query.points[k + 4][axis]);
      x[k][axis] = start + t * (end - start);
    }
  return reference::squared_distance(kind == Kind::vertex_face, x);
}

}  // namespace batchccd::testing

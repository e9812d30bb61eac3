#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "batchccd/query.hpp"
#include "exact/exact_motion.hpp"

// The contact condition as signs of polynomials in t, degenerate cases
// included (docs/design.md §6; §1, "Degenerate input").
//
// F(t, u, v), the vector between the two points the parameters name, is
// affine in (u, v); over the parameter domain it sweeps a triangle (VF: the
// vertex minus each triangle corner) or a parallelogram, the union of two
// triangles split along a diagonal (EE: the Minkowski difference of the
// edges). The primitives touch at t exactly when the origin lies in one of
// these moving triangles, whatever their shape: a proper triangle, a
// segment or a point.
namespace batchccd::exact {

using MovingTriangle = std::array<PolynomialVector, 3>;  // corners, linear in t

std::vector<MovingTriangle> difference_triangles(Kind kind, const RelativeMotion& motion);

// For a moving triangle with corners Q1, Q2, Q3 and m = (Q2 - Q1) x (Q3 - Q1),
// the origin lies in it at t exactly when
//   |m|^2 > 0, Q1 . m = 0 and every (Qj x Qk) . m >= 0 (barycentric
//   coordinates times |m|^2), or
//   |m|^2 = 0 (corners collinear or coincident: the triangle is the longest
//   of its three sides) and, for some pair, Qi x Qj = 0 and Qi . Qj <= 0 (the origin on
//   the segment between them).
// The polynomials are formed when first asked for: most queries never need
// the sides'.
class TriangleConditions {
 public:
  explicit TriangleConditions(const MovingTriangle& corners);

  const Polynomial& normal_squared() const { return normal_squared_; }  // |m|^2, degree 4
  const Polynomial& volume() const { return volume_; }  // Q1 . m: the coplanarity cubic up to sign
  // (Q2 x Q3) . m and cyclic, degree 4.
  const std::array<Polynomial, 3>& barycentric() const;
  // |Qi x Qj|^2 (degree 4) and Qi . Qj (degree 2) for the pairs (1,2),
  // (1,3), (2,3).
  const std::array<Polynomial, 3>& side_cross() const;
  const std::array<Polynomial, 3>& side_dot() const;

 private:
  void form_sides() const;

  MovingTriangle corners_;
  PolynomialVector normal_;
  Polynomial normal_squared_, volume_;
  mutable std::optional<std::array<Polynomial, 3>> barycentric_, side_cross_, side_dot_;
};

// Polynomials whose roots in (0, 1), with 0 and 1, include the first time
// the origin is in the triangle, if there is one: the condition above keeps
// its truth value between consecutive such times, and the set of contact
// times is closed, so its minimum is one of them. Only what a case needs:
// the volume's roots when it is not identically zero (a contact needs it to
// vanish), otherwise |m|^2 and the barycentric numerators, otherwise the
// sides' polynomials. Never a zero polynomial.
std::vector<Polynomial> critical_polynomials(const TriangleConditions& conditions);

// The sign of a polynomial at the time being examined; nullopt when an
// iteration bound was reached.
using SignAtTime = std::function<std::optional<int>(const Polynomial&)>;

// Whether the origin lies in the triangle at that time.
std::optional<bool> contains_origin(const TriangleConditions& conditions, const SignAtTime& sign);

}  // namespace batchccd::exact

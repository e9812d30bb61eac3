#include "exact/origin_in_triangle.hpp"

namespace batchccd::exact {
namespace {

constexpr int kSidePairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};

}  // namespace

std::vector<MovingTriangle> difference_triangles(Kind kind, const RelativeMotion& motion) {
  const PolynomialVector &x2 = motion[0], &x3 = motion[1], &x4 = motion[2];  // x1 = 0
  if (kind == Kind::vertex_face) {
    // Triangle (x1, x2, x3), vertex x4: F = p - a - u (b - a) - v (c - a)
    // covers the vertex minus each point of the face.
    return {MovingTriangle{x4, x4 - x2, x4 - x3}};
  }
  // Edges (x1, x2) and (x3, x4): F = ea0 + u (ea1 - ea0) - eb0 - v (eb1 - eb0)
  // at the parameter square's corners (0,0), (1,0), (1,1), (0,1).
  const PolynomialVector at00 = -x3, at10 = x2 - x3, at11 = x2 - x4, at01 = -x4;
  return {MovingTriangle{at00, at10, at11}, MovingTriangle{at00, at01, at11}};
}

TriangleConditions::TriangleConditions(const MovingTriangle& corners)
    : corners_(corners), normal_(cross(corners[1] - corners[0], corners[2] - corners[0])) {
  normal_squared_ = dot(normal_, normal_);
  volume_ = dot(corners[0], normal_);
}

const std::array<Polynomial, 3>& TriangleConditions::barycentric() const {
  if (!barycentric_) {
    barycentric_.emplace();
    for (int k = 0; k < 3; ++k)
      (*barycentric_)[k] = dot(cross(corners_[(k + 1) % 3], corners_[(k + 2) % 3]), normal_);
  }
  return *barycentric_;
}

void TriangleConditions::form_sides() const {
  if (side_cross_) return;
  side_cross_.emplace();
  side_dot_.emplace();
  for (int pair = 0; pair < 3; ++pair) {
    const PolynomialVector& a = corners_[kSidePairs[pair][0]];
    const PolynomialVector& b = corners_[kSidePairs[pair][1]];
    const PolynomialVector side = cross(a, b);
    (*side_cross_)[pair] = dot(side, side);
    (*side_dot_)[pair] = dot(a, b);
  }
}

const std::array<Polynomial, 3>& TriangleConditions::side_cross() const {
  form_sides();
  return *side_cross_;
}

const std::array<Polynomial, 3>& TriangleConditions::side_dot() const {
  form_sides();
  return *side_dot_;
}

std::vector<Polynomial> critical_polynomials(const TriangleConditions& c) {
  std::vector<Polynomial> critical;
  auto add = [&](const Polynomial& p) {
    if (!p.is_zero()) critical.push_back(p);
  };
  if (!c.volume().is_zero()) {
    add(c.volume());  // |m|^2 = 0 implies Q1 . m = 0: every contact is a root
  } else if (!c.normal_squared().is_zero()) {
    add(c.normal_squared());  // coplanar motion (docs/design.md §6: a 2-D problem)
    for (const Polynomial& p : c.barycentric()) add(p);
  } else {
    // Collinear throughout: where a side's cross product is not identically
    // zero only its roots can hold the origin; where it is, the dot product's
    // sign decides between its roots.
    for (int pair = 0; pair < 3; ++pair) {
      add(c.side_cross()[pair]);
      if (c.side_cross()[pair].is_zero()) add(c.side_dot()[pair]);
    }
  }
  return critical;
}

std::optional<bool> contains_origin(const TriangleConditions& c, const SignAtTime& sign) {
  const std::optional<int> volume = sign(c.volume());
  if (!volume) return std::nullopt;
  if (*volume != 0) return false;  // not even coplanar
  const std::optional<int> normal = sign(c.normal_squared());
  if (!normal) return std::nullopt;
  if (*normal > 0) {
    for (const Polynomial& p : c.barycentric()) {
      const std::optional<int> coordinate = sign(p);
      if (!coordinate) return std::nullopt;
      if (*coordinate < 0) return false;
    }
    return true;
  }
  for (int pair = 0; pair < 3; ++pair) {
    const std::optional<int> collinear = sign(c.side_cross()[pair]);
    if (!collinear) return std::nullopt;
    if (*collinear != 0) continue;
    const std::optional<int> facing = sign(c.side_dot()[pair]);
    if (!facing) return std::nullopt;
    if (*facing <= 0) return true;
  }
  return false;
}

}  // namespace batchccd::exact

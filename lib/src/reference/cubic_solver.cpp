#include "reference/cubic_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "reference/scaled_query.hpp"

namespace batchccd::reference {
namespace {

using Cubic = std::array<double, 4>;  // a0 + a1 t + a2 t^2 + a3 t^3

double evaluate(const Cubic& a, double t) { return ((a[3] * t + a[2]) * t + a[1]) * t + a[0]; }

Cubic monomial_coefficients(const std::array<Vec3, 3>& at0, const std::array<Vec3, 3>& velocity) {
  const Vec3 &a = at0[0], &b = at0[1], &c = at0[2];
  const Vec3 &va = velocity[0], &vb = velocity[1], &vc = velocity[2];
  return {a.cross(b).dot(c),
          a.cross(b).dot(vc) + a.cross(vb).dot(c) + va.cross(b).dot(c),
          a.cross(vb).dot(vc) + va.cross(b).dot(vc) + va.cross(vb).dot(c),
          va.cross(vb).dot(vc)};
}

// Real roots of q2 t^2 + q1 t + q0 inside (0, 1), the stable way.
int interior_quadratic_roots(double q2, double q1, double q0, double (&roots)[2]) {
  int count = 0;
  auto keep = [&](double t) {
    if (t > 0 && t < 1) roots[count++] = t;
  };
  if (q2 == 0) {
    if (q1 != 0) keep(-q0 / q1);
  } else {
    const double discriminant = q1 * q1 - 4 * q2 * q0;
    if (discriminant >= 0) {
      const double q = -0.5 * (q1 + std::copysign(std::sqrt(discriminant), q1));
      if (q != 0) keep(q0 / q);
      keep(q / q2);
    }
  }
  if (count == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  return count;
}

// Roots in [0, 1] in increasing order (at most 3).
int roots_in_unit_interval(const Cubic& a, double (&roots)[4]) {
  double critical[2];
  const int critical_count = interior_quadratic_roots(3 * a[3], 2 * a[2], a[1], critical);
  double ends[4] = {0};
  int end_count = 1;
  for (int i = 0; i < critical_count; ++i) ends[end_count++] = critical[i];
  ends[end_count++] = 1;

  int count = 0;
  for (int piece = 0; piece + 1 < end_count; ++piece) {
    double low = ends[piece], high = ends[piece + 1];
    double f_low = evaluate(a, low);
    const double f_high = evaluate(a, high);
    if (f_low == 0) {
      if (count == 0 || roots[count - 1] != low) roots[count++] = low;
      continue;
    }
    if (f_high == 0 && piece + 2 == end_count) {
      roots[count++] = high;
      continue;
    }
    if ((f_low < 0) == (f_high < 0)) continue;
    for (int iteration = 0; iteration < 60 && high - low > 0x1p-52; ++iteration) {
      const double middle = 0.5 * (low + high);
      const double f_middle = evaluate(a, middle);
      if ((f_middle < 0) == (f_low < 0)) {
        low = middle;
        f_low = f_middle;
      } else {
        high = middle;
      }
    }
    roots[count++] = low;
  }
  return count;
}

bool vertex_inside_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a);
  if (normal.squaredNorm() == 0) return false;
  return (b - p).cross(c - p).dot(normal) >= 0 && (c - p).cross(a - p).dot(normal) >= 0 &&
         (a - p).cross(b - p).dot(normal) >= 0;
}

bool segments_cross(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const Vec3 da = a1 - a0, db = b1 - b0, r = a0 - b0;
  const double aa = da.dot(da), ab = da.dot(db), bb = db.dot(db);
  const double ar = da.dot(r), br = db.dot(r);
  const double denominator = aa * bb - ab * ab;
  if (denominator == 0) return false;
  const double s = (ab * br - bb * ar) / denominator;
  const double t = (aa * br - ab * ar) / denominator;
  return s >= 0 && s <= 1 && t >= 0 && t <= 1;
}

}  // namespace

QueryResult solve_cubic(Kind kind, const Query& query) {
  std::array<Vec3, 4> start, end;  // x1..x4 at t0 and t1
  for (int k = 1; k <= 4; ++k) {
    start[k - 1] = query.points[point_index(kind, k)];
    end[k - 1] = query.points[point_index(kind, k) + 4];
  }
  std::array<Vec3, 3> relative, velocity;
  for (int i = 0; i < 3; ++i) {
    relative[i] = start[i + 1] - start[0];
    velocity[i] = (end[i + 1] - end[0]) - relative[i];
  }
  const Cubic a = monomial_coefficients(relative, velocity);

  double roots[4];
  int count = 0;
  if (a[0] == 0 && a[1] == 0 && a[2] == 0 && a[3] == 0) {
    roots[count++] = 0;  // coplanar motion: test the ends, as the textbook does
    roots[count++] = 1;
  } else {
    count = roots_in_unit_interval(a, roots);
  }
  for (int r = 0; r < count; ++r) {
    const double t = roots[r];
    std::array<Vec3, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = (1 - t) * start[k] + t * end[k];
    const bool contact = kind == Kind::vertex_face ? vertex_inside_triangle(x[3], x[0], x[1], x[2])
                                                   : segments_cross(x[0], x[1], x[2], x[3]);
    if (contact) return {true, t, Status::ok};
  }
  return {};
}

}  // namespace batchccd::reference

#pragma once

// The point arguments of the per-query calls (ccd.hpp, ipc.hpp): any Eigen
// vector of doubles (Vector3d, a Map, Ref, block, VectorXd, an expression;
// for ccd.hpp also a braced list {x, y, z}), its length checked before it
// is read. A length fixed at compile time that
// does not fit does not compile (the concepts below constrain the calls, so
// the refusal is also visible to std::is_invocable and requires-expressions);
// a length known only at run time is checked then (query_from_points).
#include <array>
#include <concepts>
#include <cstddef>
#include <initializer_list>
#include <span>

#include <Eigen/Core>

#include "batchccd/query.hpp"

namespace batchccd {
namespace detail {

// An Eigen vector of doubles: a Matrix, Map, Ref, block or expression.
template <class T>
concept DoubleVector = std::derived_from<T, Eigen::MatrixBase<T>> && std::same_as<typename T::Scalar, double> &&
                       bool(T::IsVectorAtCompileTime);

// A point written as a braced list of three numbers, {x, y, z}: the default
// of a point parameter of ccd.hpp's calls, which a braced list cannot
// deduce. Two numbers do not convert (Vec3 would take {1, 2} as sizes and
// leave its coordinates unset), nor do four.
struct BracedPoint {
  BracedPoint(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}  // NOLINT(google-explicit-constructor)
  static constexpr int SizeAtCompileTime = 3;
  double x, y, z;
};

// A point argument: an Eigen vector of doubles, or a braced list of three.
template <class T>
concept PointType = DoubleVector<T> || std::same_as<T, BracedPoint>;

// Lengths fixed at compile time lie in [shortest, 3] and agree; a length
// known only at run time (Eigen::Dynamic) is checked then.
constexpr bool fixed_lengths_fit(int shortest, std::initializer_list<int> lengths) {
  int fixed = Eigen::Dynamic;
  for (const int length : lengths) {
    if (length == Eigen::Dynamic) continue;
    if (length < shortest || length > 3 || (fixed != Eigen::Dynamic && length != fixed)) return false;
    fixed = length;
  }
  return true;
}

}  // namespace detail

// The points of a point-edge or point-point call: all 2D or all 3D.
template <class... Points>
concept PlanarOrSpatialPoints =
    (detail::PointType<Points> && ...) && detail::fixed_lengths_fit(2, {int(Points::SizeAtCompileTime)...});

// The points of a vertex-face (point-triangle) or edge-edge call: 3D.
template <class... Points>
concept SpatialPoints =
    (detail::PointType<Points> && ...) && detail::fixed_lengths_fit(3, {int(Points::SizeAtCompileTime)...});

namespace detail {

// One point argument: its name for messages, its length, and its
// coordinates in 3D (z = 0 for a 2D point). A vector of another length is
// not read; query_from_points refuses it.
struct PointArgument {
  const char* name;
  Eigen::Index length;
  Vec3 point;
};

template <class P>
PointArgument read_point(const char* name, const Eigen::MatrixBase<P>& point) {
  PointArgument argument{name, point.size(), Vec3::Zero()};
  if (argument.length == 2 || argument.length == 3) argument.point.head(argument.length) = point;
  return argument;
}

inline PointArgument read_point(const char* name, const BracedPoint& point) {
  return {name, 3, Vec3(point.x, point.y, point.z)};
}

// Every point of a call read under its name, in the order given (a braced
// list's elements are evaluated in order).
template <class... Points>
std::array<PointArgument, sizeof...(Points)> read_points(const std::array<const char*, sizeof...(Points)>& names,
                                                         const Points&... points) {
  std::size_t i = 0;
  return {read_point(names[i++], points)...};
}

// The query of `kind` whose points are `points`: the t0 points, then the t1
// points, in make_query's order. Every point has length 3, or, for
// vertex_edge and vertex_vertex, all have length 2 (the plane z = 0);
// otherwise throws std::invalid_argument "<call>: <name> must be of length
// ..., got <length>" naming the first argument that does not fit.
Query query_from_points(const char* call, Kind kind, std::span<const PointArgument> points);

}  // namespace detail
}  // namespace batchccd

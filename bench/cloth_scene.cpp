// The cloth scene: a procedural drape, fold and twist of a square sheet
// (see scenes.hpp). Every vertex follows a closed-form path, so any frame
// can be made directly at any resolution.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "scenes.hpp"

namespace batchccd::scenes {
namespace {

constexpr double kFoldLine = 0.45;       // u of the fold; the flap is u > kFoldLine
constexpr double kBendRadius = 0.05;     // radius of the crease
constexpr double kFoldOvershoot = 0.35;  // radians past flat-on-top: the flap dives into the layer below
constexpr double kTwist = 0.5;           // radians the flap's tip turns about the flap's centre line
constexpr double kSag = 0.15;            // drop of the sheet's sides over the ridge
constexpr double kRipple = 0.01;         // amplitude of a travelling ripple

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

// Position of the sheet point (u, v) in [0, 1]^2 at animation time in [0, 1].
Eigen::Vector3d cloth_point(double u, double v, double time) {
  const double progress = smoothstep(time);
  const double fold_angle = (std::numbers::pi + kFoldOvershoot) * progress;
  const double s = u - kFoldLine;  // arc length past the fold line

  // The centre line (v = 1/2) bent in the xz plane: flat, a circular crease,
  // then the straight flap at fold_angle; `normal` is the sheet's normal there.
  Eigen::Vector3d centre(u, 0.5, 0.0), normal(0.0, 0.0, 1.0);
  double twist = 0;
  if (s > 0) {
    const double crease_length = kBendRadius * fold_angle;
    const double angle = s <= crease_length ? s / kBendRadius : fold_angle;
    const double straight = std::max(0.0, s - crease_length);
    centre = {kFoldLine + kBendRadius * std::sin(angle) + straight * std::cos(angle), 0.5,
              kBendRadius * (1 - std::cos(angle)) + straight * std::sin(angle)};
    normal = {-std::sin(angle), 0.0, std::cos(angle)};
    twist = kTwist * progress * smoothstep(s / (1 - kFoldLine));
  }
  Eigen::Vector3d point =
      centre + (v - 0.5) * (std::cos(twist) * Eigen::Vector3d::UnitY() + std::sin(twist) * normal);

  // Drape: a function of (x, y) only, so the layers of the fold keep their
  // spacing; it keeps the whole sheet moving (no static, exactly flat part).
  const double x = point.x(), y = point.y();
  point.z() -= kSag * progress * 4 * (y - 0.5) * (y - 0.5);
  point.z() += kRipple * std::sin(2 * std::numbers::pi * (1.5 * x + 0.5 * y - 2 * time));
  return point;
}

Eigen::MatrixXd sheet_positions(int resolution, double time) {
  Eigen::MatrixXd positions(resolution * resolution, 3);
  const double step = 1.0 / (resolution - 1);
  for (int j = 0; j < resolution; ++j)
    for (int i = 0; i < resolution; ++i)
      positions.row(j * resolution + i) = cloth_point(i * step, j * step, time).transpose();
  return positions;
}

// Two triangles a grid cell, the diagonal alternating like a checkerboard
// so the sheet has no preferred direction.
Eigen::MatrixXi sheet_faces(int resolution) {
  const int cells = resolution - 1;
  Eigen::MatrixXi faces(2 * cells * cells, 3);
  int f = 0;
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int a = j * resolution + i, b = a + 1, c = a + resolution, d = c + 1;
      if ((i + j) % 2 == 0) {
        faces.row(f++) << a, b, d;
        faces.row(f++) << a, d, c;
      } else {
        faces.row(f++) << a, b, c;
        faces.row(f++) << b, d, c;
      }
    }
  }
  return faces;
}

}  // namespace

MovingMesh cloth_scene(const ClothOptions& options) {
  if (options.resolution < 2 || options.frames < 1 || options.frame < 0 ||
      options.frame >= options.frames)
    throw std::invalid_argument("cloth scene: need resolution >= 2 and 0 <= frame < frames");
  const double frames = options.frames;
  MovingMesh mesh;
  mesh.name = "cloth-n" + std::to_string(options.resolution) + "-f" + std::to_string(options.frame) +
              "of" + std::to_string(options.frames);
  mesh.positions_t0 = sheet_positions(options.resolution, options.frame / frames);
  mesh.positions_t1 = sheet_positions(options.resolution, (options.frame + 1) / frames);
  mesh.faces = sheet_faces(options.resolution);
  return mesh;
}

}  // namespace batchccd::scenes

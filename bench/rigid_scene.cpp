// The fast rigid-body scene (see scenes.hpp): thin boxes meshed as closed
// surface grids, each placed by one rigid pose at t0 and another at t1.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "scenes.hpp"

namespace batchccd::scenes {
namespace {

constexpr double kThickness = 0.02;
constexpr double kQuarterTurn = std::numbers::pi / 2;

struct Pose {
  Eigen::Vector3d centre;
  Eigen::Matrix3d rotation;
};

struct Body {
  Eigen::Vector3d size;   // extents along the body's own axes
  Eigen::Vector3i cells;  // grid cells along them
  Pose start, end;        // at t0 and t1
};

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// A closed box surface: a grid on each of its six sides, sharing the
// vertices along the box's edges. Vertices in the body's own frame.
struct BoxSurface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
};

BoxSurface box_surface(const Eigen::Vector3d& size, const Eigen::Vector3i& cells) {
  BoxSurface surface;
  const int nx = cells.x() + 1, ny = cells.y() + 1, nz = cells.z() + 1;
  std::vector<int> id(static_cast<std::size_t>(nx) * ny * nz, -1);
  auto lattice = [&](int i, int j, int k) -> int& {
    return id[(static_cast<std::size_t>(k) * ny + j) * nx + i];
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i != 0 && i != nx - 1 && j != 0 && j != ny - 1 && k != 0 && k != nz - 1) continue;
        lattice(i, j, k) = static_cast<int>(surface.vertices.size());
        const Eigen::Vector3d fraction(double(i) / cells.x(), double(j) / cells.y(), double(k) / cells.z());
        surface.vertices.push_back(size.cwiseProduct(fraction - Eigen::Vector3d::Constant(0.5)));
      }
  // Side `axis` at its low or high end; (b, c) follow axis cyclically, so
  // counter-clockwise in (b, c) faces outward on the high side.
  for (int axis = 0; axis < 3; ++axis) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    for (const bool high : {false, true}) {
      for (int q = 0; q < cells[c]; ++q)
        for (int p = 0; p < cells[b]; ++p) {
          auto corner = [&](int dp, int dq) {
            Eigen::Vector3i index;
            index[axis] = high ? cells[axis] : 0;
            index[b] = p + dp;
            index[c] = q + dq;
            return lattice(index.x(), index.y(), index.z());
          };
          const int v00 = corner(0, 0), v10 = corner(1, 0), v11 = corner(1, 1), v01 = corner(0, 1);
          if (high) {
            surface.faces.emplace_back(v00, v10, v11);
            surface.faces.emplace_back(v00, v11, v01);
          } else {
            surface.faces.emplace_back(v00, v11, v10);
            surface.faces.emplace_back(v00, v01, v11);
          }
        }
    }
  }
  return surface;
}

// A smooth bend in the body's own frame, not separable in x and y, so no
// three grid vertices stay collinear and no four coplanar.
Eigen::Vector3d warped(const Eigen::Vector3d& p, double warp) {
  return p + warp * Eigen::Vector3d(0.0, 0.5 * std::sin(3.7 * p.x() + 1.3),
                                    std::sin(2.9 * p.x() + 0.4) * std::cos(2.3 * p.y() + 0.9));
}

Eigen::Vector3i grid_cells(const Eigen::Vector3d& size, int resolution) {
  Eigen::Vector3i cells;
  for (int axis = 0; axis < 3; ++axis)
    cells[axis] = std::max(1, static_cast<int>(std::lround(size[axis] * resolution)));
  return cells;
}

std::vector<Body> layout(int resolution) {
  const Eigen::Vector3d plate(1.0, 0.6, kThickness), rod(1.0, kThickness, kThickness);
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                        z = Eigen::Vector3d::UnitZ();
  std::vector<Body> bodies;
  auto add = [&](const Eigen::Vector3d& size, const Pose& start, const Pose& end) {
    bodies.push_back({size, grid_cells(size, resolution), start, end});
  };
  // The target: a horizontal plate that barely moves.
  add(plate, {Eigen::Vector3d(0, 0, 0), rotation(0.0, z)},
      {Eigen::Vector3d(0.02, 0, -0.01), rotation(0.05, x)});
  // Four spinning rods that drop through it, 50 thicknesses in one step.
  for (int k = 0; k < 4; ++k) {
    const double sx = (k % 2) ? 0.2 : -0.2, sy = (k / 2) ? 0.12 : -0.12;
    const Eigen::Matrix3d heading = rotation(0.4 * k + 0.3, z) * rotation(0.15, y);
    add(rod, {Eigen::Vector3d(sx, sy, 0.5), heading},
        {Eigen::Vector3d(sx + 0.1, sy - 0.05, -0.5), rotation(0.5, z) * heading});
  }
  // A blade standing on its edge (plane xz) that slides through the target
  // and the rods' paths, 130 thicknesses in one step.
  const Eigen::Matrix3d standing = rotation(kQuarterTurn, x);
  add(plate, {Eigen::Vector3d(-1.3, 0.05, 0.0), standing},
      {Eigen::Vector3d(1.3, 0.05, 0.05), rotation(0.3, z) * standing});
  // A plate facing x that sweeps across the target along its normal.
  const Eigen::Matrix3d facing = rotation(kQuarterTurn, y) * rotation(kQuarterTurn, z);
  add(plate, {Eigen::Vector3d(1.0, 0.0, 0.25), facing},
      {Eigen::Vector3d(-1.0, 0.05, 0.2), rotation(-0.25, z) * facing});
  return bodies;
}

}  // namespace

MovingMesh rigid_scene(const RigidOptions& options) {
  if (options.resolution < 1 || !(options.warp >= 0) || !std::isfinite(options.warp))
    throw std::invalid_argument("rigid scene: need resolution >= 1 and a finite warp >= 0");
  std::vector<Body> bodies = layout(options.resolution);
  std::vector<BoxSurface> surfaces;
  Eigen::Index vertex_count = 0, face_count = 0;
  for (const Body& body : bodies) {
    surfaces.push_back(box_surface(body.size, body.cells));
    vertex_count += static_cast<Eigen::Index>(surfaces.back().vertices.size());
    face_count += static_cast<Eigen::Index>(surfaces.back().faces.size());
  }
  MovingMesh mesh;
  mesh.name = "rigid-n" + std::to_string(options.resolution);
  mesh.positions_t0.resize(vertex_count, 3);
  mesh.positions_t1.resize(vertex_count, 3);
  mesh.faces.resize(face_count, 3);
  Eigen::Index v = 0, f = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const int first_vertex = static_cast<int>(v);
    for (const Eigen::Vector3d& local : surfaces[b].vertices) {
      const Eigen::Vector3d shape = warped(local, options.warp);
      mesh.positions_t0.row(v) = (bodies[b].start.rotation * shape + bodies[b].start.centre).transpose();
      mesh.positions_t1.row(v) = (bodies[b].end.rotation * shape + bodies[b].end.centre).transpose();
      ++v;
    }
    for (const Eigen::Vector3i& face : surfaces[b].faces)
      mesh.faces.row(f++) = (face.array() + first_vertex).transpose();
  }
  return mesh;
}

}  // namespace batchccd::scenes

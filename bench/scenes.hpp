#pragma once

#include <string>

#include <Eigen/Core>

#include "batchccd/batch.hpp"

// Built-in benchmark scenes, generated in code: deterministic (no random
// numbers; closed-form motion, so the same numbers on every run), no data
// files needed. Each returns one time step of a moving triangle mesh;
// candidates come from the broad phase (broad_phase.hpp).
namespace batchccd::scenes {

// A triangle mesh over one time step: vertex positions at t0 and t1.
struct MovingMesh {
  std::string name;  // says what it is and its size, e.g. "cloth-n64-f76of100"
  Eigen::MatrixXd positions_t0;  // n x 3
  Eigen::MatrixXd positions_t1;  // n x 3
  Eigen::MatrixXi faces;         // m x 3

  MeshView view() const { return {positions_t0, positions_t1, faces}; }
};

// A unit square sheet that sags over a ridge, ripples, and folds its far
// part over onto the near part while that flap twists, so that the flap's
// corner and then its tip pass through the layer below. The motion is
// procedural (no collision response), cut into `frames` steps; with 100
// steps the first contact falls in step 73 at the resolutions tried (12 to
// 64), and contacts go on to the end as the crossing moves.
struct ClothOptions {
  int resolution = 64;  // vertices per side (>= 2); the candidate count grows about as its square
  int frames = 100;     // steps the whole motion is cut into (>= 1)
  int frame = 76;       // the step returned, 0 <= frame < frames: t0 = frame, t1 = frame + 1
};
MovingMesh cloth_scene(const ClothOptions& options = {});

// Thin rigid bodies (plates 1 x 0.6 x 0.02, rods 1 x 0.02 x 0.02) moving far
// within one step: four spinning rods drop 1 unit (50 thicknesses) through a
// nearly still plate, a blade slides 2.6 units edgewise through it, a second
// plate sweeps 2 units across it along its normal. The moving bodies turn as
// they go; they touch within the step although no two touch at t0 or at t1
// (tunnelling: a check of the end poses alone misses every contact).
struct RigidOptions {
  int resolution = 8;  // grid cells along a body's unit length (>= 1); candidates grow about as its cube
  // Amplitude of a smooth bend of every body, in body lengths. Exactly flat
  // faces moving rigidly keep every in-plane pair coplanar for the whole step
  // (a degenerate cubic, d = 0); real thin parts are never exactly flat.
  double warp = 0.005;
};
MovingMesh rigid_scene(const RigidOptions& options = {});

}  // namespace batchccd::scenes

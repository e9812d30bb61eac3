#pragma once

#include <filesystem>

#include "batchccd/batch.hpp"

namespace batchccd::scenes {

// Writes a scene directory in the format of docs/design.md §9, readable by
// batchccd::read_scene: t0.ply and t1.ply (binary little-endian, x y z as
// doubles, faces as a uchar count and int vertex ids), vf.csv ("vertex,face"
// a line) and ee.csv ("a0,a1,b0,b1" a line). Creates the directory and
// replaces these files; removes vf_truth.txt and ee_truth.txt, which would
// no longer match. Throws std::runtime_error naming the file when one cannot
// be written.
void write_scene_directory(const std::filesystem::path& directory, const MeshView& mesh,
                           const Candidates& candidates);

}  // namespace batchccd::scenes

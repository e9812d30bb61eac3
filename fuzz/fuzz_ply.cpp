// libFuzzer target: the PLY reader (ascii, binary little- and big-endian).
// What it returns is a mesh the engine can take: n x 3 finite positions and
// m x 3 faces whose ids lie in [0, n). Anything else is InputError.

#include <cstddef>
#include <cstdint>

#include "batchccd/io.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using batchccd::fuzz::require;
  try {
    const batchccd::PlyMesh mesh = batchccd::read_ply(batchccd::fuzz::as_input_file(data, size));
    require(mesh.vertices.cols() == 3, "positions have 3 columns");
    require(mesh.faces.cols() == 3, "faces have 3 columns");
    require(mesh.vertices.allFinite(), "positions are finite");
    const Eigen::Index n = mesh.vertices.rows();
    for (Eigen::Index i = 0; i < mesh.faces.size(); ++i)
      require(mesh.faces.data()[i] >= 0 && mesh.faces.data()[i] < n, "face ids lie in [0, n)");
  } catch (const batchccd::InputError&) {
  }
  return 0;
}

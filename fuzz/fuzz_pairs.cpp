// libFuzzer target: the candidate-list readers ("vertex,face" and
// "a0,a1,b0,b1" a line). Every id read is a non-negative int; anything else
// is InputError. Both readers see every input.

#include <cstddef>
#include <cstdint>

#include "batchccd/io.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input_file.hpp"

namespace {

template <class Rows>
void check_ids(const Rows& rows) {
  for (const auto& row : rows)
    for (const int id : row) batchccd::fuzz::require(id >= 0, "ids read are non-negative");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& path = batchccd::fuzz::as_input_file(data, size);
  try {
    check_ids(batchccd::read_vertex_face_pairs(path));
  } catch (const batchccd::InputError&) {
  }
  try {
    check_ids(batchccd::read_edge_edge_pairs(path));
  } catch (const batchccd::InputError&) {
  }
  return 0;
}

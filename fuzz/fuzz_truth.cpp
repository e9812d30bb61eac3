// libFuzzer target: the ground-truth reader (a JSON array of true/false/0/1,
// or one 0/1 a line). Any bytes either parse or throw InputError; any other
// exception escapes and is reported as a crash.

#include <cstddef>
#include <cstdint>

#include "batchccd/io.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    batchccd::read_truth(batchccd::fuzz::as_input_file(data, size));
  } catch (const batchccd::InputError&) {
    // refused clearly
  }
  return 0;
}

#pragma once

// The readers take file paths: each fuzz input is written to one in-memory
// file per process (Linux memfd, rewritten for every input) and read back
// through its /proc/self/fd path. This adds no public API, costs a few
// microseconds, and leaves nothing behind however the process ends
// (libFuzzer leaves with _Exit, past any cleanup). A file on disk would be
// slow too: ext4 flushes a file truncated and rewritten at every close.

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace batchccd::fuzz {

namespace detail {

inline int input_file_descriptor() {
  static const int descriptor = ::memfd_create("batchccd-fuzz-input", 0);
  if (descriptor < 0) std::abort();  // a harness failure, not a finding: stop loudly
  return descriptor;
}

}  // namespace detail

// Writes the fuzz input to the in-memory file and returns its path.
inline const std::filesystem::path& as_input_file(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = "/proc/self/fd/" + std::to_string(detail::input_file_descriptor());
  const int descriptor = detail::input_file_descriptor();
  if (::ftruncate(descriptor, 0) != 0) std::abort();
  std::size_t written = 0;
  while (written < size) {
    const ssize_t count = ::pwrite(descriptor, data + written, size - written, static_cast<off_t>(written));
    if (count <= 0) std::abort();
    written += static_cast<std::size_t>(count);
  }
  return path;
}

}  // namespace batchccd::fuzz

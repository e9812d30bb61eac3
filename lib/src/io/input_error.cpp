#include <utility>

#include "batchccd/io.hpp"

namespace batchccd {

namespace {

std::string located_message(const std::string& file, long line, const std::string& problem) {
  if (line > 0) return file + ":" + std::to_string(line) + ": " + problem;
  return file + ": " + problem;
}

}  // namespace

InputError::InputError(std::string file, long line, const std::string& problem)
    : std::runtime_error(located_message(file, line, problem)), file_(std::move(file)), line_(line) {}

}  // namespace batchccd

#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "run.hpp"

// What the comparison commands (demo, report) run every method on: a list
// of candidates in a fixed order, either raw queries of one kind or a mesh
// with its candidate lists (vertex-face first, then edge-edge, the order of
// mesh_ccd's results), with ground truth when the input has it.
namespace batchccd::bench {

using cli::FoundInput;

struct RawWorkload {
  Kind kind = Kind::vertex_face;
  std::vector<Query> queries;
};

struct MeshWorkload {
  Eigen::MatrixXd positions_t0, positions_t1;
  Eigen::MatrixXi faces;
  Candidates candidates;

  MeshView view() const { return {positions_t0, positions_t1, faces}; }
};

struct Workload {
  std::string name;  // input path, or the built-in scene and frame
  std::variant<RawWorkload, MeshWorkload> source;
  std::optional<std::vector<bool>> truth;  // one per candidate, when known

  std::size_t size() const;
  Kind kind_at(std::size_t i) const;
  Query query_at(std::size_t i) const;  // candidate i as a raw query
  // The engine's own path for the whole list: batch_ccd or mesh_ccd, into a
  // new result or into `out`.
  BatchResult run(const Options& options, const lab::Settings& settings = {}) const;
  void run(const Options& options, BatchResult& out) const;
  void run(const Options& options, const lab::Settings& settings, BatchResult& out) const;
};

// A query file or scene found by find_inputs (run.hpp), read in full; a
// query file whose path names no kind is `fallback_kind`'s. Throws
// InputError (naming file and line) on bad input.
Workload read_workload(const FoundInput& input, const std::optional<Kind>& fallback_kind);

}  // namespace batchccd::bench

#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

namespace batchccd {

struct Counters {
  std::int64_t candidates = 0;  // queries evaluated
  std::int64_t culled = 0;      // removed by the lane filters
  std::int64_t solved = 0;      // sent to the solver (candidates - culled)
  std::int64_t hits = 0;
  std::int64_t undecided = 0;   // solver ran out of iterations: reported as hits
  std::int64_t invalid = 0;     // Status::invalid_input

  Counters& operator+=(const Counters& other);
};

struct BatchResult {
  // One per candidate, in input order (a mesh call: vertex-face candidates
  // first, then edge-edge). Empty when Options::per_candidate_results is false.
  std::vector<QueryResult> results;
  // Earliest TOI over all candidates, +inf when nothing collides.
  double earliest_toi = std::numeric_limits<double>::infinity();
  Counters counters;
};

// The instruction set a batch call with `requested` runs: automatic picks
// the best this processor and build have. Throws std::invalid_argument when
// a forced one is not available.
Isa resolve_isa(Isa requested);

// Raw queries, all of one kind.
BatchResult batch_ccd(Kind kind, std::span<const Query> queries,
                      const Options& options = {});

// Vertex positions at t0 and t1 (n x 3), triangles (m x 3 vertex ids).
struct MeshView {
  const Eigen::MatrixXd& positions_t0;
  const Eigen::MatrixXd& positions_t1;
  const Eigen::MatrixXi& faces;
};

// Broad-phase candidates over a mesh.
struct Candidates {
  std::vector<std::array<int, 2>> vertex_face;  // vertex id, face id
  std::vector<std::array<int, 4>> edge_edge;    // a0, a1, b0, b1 vertex ids
};

// Throws std::invalid_argument naming the first bad item when the matrices
// are not n x 3 / m x 3 of matching sizes or an index is out of range.
BatchResult mesh_ccd(const MeshView& mesh, const Candidates& candidates,
                     const Options& options = {});

}  // namespace batchccd

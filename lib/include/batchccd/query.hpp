#pragma once

#include <array>
#include <limits>

#include <Eigen/Core>

namespace batchccd {

using Vec3 = Eigen::Vector3d;

// The two elementary tests of triangle-mesh CCD (DESIGN.md §1).
enum class Kind { vertex_face, edge_edge };

const char* to_string(Kind kind);

// One elementary query: eight points, in the order of the query files
// (DESIGN.md §5):
//   vertex_face: p_t0, a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1
//   edge_edge:   ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1
// Every vertex moves linearly from its t0 to its t1 position over t in [0, 1].
struct Query {
  std::array<Vec3, 8> points;
};

enum class Status {
  ok,             // evaluated; hit and toi are meaningful
  invalid_input,  // a coordinate is NaN or infinite: not evaluated, hit is true
                  // so that a caller that ignores status never skips a contact
};

struct QueryResult {
  bool hit = false;
  // Time of impact in [0, 1]: never later than the first contact (a lower
  // bound), +inf when there is none or when it was not asked for.
  double toi = std::numeric_limits<double>::infinity();
  Status status = Status::ok;
};

}  // namespace batchccd

#pragma once

#include <limits>

#include "batchccd/query.hpp"

// Outside peers for the report: other libraries' CCD called on batchccd's
// queries, unchanged, so their answers can be set beside batchccd's modes.
namespace batchccd::peers {

// True when this build has FCL (libfcl-dev found at configure time).
bool fcl_available();

// A peer's answer. toi is +inf when there is no hit.
struct PeerResult {
  bool hit = false;
  double toi = std::numeric_limits<double>::infinity();
};

// One query through FCL 0.7's deformable-primitive CCD,
// fcl::detail::Intersect<double>::intersect_VF / intersect_EE, with FCL's
// default interval-Newton root search and nothing added or filtered.
// What FCL promises, so the report can read its answers fairly:
// - toi is FCL's collision_time as given, in [0, 1] on a hit: the middle of a
//   bracket narrower than 1e-7 around a root of the coplanarity cubic, so it
//   may fall slightly after the first contact (not a lower bound).
// - Its tolerances are absolute (1e-7 on the cubic's coefficients, 1e-5 in the
//   inside-triangle test), so answers depend on the queries' length scale.
// - A pair coplanar throughout (cubic ~ 0) is reported as no hit.
// Throws std::logic_error when !fcl_available().
PeerResult fcl_ccd(Kind kind, const Query& query);

}  // namespace batchccd::peers

#include "peers/fcl_peer.hpp"

#include <stdexcept>

#ifdef BATCHCCD_HAVE_FCL
#include <fcl/narrowphase/detail/traversal/collision/intersect.h>
#endif

namespace batchccd::peers {

#ifdef BATCHCCD_HAVE_FCL

bool fcl_available() { return true; }

PeerResult fcl_ccd(Kind kind, const Query& query) {
  using Intersect = fcl::detail::Intersect<double>;
  const auto& x = query.points;
  double collision_time = 0;
  // FCL writes the contact point on a hit and never accepts null here.
  fcl::Vector3<double> contact_point;
  // useNewton = true is FCL's default: interval Newton over [0, 1] rather
  // than its closed-form cubic solver.
  constexpr bool kUseNewton = true;
  const bool hit =
      kind == Kind::vertex_face
          // FCL takes the triangle first, then the vertex: a, b, c, p at t0, then at t1.
          ? Intersect::intersect_VF(x[1], x[2], x[3], x[0], x[5], x[6], x[7], x[4],
                                    &collision_time, &contact_point, kUseNewton)
          // Edge (a, b) against edge (c, d): the query's own order.
          : Intersect::intersect_EE(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7],
                                    &collision_time, &contact_point, kUseNewton);
  if (!hit) return {};
  return {true, collision_time};
}

#else

bool fcl_available() { return false; }

PeerResult fcl_ccd(Kind, const Query&) {
  throw std::logic_error("fcl_ccd: this build has no FCL (install libfcl-dev and reconfigure)");
}

#endif

}  // namespace batchccd::peers

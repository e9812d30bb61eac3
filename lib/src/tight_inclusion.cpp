#include "batchccd/tight_inclusion.hpp"

#include <cmath>
#include <limits>

#include "batchccd/ccd.hpp"
#include "fronts.hpp"

namespace batchccd::ticcd {
namespace {

bool ccd(const char* call, Kind kind, const Query& query, double ms, double& toi, double tolerance,
         double t_max, long max_itr, double& output_tolerance) {
  fronts::require(ms >= 0 && std::isfinite(ms), call, "ms", ">= 0 and finite", ms);
  fronts::require(t_max > 0 && t_max <= 1, call, "t_max", "in (0, 1]", t_max);
  fronts::require(tolerance > 0 && std::isfinite(tolerance), call, "tolerance", "positive and finite", tolerance);
  Options options = fronts::conservative_options(query, tolerance, max_itr);
  options.min_distance = ms;
  options.tmax = t_max;
  const QueryResult result = query_ccd(kind, query, options);
  output_tolerance = tolerance;
  toi = result.hit ? result.toi : std::numeric_limits<double>::infinity();
  return result.hit;
}

}  // namespace

bool vertexFaceCCD(const Vector3& vertex_start, const Vector3& face_vertex0_start,
                   const Vector3& face_vertex1_start, const Vector3& face_vertex2_start,
                   const Vector3& vertex_end, const Vector3& face_vertex0_end, const Vector3& face_vertex1_end,
                   const Vector3& face_vertex2_end, const Array3& /*err*/, double ms, double& toi,
                   double tolerance, double t_max, long max_itr, double& output_tolerance) {
  return ccd("batchccd::ticcd::vertexFaceCCD", Kind::vertex_face,
             {{vertex_start, face_vertex0_start, face_vertex1_start, face_vertex2_start, vertex_end,
               face_vertex0_end, face_vertex1_end, face_vertex2_end}},
             ms, toi, tolerance, t_max, max_itr, output_tolerance);
}

bool edgeEdgeCCD(const Vector3& edge0_vertex0_start, const Vector3& edge0_vertex1_start,
                 const Vector3& edge1_vertex0_start, const Vector3& edge1_vertex1_start,
                 const Vector3& edge0_vertex0_end, const Vector3& edge0_vertex1_end,
                 const Vector3& edge1_vertex0_end, const Vector3& edge1_vertex1_end, const Array3& /*err*/,
                 double ms, double& toi, double tolerance, double t_max, long max_itr,
                 double& output_tolerance) {
  return ccd("batchccd::ticcd::edgeEdgeCCD", Kind::edge_edge,
             {{edge0_vertex0_start, edge0_vertex1_start, edge1_vertex0_start, edge1_vertex1_start,
               edge0_vertex0_end, edge0_vertex1_end, edge1_vertex0_end, edge1_vertex1_end}},
             ms, toi, tolerance, t_max, max_itr, output_tolerance);
}

}  // namespace batchccd::ticcd

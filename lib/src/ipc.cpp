#include "batchccd/ipc.hpp"

#include <algorithm>
#include <cmath>

#include "batchccd/ccd.hpp"
#include "fronts.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd::ipc {
namespace {

// ipc-toolkit's constants around Tight Inclusion (ipc/ccd/ccd.cpp).
constexpr double kInitialDistanceToleranceScale = 0.5;
constexpr double kLargestRescalingSeparation = 1e-4;
constexpr double kSmallToi = 1e-6;

bool moves(const Query& query) {
  for (int k = 0; k < 4; ++k)
    if (query.points[k] != query.points[k + 4]) return true;
  return false;
}

bool ccd(const char* call, Kind kind, const Query& query, double& toi, double min_distance, double tmax,
         double tolerance, long max_iterations, double conservative_rescaling) {
  fronts::require(min_distance >= 0 && std::isfinite(min_distance), call, "min_distance", ">= 0 and finite",
                  min_distance);
  fronts::require(tmax >= 0 && tmax <= 1, call, "tmax", "in [0, 1]", tmax);
  fronts::require(tolerance > 0 && std::isfinite(tolerance), call, "tolerance", "positive and finite", tolerance);
  fronts::require(conservative_rescaling > 0 && conservative_rescaling <= 1, call, "conservative_rescaling",
                  "in (0, 1]", conservative_rescaling);
  if (!reference::all_finite(query)) {  // never step into what cannot be checked
    toi = 0;
    return true;
  }
  if (!moves(query)) return false;
  const double distance = std::sqrt(squared_distance(kind, query, 0));
  if (distance <= min_distance) {
    toi = 0;
    return true;
  }
  if (tmax == 0) return false;
  Options options = fronts::conservative_options(
      query, std::min(kInitialDistanceToleranceScale * distance, tolerance), max_iterations);
  options.tmax = tmax;
  options.min_distance =
      std::min((1 - conservative_rescaling) * distance, kLargestRescalingSeparation) + min_distance;
  QueryResult result = query_ccd(kind, query, options);
  if (result.hit && result.toi < kSmallToi) {
    // Too close to step: the separation alone, the step rescaled instead.
    options.min_distance = min_distance;
    result = query_ccd(kind, query, options);
    result.toi *= conservative_rescaling;
  }
  if (result.hit) toi = result.toi;
  return result.hit;
}

}  // namespace

bool point_point_ccd(const Vec3& p0_t0, const Vec3& p1_t0, const Vec3& p0_t1, const Vec3& p1_t1, double& toi,
                     double min_distance, double tmax, double tolerance, long max_iterations,
                     double conservative_rescaling) {
  return ccd("batchccd::ipc::point_point_ccd", Kind::vertex_vertex,
             {{p0_t0, p0_t0, p1_t0, p1_t0, p0_t1, p0_t1, p1_t1, p1_t1}}, toi, min_distance, tmax, tolerance,
             max_iterations, conservative_rescaling);
}

bool point_edge_ccd(const Vec3& p_t0, const Vec3& e0_t0, const Vec3& e1_t0, const Vec3& p_t1, const Vec3& e0_t1,
                    const Vec3& e1_t1, double& toi, double min_distance, double tmax, double tolerance,
                    long max_iterations, double conservative_rescaling) {
  return ccd("batchccd::ipc::point_edge_ccd", Kind::vertex_edge,
             {{p_t0, p_t0, e0_t0, e1_t0, p_t1, p_t1, e0_t1, e1_t1}}, toi, min_distance, tmax, tolerance,
             max_iterations, conservative_rescaling);
}

bool edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0, const Vec3& eb1_t0,
                   const Vec3& ea0_t1, const Vec3& ea1_t1, const Vec3& eb0_t1, const Vec3& eb1_t1, double& toi,
                   double min_distance, double tmax, double tolerance, long max_iterations,
                   double conservative_rescaling) {
  return ccd("batchccd::ipc::edge_edge_ccd", Kind::edge_edge,
             {{ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1}}, toi, min_distance, tmax,
             tolerance, max_iterations, conservative_rescaling);
}

bool point_triangle_ccd(const Vec3& p_t0, const Vec3& t0_t0, const Vec3& t1_t0, const Vec3& t2_t0,
                        const Vec3& p_t1, const Vec3& t0_t1, const Vec3& t1_t1, const Vec3& t2_t1, double& toi,
                        double min_distance, double tmax, double tolerance, long max_iterations,
                        double conservative_rescaling) {
  return ccd("batchccd::ipc::point_triangle_ccd", Kind::vertex_face,
             {{p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1}}, toi, min_distance, tmax, tolerance,
             max_iterations, conservative_rescaling);
}

}  // namespace batchccd::ipc

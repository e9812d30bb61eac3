#include "batchccd/ccd.hpp"
#include "batchccd/lab.hpp"

#include <array>

#include "reference/closest_distance.hpp"
#include "reference/reference.hpp"
#include "reference/scaled_query.hpp"

namespace batchccd {

QueryResult lab::query_ccd(Kind kind, const Query& query, const Options& options, const Settings& settings) {
  validate(options, settings);
  return reference::evaluate_query(reference::evaluated_kind(kind), query, options, settings).result;
}

QueryResult query_ccd(Kind kind, const Query& query, const Options& options) {
  return lab::query_ccd(kind, query, options, {});
}

QueryResult vertex_face_ccd(const Vec3& p_t0, const Vec3& a_t0, const Vec3& b_t0,
                            const Vec3& c_t0, const Vec3& p_t1, const Vec3& a_t1,
                            const Vec3& b_t1, const Vec3& c_t1, const Options& options) {
  return query_ccd(Kind::vertex_face, {{p_t0, a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1}}, options);
}

QueryResult edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0,
                          const Vec3& eb1_t0, const Vec3& ea0_t1, const Vec3& ea1_t1,
                          const Vec3& eb0_t1, const Vec3& eb1_t1, const Options& options) {
  return query_ccd(Kind::edge_edge,
                   {{ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1}}, options);
}

QueryResult vertex_edge_ccd(const Vec3& p_t0, const Vec3& e0_t0, const Vec3& e1_t0,
                            const Vec3& p_t1, const Vec3& e0_t1, const Vec3& e1_t1,
                            const Options& options) {
  return query_ccd(Kind::vertex_edge, {{p_t0, p_t0, e0_t0, e1_t0, p_t1, p_t1, e0_t1, e1_t1}}, options);
}

QueryResult vertex_vertex_ccd(const Vec3& p_t0, const Vec3& q_t0, const Vec3& p_t1,
                              const Vec3& q_t1, const Options& options) {
  return query_ccd(Kind::vertex_vertex, {{p_t0, p_t0, q_t0, q_t0, p_t1, p_t1, q_t1, q_t1}}, options);
}

double squared_distance(Kind kind, const Query& query, double t) {
  std::array<reference::Point<double>, 4> x;
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = (1 - t) * query.points[k] + t * query.points[k + 4];
    x[k] = {p.x(), p.y(), p.z()};
  }
  return reference::squared_distance(kind == Kind::vertex_face, x);
}

}  // namespace batchccd

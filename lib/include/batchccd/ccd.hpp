#pragma once

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

namespace batchccd {

// Vertex p against triangle (a, b, c), all moving linearly over t in [0, 1].
QueryResult vertex_face_ccd(const Vec3& p_t0, const Vec3& a_t0, const Vec3& b_t0,
                            const Vec3& c_t0, const Vec3& p_t1, const Vec3& a_t1,
                            const Vec3& b_t1, const Vec3& c_t1,
                            const Options& options = {});

// Edge (ea0, ea1) against edge (eb0, eb1), all moving linearly over t in [0, 1].
QueryResult edge_edge_ccd(const Vec3& ea0_t0, const Vec3& ea1_t0, const Vec3& eb0_t0,
                          const Vec3& eb1_t0, const Vec3& ea0_t1, const Vec3& ea1_t1,
                          const Vec3& eb0_t1, const Vec3& eb1_t1,
                          const Options& options = {});

// One query of either kind, points in the order of Query.
QueryResult query_ccd(Kind kind, const Query& query, const Options& options = {});

}  // namespace batchccd

// A collision-free step the way an IPC solver (ipc-toolkit's
// compute_collision_free_stepsize) takes one: every candidate pair keeps a
// separation of a fraction of its own initial distance, plus a global
// minimum distance, and the step goes to the earliest time of impact over all
// candidates. Here in one mesh_ccd call; checked against the same queries
// asked one at a time (the same step, bit for bit). Exit status 1 if not.
//
// The scene: a sheet of cloth falling and turning onto a still sheet below,
// with a few particles (vertices of no face) moving between them, every pair
// of primitives a candidate (a broad phase would hand over far fewer).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include <batchccd/batchccd.hpp>

namespace {

constexpr int kSide = 6;                     // vertices along a sheet's side
constexpr double kMinDistance = 1e-3;        // ipc's min_distance
constexpr double kConservativeRescaling = 0.8;

struct Scene {
  Eigen::MatrixXd x0, x1;
  Eigen::MatrixXi faces;
  std::vector<std::array<int, 2>> edges;
  int sheet_vertices = kSide * kSide;
  int particles = 0;
};

// Two kSide x kSide sheets in z = 0 (still) and z = 0.5 (falling 1 and
// turning), and four particles crossing the gap.
Scene make_scene() {
  Scene scene;
  const int n = 2 * scene.sheet_vertices;
  const std::array<std::array<double, 6>, 4> particles = {
      {{0.3, 0.3, 0.2, 0.35, 0.3, 0.9}, {0.7, 0.2, 0.6, 0.6, 0.25, -0.4},
       {0.5, 0.5, 0.25, 0.5, 0.52, 0.25}, {0.1, 0.9, 0.1, 0.9, 0.1, 0.3}}};
  scene.particles = static_cast<int>(particles.size());
  scene.x0.resize(n + scene.particles, 3);
  scene.x1.resize(n + scene.particles, 3);
  for (int sheet = 0; sheet < 2; ++sheet)
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j) {
        const int v = sheet * scene.sheet_vertices + i * kSide + j;
        const double x = static_cast<double>(i) / (kSide - 1), y = static_cast<double>(j) / (kSide - 1);
        scene.x0.row(v) << x, y, sheet * 0.5;
        const double angle = sheet * 0.3;  // the falling sheet turns about its centre
        const double cx = x - 0.5, cy = y - 0.5;
        scene.x1.row(v) << 0.5 + std::cos(angle) * cx - std::sin(angle) * cy,
            0.5 + std::sin(angle) * cx + std::cos(angle) * cy, sheet * (0.5 - 1.0) + 0.1 * x * y;
      }
  for (int p = 0; p < scene.particles; ++p) {
    scene.x0.row(n + p) << particles[p][0], particles[p][1], particles[p][2];
    scene.x1.row(n + p) << particles[p][3], particles[p][4], particles[p][5];
  }
  std::vector<std::array<int, 3>> triangles;
  for (int sheet = 0; sheet < 2; ++sheet)
    for (int i = 0; i + 1 < kSide; ++i)
      for (int j = 0; j + 1 < kSide; ++j) {
        const int v = sheet * scene.sheet_vertices + i * kSide + j;
        triangles.push_back({v, v + kSide, v + kSide + 1});
        triangles.push_back({v, v + kSide + 1, v + 1});
        scene.edges.push_back({v, v + kSide});
        scene.edges.push_back({v, v + 1});
        scene.edges.push_back({v, v + kSide + 1});
      }
  scene.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    scene.faces.row(static_cast<Eigen::Index>(f)) << triangles[f][0], triangles[f][1], triangles[f][2];
  return scene;
}

// Which sheet a vertex is on (2: a particle).
int body(const Scene& scene, int vertex) { return std::min(vertex / scene.sheet_vertices, 2); }

batchccd::Query query_of(const Scene& scene, batchccd::Kind kind, const std::array<int, 4>& ids) {
  batchccd::Query query;
  for (int k = 0; k < 4; ++k) {
    query.points[k] = scene.x0.row(ids[k]);
    query.points[k + 4] = scene.x1.row(ids[k]);
  }
  (void)kind;
  return query;
}

struct Pairs {
  batchccd::Candidates candidates;
  std::vector<batchccd::Kind> kinds;          // per candidate, in mesh_ccd's result order
  std::vector<std::array<int, 4>> vertex_ids;  // per candidate, Query's layout
};

// Every pair of primitives on different bodies.
Pairs all_pairs(const Scene& scene) {
  Pairs pairs;
  const int vertices = static_cast<int>(scene.x0.rows());
  for (int v = 0; v < vertices; ++v)
    for (int f = 0; f < scene.faces.rows(); ++f)
      if (body(scene, v) != body(scene, scene.faces(f, 0))) {
        pairs.candidates.vertex_face.push_back({v, f});
        pairs.vertex_ids.push_back({v, scene.faces(f, 0), scene.faces(f, 1), scene.faces(f, 2)});
        pairs.kinds.push_back(batchccd::Kind::vertex_face);
      }
  for (const auto& a : scene.edges)
    for (const auto& b : scene.edges)
      if (body(scene, a[0]) == 0 && body(scene, b[0]) == 1) {
        pairs.candidates.edge_edge.push_back({a[0], a[1], b[0], b[1]});
        pairs.vertex_ids.push_back({a[0], a[1], b[0], b[1]});
        pairs.kinds.push_back(batchccd::Kind::edge_edge);
      }
  const int first_particle = 2 * scene.sheet_vertices;
  for (int p = first_particle; p < vertices; ++p)
    for (const auto& e : scene.edges) {
      pairs.candidates.vertex_edge.push_back({p, e[0], e[1]});
      pairs.vertex_ids.push_back({p, p, e[0], e[1]});
      pairs.kinds.push_back(batchccd::Kind::vertex_edge);
    }
  for (int p = first_particle; p < vertices; ++p)
    for (int q = p + 1; q < vertices; ++q) {
      pairs.candidates.vertex_vertex.push_back({p, q});
      pairs.vertex_ids.push_back({p, p, q, q});
      pairs.kinds.push_back(batchccd::Kind::vertex_vertex);
    }
  return pairs;
}

}  // namespace

int main() {
  try {
    const Scene scene = make_scene();
    const Pairs pairs = all_pairs(scene);
    // Each pair keeps (1 - rescaling) of its initial distance, plus the global minimum.
    std::vector<double> separations;
    for (std::size_t i = 0; i < pairs.kinds.size(); ++i) {
      const batchccd::Query query = query_of(scene, pairs.kinds[i], pairs.vertex_ids[i]);
      const double initial = std::sqrt(batchccd::squared_distance(pairs.kinds[i], query));
      separations.push_back((1 - kConservativeRescaling) * initial + kMinDistance);
    }
    const std::size_t vf = pairs.candidates.vertex_face.size(), ee = pairs.candidates.edge_edge.size(),
                      ve = pairs.candidates.vertex_edge.size();
    const std::span<const double> all(separations);
    const batchccd::MinDistances per_pair{all.subspan(0, vf), all.subspan(vf, ee), all.subspan(vf + ee, ve),
                                          all.subspan(vf + ee + ve)};

    batchccd::Options options;  // conservative: never a missed contact
    options.per_candidate_results = false;
    batchccd::BatchResult batch;
    batchccd::mesh_ccd({scene.x0, scene.x1, scene.faces}, pairs.candidates, per_pair, options, batch);
    const double step = std::min(1.0, batch.earliest_toi);

    // The same queries one at a time.
    double single_step = 1.0;
    for (std::size_t i = 0; i < pairs.kinds.size(); ++i) {
      batchccd::Options own = options;
      own.min_distance = separations[i];
      const batchccd::QueryResult result =
          batchccd::query_ccd(pairs.kinds[i], query_of(scene, pairs.kinds[i], pairs.vertex_ids[i]), own);
      if (result.hit) single_step = std::min(single_step, result.toi);
    }

    // At the step no pair is closer than the global minimum distance.
    double closest = INFINITY;
    for (std::size_t i = 0; i < pairs.kinds.size(); ++i)
      closest = std::min(closest, batchccd::squared_distance(
                                      pairs.kinds[i], query_of(scene, pairs.kinds[i], pairs.vertex_ids[i]), step));
    const batchccd::Counters& c = batch.counters;
    std::printf("ipc step: %lld candidates (%zu vertex-face, %zu edge-edge, %zu vertex-edge, %zu vertex-vertex), "
                "%lld culled, %lld hits\n",
                static_cast<long long>(c.candidates), vf, ee, ve, pairs.candidates.vertex_vertex.size(),
                static_cast<long long>(c.culled), static_cast<long long>(c.hits));
    std::printf("collision-free step %.9g (one query at a time: %.9g); closest pair there %.6g apart\n", step,
                single_step, std::sqrt(closest));
    if (step != single_step || !(std::sqrt(closest) > kMinDistance)) {
      std::fprintf(stderr, "ipc_step: the batch and the single queries disagree, or the step is not free\n");
      return 1;
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ipc_step: %s\n", error.what());
    return 1;
  }
}

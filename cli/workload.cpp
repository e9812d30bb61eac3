#include "workload.hpp"

#include <array>

#include "batchccd/io.hpp"

namespace batchccd::cli {
namespace {

// Candidate i of a mesh as a raw query, points in the order of Query.
Query mesh_query(const MeshWorkload& mesh, std::size_t i) {
  const std::size_t vertex_face = mesh.candidates.vertex_face.size();
  std::array<int, 4> ids;
  if (i < vertex_face) {
    const auto [vertex, face] = mesh.candidates.vertex_face[i];
    ids = {vertex, mesh.faces(face, 0), mesh.faces(face, 1), mesh.faces(face, 2)};
  } else {
    ids = mesh.candidates.edge_edge[i - vertex_face];
  }
  Query query;
  for (int k = 0; k < 4; ++k) {
    query.points[k] = mesh.positions_t0.row(ids[k]).transpose();
    query.points[k + 4] = mesh.positions_t1.row(ids[k]).transpose();
  }
  return query;
}

}  // namespace

std::size_t Workload::size() const {
  if (const auto* raw = std::get_if<RawWorkload>(&source)) return raw->queries.size();
  const auto& mesh = std::get<MeshWorkload>(source);
  return mesh.candidates.vertex_face.size() + mesh.candidates.edge_edge.size();
}

Kind Workload::kind_at(std::size_t i) const {
  if (const auto* raw = std::get_if<RawWorkload>(&source)) return raw->kind;
  return i < std::get<MeshWorkload>(source).candidates.vertex_face.size() ? Kind::vertex_face
                                                                          : Kind::edge_edge;
}

Query Workload::query_at(std::size_t i) const {
  if (const auto* raw = std::get_if<RawWorkload>(&source)) return raw->queries[i];
  return mesh_query(std::get<MeshWorkload>(source), i);
}

BatchResult Workload::run(const Options& options) const {
  BatchResult result;
  run(options, result);
  return result;
}

void Workload::run(const Options& options, BatchResult& out) const {
  if (const auto* raw = std::get_if<RawWorkload>(&source)) {
    batch_ccd(raw->kind, raw->queries, options, out);
  } else {
    const auto& mesh = std::get<MeshWorkload>(source);
    mesh_ccd(mesh.view(), mesh.candidates, options, out);
  }
}

Workload read_workload(const FoundInput& input, const std::optional<Kind>& fallback_kind) {
  Workload workload;
  workload.name = input.path.string();
  if (!input.is_scene) {
    const std::optional<Kind> kind = kind_from_path(input.path) ? kind_from_path(input.path) : fallback_kind;
    if (!kind)
      throw InputError(input.path.string(), 0,
                       "the path names no kind (vertex-face/vf or edge-edge/ee): use --kind");
    QueryFile file = read_query_csv(input.path, *kind);
    workload.source = RawWorkload{*kind, std::move(file.queries)};
    workload.truth = std::move(file.truth);
    return workload;
  }
  Scene scene = read_scene(input.path);
  // Truth for the whole list only when each kind has it (or no candidates).
  const bool vertex_face_known = scene.vertex_face_truth || scene.candidates.vertex_face.empty();
  const bool edge_edge_known = scene.edge_edge_truth || scene.candidates.edge_edge.empty();
  if (vertex_face_known && edge_edge_known) {
    std::vector<bool> truth = scene.vertex_face_truth.value_or(std::vector<bool>{});
    const std::vector<bool> edge_edge = scene.edge_edge_truth.value_or(std::vector<bool>{});
    truth.insert(truth.end(), edge_edge.begin(), edge_edge.end());
    workload.truth = std::move(truth);
  }
  workload.source = MeshWorkload{std::move(scene.positions_t0), std::move(scene.positions_t1),
                                 std::move(scene.faces), std::move(scene.candidates)};
  return workload;
}

}  // namespace batchccd::cli

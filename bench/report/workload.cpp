#include "workload.hpp"

#include "batchccd/io.hpp"

namespace batchccd::bench {

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
  const auto& mesh = std::get<MeshWorkload>(source);
  const std::size_t vertex_face = mesh.candidates.vertex_face.size();
  return i < vertex_face ? vertex_face_query(mesh.view(), mesh.candidates.vertex_face[i])
                         : edge_edge_query(mesh.view(), mesh.candidates.edge_edge[i - vertex_face]);
}

BatchResult Workload::run(const Options& options, const lab::Settings& settings) const {
  BatchResult result;
  run(options, settings, result);
  return result;
}

void Workload::run(const Options& options, BatchResult& out) const { run(options, {}, out); }

void Workload::run(const Options& options, const lab::Settings& settings, BatchResult& out) const {
  if (const auto* raw = std::get_if<RawWorkload>(&source)) {
    lab::batch_ccd(raw->kind, raw->queries, {}, options, settings, out);
  } else {
    const auto& mesh = std::get<MeshWorkload>(source);
    lab::mesh_ccd(mesh.view(), mesh.candidates, {}, options, settings, out);
  }
}

Workload read_workload(const FoundInput& input, const std::optional<Kind>& fallback_kind) {
  Workload workload;
  workload.name = input.path.string();
  if (!input.is_scene) {
    const Kind kind = cli::kind_of_query_file(input.path, fallback_kind);
    QueryFile file = read_query_csv(input.path, kind);
    workload.source = RawWorkload{kind, std::move(file.queries)};
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

}  // namespace batchccd::bench

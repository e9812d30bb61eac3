// libFuzzer target: the query kernels on arbitrary bit patterns
// (kernel_input.hpp says how bytes become queries). Every invariant below
// that breaks aborts with its name, and libFuzzer keeps the input:
//
// - well formed, every mode and baseline (lab.hpp): a non-finite coordinate gives invalid_input with
//   hit = true and toi = 0; otherwise status ok, a hit's toi in [0, 1], a
//   miss's toi = +inf, never NaN;
// - the modes (conservative, exact) find every forced contact within the
//   time window, at a toi no later than it;
// - exact says yes => conservative says yes (a conservative "no" there is a
//   false negative), and the conservative toi is no later than the exact one;
// - at a separation or a time window tmax < 1, finite queries: the checks of
//   pair_search_check.hpp (both certified modes against each other and
//   against exact truth: the exact stage at d = 0, tests/exact_distance.hpp's
//   rational labels at d > 0), in place of the line above;
// - power-of-two scaling (when exact) changes nothing: decision and toi bit
//   for bit in the scaled frame (conservative, the fast baseline), the
//   decision in exact mode; a separation is scaled with the query;
// - batch_ccd and mesh_ccd, in every instruction set this machine runs,
//   give each query the decision query_ccd (the scalar reference) gives it
//   alone, with consistent counters (with one separation per candidate);
// - mesh_ccd asked for the earliest TOI only, its window narrowed by a
//   first batch of contacts just above the records' earliest, gives the
//   minimum of its per-candidate results (check_earliest_in_window).
// Scaling, the batch entry points, the separation and the time window come
// in one configuration per input, picked by its setup byte (kernel_input.hpp).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "fuzz_check.hpp"
#include "kernel_input.hpp"
#include "pair_search_check.hpp"

namespace {

using batchccd::BatchResult;
using batchccd::Isa;
using batchccd::Kind;
using batchccd::Options;
using batchccd::Query;
using batchccd::QueryResult;
using batchccd::Status;
using batchccd::fuzz::ForcedContact;
using batchccd::fuzz::KernelRecord;
using batchccd::fuzz::require;

namespace lab = batchccd::lab;

// In the setup byte's order (kernel_input.hpp): conservative first, exact last.
constexpr lab::Method kMethods[] = {lab::kConservative, lab::kFast, lab::kCubic, lab::kExact};

bool is_certified(const lab::Method& method) { return method.baseline == lab::Baseline::none; }

QueryResult run(Kind kind, const Query& query, const lab::Method& method, const Options& options) {
  return lab::query_ccd(kind, query, method.applied_to(options), method.settings());
}


// What one call asks besides its queries.
struct Window {
  bool need_toi = true;
  double tmax = 1;
};

// A fuzz input must not take seconds: a smaller search budget keeps the
// runs fast, and an exhausted budget is still answered soundly (the fast
// baseline: a hit; the modes: the exact stage, or at a separation an
// undecided hit).
Options options_for(const Window& window, double separation) {
  Options options;
  options.need_toi = window.need_toi;
  options.tmax = window.tmax;
  options.min_distance = separation;
  options.max_iterations = 1 << 8;
  options.threads = 1;
  return options;
}

// The setup's separation for one query: a fraction of its size (its largest
// coordinate difference, rounded down to a power of two; 1 where that is 0
// or not finite), so that it matters at every scale; never 0 but at index 0.
constexpr double kSeparationFractions[] = {0, 0x1p-20, 0x1p-6, 0x1p-1};
double separation_for(const Query& query, unsigned index) {
  if (index == 0) return 0;
  double size = 0;
  for (const batchccd::Vec3& point : query.points)
    size = std::max(size, (point - query.points[0]).cwiseAbs().maxCoeff());
  const int exponent = std::isfinite(size) && size > 0 ? std::ilogb(size) : 0;
  return std::max(std::ldexp(kSeparationFractions[index % std::size(kSeparationFractions)], exponent),
                  std::numeric_limits<double>::denorm_min());
}

bool all_finite(const Query& query) {
  for (const batchccd::Vec3& point : query.points)
    if (!point.allFinite()) return false;
  return true;
}

void check_well_formed(const QueryResult& r, bool finite) {
  if (!finite) {
    require(r.status == Status::invalid_input, "non-finite input gives invalid_input");
    require(r.hit && r.toi == 0.0, "invalid_input reads as a contact at t = 0");
    return;
  }
  require(r.status == Status::ok, "finite input is evaluated");
  require(!std::isnan(r.toi), "toi is never NaN");
  if (r.hit) {
    require(r.toi >= 0.0 && r.toi <= 1.0, "a hit's toi lies in [0, 1]");
  } else {
    require(r.toi == std::numeric_limits<double>::infinity(), "a miss's toi is +inf");
  }
}

void check_forced_contact(const KernelRecord& record, const Window& window, const QueryResult& r) {
  if (record.contact == ForcedContact::none || r.status != Status::ok) return;
  const double time = record.contact == ForcedContact::at_t1 ? 1.0 : 0.0;
  if (time > window.tmax) return;
  require(r.hit, "a mode finds a forced contact", batchccd::to_string(record.kind));
  if (record.need_toi) require(r.toi <= time, "toi no later than a forced contact");
}

// Conservative and fast work in a frame scaled by powers of two: the same
// decision and toi bit for bit. Exact arithmetic: the same decision.
void check_scaling(const KernelRecord& record, const Window& window, double separation, const lab::Method& method,
                   const QueryResult& original) {
  const std::optional<Query> scaled = batchccd::fuzz::exactly_scaled(record.query, record.scale_exponent);
  const double scaled_separation = std::ldexp(separation, record.scale_exponent);
  if (!scaled || !std::isfinite(scaled_separation) ||
      std::ldexp(scaled_separation, -record.scale_exponent) != separation)
    return;
  const QueryResult r = run(record.kind, *scaled, method, options_for(window, scaled_separation));
  require(r.status == original.status && r.hit == original.hit, "scaling by 2^k keeps the decision",
          lab::to_string(method));
  if (method != lab::kExact)
    require(r.toi == original.toi, "scaling by 2^k keeps the toi bit for bit", lab::to_string(method));
}

// Every method on one query alone (the cubic baseline only without a
// separation), scaled by the setup's method; returns the setup's answer.
QueryResult check_alone(const KernelRecord& record, const Window& window, double separation,
                        const lab::Method& setup_method) {
  const bool finite = all_finite(record.query);
  std::vector<QueryResult> answers;
  QueryResult setup_answer;
  for (const lab::Method& method : kMethods) {
    if (method == lab::kCubic && separation > 0) continue;
    const QueryResult r = run(record.kind, record.query, method, options_for(window, separation));
    check_well_formed(r, finite);
    if (is_certified(method)) check_forced_contact(record, window, r);
    if (method == setup_method && method != lab::kCubic) check_scaling(record, window, separation, method, r);
    if (method == setup_method) setup_answer = r;
    answers.push_back(r);
  }
  if (finite && (separation > 0 || window.tmax < 1)) {
    // A decision counted undecided (exact mode at a separation) may stand
    // against a conservative miss: compared as pair_search_check.hpp does.
    const double windows[] = {window.tmax};
    batchccd::fuzz::check_at_separation(record.kind, record.query, separation, windows);
    return setup_answer;
  }
  const QueryResult& conservative = answers.front();
  const QueryResult& exact = answers.back();
  if (exact.hit && exact.status == Status::ok) {
    require(conservative.hit, "conservative says no where exact says yes (a false negative)");
    if (record.need_toi) require(conservative.toi <= exact.toi + 0x1p-40, "conservative toi no later than exact");
  }
  return setup_answer;
}

void check_counters(const BatchResult& batch, const std::vector<QueryResult>& alone) {
  std::int64_t hits = 0, invalid = 0;
  for (const QueryResult& r : alone) {
    hits += r.hit ? 1 : 0;
    invalid += r.status == Status::invalid_input ? 1 : 0;
  }
  require(batch.counters.candidates == static_cast<std::int64_t>(alone.size()), "counters: candidates");
  require(batch.counters.hits == hits, "counters: hits");
  require(batch.counters.invalid == invalid, "counters: invalid");
}

void check_same_decisions(const BatchResult& batch, const std::vector<QueryResult>& alone, const char* path) {
  require(batch.results.size() == alone.size(), "one result per candidate", path);
  for (std::size_t i = 0; i < alone.size(); ++i) {
    require(batch.results[i].status == alone[i].status, "batch status equals the query alone", path);
    require(batch.results[i].hit == alone[i].hit, "batch decision equals the query alone", path);
  }
  check_counters(batch, alone);
}

// The records of one kind as a mesh: query i owns vertices 4i .. 4i + 3
// (vertex-face: vertex 4i against face i = (4i + 1, 4i + 2, 4i + 3)).
struct RecordMesh {
  Eigen::MatrixXd t0, t1;
  Eigen::MatrixXi faces;
  batchccd::Candidates candidates;
};

RecordMesh as_mesh(Kind kind, std::span<const Query> queries) {
  RecordMesh mesh;
  const auto n = static_cast<Eigen::Index>(queries.size());
  mesh.t0.resize(4 * n, 3);
  mesh.t1.resize(4 * n, 3);
  mesh.faces.resize(kind == Kind::vertex_face ? n : 0, 3);
  for (Eigen::Index q = 0; q < n; ++q) {
    for (Eigen::Index k = 0; k < 4; ++k) {
      mesh.t0.row(4 * q + k) = queries[static_cast<std::size_t>(q)].points[static_cast<std::size_t>(k)];
      mesh.t1.row(4 * q + k) = queries[static_cast<std::size_t>(q)].points[static_cast<std::size_t>(k + 4)];
    }
    const int first = static_cast<int>(4 * q);
    if (kind == Kind::vertex_face) {
      mesh.faces.row(q) << first + 1, first + 2, first + 3;
      mesh.candidates.vertex_face.push_back({first, static_cast<int>(q)});
    } else {
      mesh.candidates.edge_edge.push_back({first, first + 1, first + 2, first + 3});
    }
  }
  return mesh;
}

// The earliest-TOI-only mesh call (certified modes) filters each batch over
// the part of the step the batches before it left open (scheduler/horizons.hpp).
// Here a first batch (one contact at t_w, a power of two at most 1/32 above
// the records' earliest contact, then static pairs far apart, which the
// lanes cull at once) narrows the window before the records' batch: the call's earliest TOI must still be the minimum of the
// same call's per-candidate results. Skipped where a search ran out of its
// budget (an undecided hit's TOI may depend on tmax).
void check_earliest_in_window(Kind kind, const RecordMesh& mesh, std::span<const double> separations,
                              const BatchResult& per_candidate, Options options, const lab::Method& method) {
  if (!options.need_toi || per_candidate.counters.undecided > 0) return;
  double t_w = 0x1p-5;
  while (t_w / 2 > per_candidate.earliest_toi && t_w > 0x1p-40) t_w /= 2;
  constexpr int kBatch = 2048;  // simd::kFilterBatch
  const auto n = static_cast<int>(mesh.t0.rows());
  Eigen::MatrixXd t0(n + 6, 3), t1(n + 6, 3);
  t0.topRows(n) = mesh.t0;
  t1.topRows(n) = mesh.t1;
  // Vertex-face: vertex n + 3 falls onto face (n, n + 1, n + 2) at t_w;
  // vertex n + 4 stays 10 above it. Edge-edge: edge (n + 2, n + 3) falls
  // onto edge (n, n + 1) at t_w; edge (n + 4, n + 5) stays 10 above it.
  const bool faces = kind == Kind::vertex_face;
  t0.bottomRows(6) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, 1, 0.25, 0.25, 10, 0, 1, 10;
  if (!faces) t0.bottomRows(6) << -1, 0, 0, 1, 0, 0, 0, -1, 1, 0, 1, 1, 0, -1, 10, 0, 1, 10;
  t1.bottomRows(6) = t0.bottomRows(6);
  for (int k = faces ? 3 : 2; k < 4; ++k) t1(n + k, 2) = 1 - 1 / t_w;
  Eigen::MatrixXi face_rows(mesh.faces.rows() + (faces ? 1 : 0), 3);
  face_rows.topRows(mesh.faces.rows()) = mesh.faces;
  batchccd::Candidates candidates;
  if (faces) {
    const int face = static_cast<int>(mesh.faces.rows());
    face_rows.bottomRows(1) << n, n + 1, n + 2;
    candidates.vertex_face.assign(kBatch, {n + 4, face});
    candidates.vertex_face.front() = {n + 3, face};
    candidates.vertex_face.insert(candidates.vertex_face.end(), mesh.candidates.vertex_face.begin(),
                                  mesh.candidates.vertex_face.end());
  } else {
    candidates.edge_edge.assign(kBatch, {n, n + 1, n + 4, n + 5});
    candidates.edge_edge.front() = {n, n + 1, n + 2, n + 3};
    candidates.edge_edge.insert(candidates.edge_edge.end(), mesh.candidates.edge_edge.begin(),
                                mesh.candidates.edge_edge.end());
  }
  std::vector<double> each;
  batchccd::MinDistances per_list;
  if (!separations.empty() && separations.front() > 0) {
    each.assign(kBatch, 0.0);
    each.insert(each.end(), separations.begin(), separations.end());
    (faces ? per_list.vertex_face : per_list.edge_edge) = each;
  }
  const batchccd::MeshView view{t0, t1, face_rows};
  BatchResult all, earliest;
  lab::mesh_ccd(view, candidates, per_list, options, method.settings(), all);
  if (all.counters.undecided > 0) return;
  double minimum = std::numeric_limits<double>::infinity();
  for (const QueryResult& r : all.results)
    if (r.hit) minimum = std::min(minimum, r.toi);
  options.per_candidate_results = false;
  options.hit_list = false;
  lab::mesh_ccd(view, candidates, per_list, options, method.settings(), earliest);
  require(std::memcmp(&earliest.earliest_toi, &minimum, sizeof(double)) == 0,
          "an earliest-TOI-only mesh call's TOI is the minimum of its per-candidate results");
  require(earliest.counters.candidates == all.counters.candidates, "earliest-TOI-only: candidates");
}

// All queries of one kind (and need_toi) in one call of the setup's entry
// point, method and instruction set, each at its separation, against their
// answers alone. Without a separation no list of them is passed: a list of
// zeros turns on the lane filters' forms for a separation, and the fast
// baseline (uncertified) may then answer a query otherwise than with
// Options::min_distance = 0 (a fuzz input did: a miss alone, a hit at 0 in
// the batch, in every instruction set).
void check_batch(Kind kind, std::span<const Query> queries, std::span<const double> separations,
                 const std::vector<QueryResult>& alone, const Window& window, const lab::Method& method, Isa isa,
                 bool through_mesh) {
  if (queries.empty()) return;
  Options options = method.applied_to(options_for(window, 0));
  options.isa = isa;
  BatchResult batch;
  if (through_mesh) {
    const RecordMesh mesh = as_mesh(kind, queries);
    batchccd::MinDistances per_candidate;
    if (separations.front() > 0)
      (kind == Kind::vertex_face ? per_candidate.vertex_face : per_candidate.edge_edge) = separations;
    lab::mesh_ccd({mesh.t0, mesh.t1, mesh.faces}, mesh.candidates, per_candidate, options, method.settings(), batch);
    if (is_certified(method)) check_earliest_in_window(kind, mesh, separations, batch, options, method);
  } else {
    lab::batch_ccd(kind, queries, separations.front() > 0 ? separations : std::span<const double>(), options,
                   method.settings(), batch);
  }
  check_same_decisions(batch, alone, batchccd::to_string(isa));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const batchccd::fuzz::KernelInput input = batchccd::fuzz::decode_input(std::span(data, size));
  static const std::vector<Isa> isas = batchccd::available_isas();
  const lab::Method& method = kMethods[input.setup.mode_index % std::size(kMethods)];
  const Isa isa = isas[input.setup.isa_index % isas.size()];
  const unsigned separation_index = method == lab::kCubic ? 0 : input.setup.separation_index;
  // A batch call shares one need_toi: group by kind and need_toi.
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const bool need_toi : {true, false}) {
      const Window window{need_toi, input.setup.tmax};
      std::vector<Query> queries;
      std::vector<double> separations;
      std::vector<QueryResult> alone;  // by the setup's method
      for (const KernelRecord& record : input.records) {
        if (record.kind != kind || record.need_toi != need_toi) continue;
        queries.push_back(record.query);
        separations.push_back(separation_for(record.query, separation_index));
        alone.push_back(check_alone(record, window, separations.back(), method));
      }
      check_batch(kind, queries, separations, alone, window, method, isa, input.setup.mesh);
    }
  return 0;
}

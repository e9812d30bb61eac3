// libFuzzer target: the query kernels on arbitrary bit patterns
// (kernel_input.hpp says how bytes become queries). Every invariant below
// that breaks aborts with its name, and libFuzzer keeps the input:
//
// - well formed, every mode and baseline (lab.hpp): a non-finite coordinate gives invalid_input with
//   hit = true and toi = 0; otherwise status ok, a hit's toi in [0, 1], a
//   miss's toi = +inf, never NaN;
// - the modes (conservative, exact) find every forced contact, at a toi no
//   later than it;
// - exact says yes => conservative says yes (a conservative "no" there is a
//   false negative), and the conservative toi is no later than the exact one;
// - power-of-two scaling (when exact) changes nothing: decision and toi bit
//   for bit in the scaled frame (conservative, the fast baseline), the
//   decision in exact mode;
// - batch_ccd and mesh_ccd, in every instruction set this machine runs,
//   give each query the decision query_ccd (the scalar reference) gives it
//   alone, with consistent counters.
// Scaling and the batch entry points run in one configuration per input,
// picked by its setup byte (kernel_input.hpp).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "batchccd/lab.hpp"
#include "fuzz_check.hpp"
#include "kernel_input.hpp"

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


// A fuzz input must not take seconds: a smaller search budget keeps the
// runs fast, and an exhausted budget is still answered soundly (the fast
// baseline: a hit; the modes: the exact stage).
Options options_for(bool need_toi) {
  Options options;
  options.need_toi = need_toi;
  options.max_iterations = 1 << 8;
  options.threads = 1;
  return options;
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

double forced_contact_time(ForcedContact contact) { return contact == ForcedContact::at_t1 ? 1.0 : 0.0; }

void check_forced_contact(const KernelRecord& record, const QueryResult& r) {
  if (record.contact == ForcedContact::none || r.status != Status::ok) return;
  require(r.hit, "a mode finds a forced contact", batchccd::to_string(record.kind));
  if (record.need_toi) require(r.toi <= forced_contact_time(record.contact), "toi no later than a forced contact");
}

// Conservative and fast work in a frame scaled by powers of two: the same
// decision and toi bit for bit. Exact arithmetic: the same decision.
void check_scaling(const KernelRecord& record, const lab::Method& method, const QueryResult& original) {
  const std::optional<Query> scaled = batchccd::fuzz::exactly_scaled(record.query, record.scale_exponent);
  if (!scaled) return;
  const QueryResult r = run(record.kind, *scaled, method, options_for(record.need_toi));
  require(r.status == original.status && r.hit == original.hit, "scaling by 2^k keeps the decision",
          lab::to_string(method));
  if (method != lab::kExact)
    require(r.toi == original.toi, "scaling by 2^k keeps the toi bit for bit", lab::to_string(method));
}

// Every method on one query alone, scaled by the setup's method; returns
// the answers in kMethods order.
std::vector<QueryResult> check_alone(const KernelRecord& record, const lab::Method& setup_method) {
  const bool finite = all_finite(record.query);
  std::vector<QueryResult> answers;
  for (const lab::Method& method : kMethods) {
    const QueryResult r = run(record.kind, record.query, method, options_for(record.need_toi));
    check_well_formed(r, finite);
    if (is_certified(method)) check_forced_contact(record, r);
    if (method == setup_method && method != lab::kCubic) check_scaling(record, method, r);
    answers.push_back(r);
  }
  const QueryResult& conservative = answers.front();
  const QueryResult& exact = answers.back();
  if (exact.hit && exact.status == Status::ok) {
    require(conservative.hit, "conservative says no where exact says yes (a false negative)");
    if (record.need_toi) require(conservative.toi <= exact.toi + 0x1p-40, "conservative toi no later than exact");
  }
  return answers;
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

RecordMesh as_mesh(Kind kind, const std::vector<Query>& queries) {
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

// All queries of one kind (and need_toi) in one call of the setup's entry
// point, method and instruction set, against their answers alone.
void check_batch(Kind kind, const std::vector<const KernelRecord*>& records, const std::vector<QueryResult>& alone,
                 bool need_toi, const lab::Method& method, Isa isa, bool through_mesh) {
  if (records.empty()) return;
  std::vector<Query> queries;
  for (const KernelRecord* record : records) queries.push_back(record->query);
  Options options = method.applied_to(options_for(need_toi));
  options.isa = isa;
  if (through_mesh) {
    const RecordMesh mesh = as_mesh(kind, queries);
    check_same_decisions(
        lab::mesh_ccd({mesh.t0, mesh.t1, mesh.faces}, mesh.candidates, options, method.settings()), alone,
        batchccd::to_string(isa));
  } else {
    check_same_decisions(lab::batch_ccd(kind, queries, options, method.settings()), alone,
                         batchccd::to_string(isa));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const batchccd::fuzz::KernelInput input = batchccd::fuzz::decode_input(std::span(data, size));
  static const std::vector<Isa> isas = batchccd::available_isas();
  const std::size_t method_index = input.setup.mode_index % std::size(kMethods);
  const Isa isa = isas[input.setup.isa_index % isas.size()];
  // A batch call shares one need_toi: group by kind and need_toi.
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const bool need_toi : {true, false}) {
      std::vector<const KernelRecord*> group;
      std::vector<QueryResult> alone;  // by the setup's method
      for (const KernelRecord& record : input.records) {
        if (record.kind != kind || record.need_toi != need_toi) continue;
        group.push_back(&record);
        alone.push_back(check_alone(record, kMethods[method_index])[method_index]);
      }
      check_batch(kind, group, alone, need_toi, kMethods[method_index], isa, input.setup.mesh);
    }
  return 0;
}

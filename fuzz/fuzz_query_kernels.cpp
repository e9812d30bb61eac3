// libFuzzer target: the query kernels on arbitrary bit patterns
// (kernel_input.hpp says how bytes become queries). Every invariant below
// that breaks aborts with its name, and libFuzzer keeps the input:
//
// - well formed, every mode: a non-finite coordinate gives invalid_input with
//   hit = true and toi = 0; otherwise status ok, a hit's toi in [0, 1], a
//   miss's toi = +inf, never NaN;
// - certified modes (conservative, and exact where the build has it) find
//   every forced contact, at a toi no later than it;
// - exact says yes => conservative says yes (a conservative "no" there is a
//   false negative), and the conservative toi is no later than the exact one;
// - power-of-two scaling (when exact) changes nothing: decision and toi bit
//   for bit in the scaled-frame modes (conservative, fast), the decision in
//   exact mode;
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
#include "fuzz_check.hpp"
#include "kernel_input.hpp"

namespace {

using batchccd::BatchResult;
using batchccd::Isa;
using batchccd::Kind;
using batchccd::Mode;
using batchccd::Options;
using batchccd::Query;
using batchccd::QueryResult;
using batchccd::Status;
using batchccd::fuzz::ForcedContact;
using batchccd::fuzz::KernelRecord;
using batchccd::fuzz::require;

// Mode::exact joins every check below as soon as options.hpp has it.
template <class M = Mode>
std::optional<M> exact_mode() {
  if constexpr (requires { M::exact; }) {
    return M::exact;
  } else {
    return std::nullopt;
  }
}

std::vector<Mode> modes_to_check() {
  std::vector<Mode> modes{Mode::conservative, Mode::fast, Mode::cubic};
  if (exact_mode()) modes.push_back(*exact_mode());
  return modes;
}

bool is_certified(Mode mode) { return mode == Mode::conservative || mode == exact_mode(); }


// A fuzz input must not take seconds: a smaller search budget keeps the
// runs fast, and an exhausted budget is still answered soundly (fast mode:
// a hit; the certified modes: the exact stage).
Options options_for(Mode mode, bool need_toi) {
  Options options;
  options.mode = mode;
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
  require(r.hit, "a certified mode finds a forced contact", batchccd::to_string(record.kind));
  if (record.need_toi) require(r.toi <= forced_contact_time(record.contact), "toi no later than a forced contact");
}

// Conservative and fast work in a frame scaled by powers of two: the same
// decision and toi bit for bit. Exact arithmetic: the same decision.
void check_scaling(const KernelRecord& record, Mode mode, const QueryResult& original) {
  const std::optional<Query> scaled = batchccd::fuzz::exactly_scaled(record.query, record.scale_exponent);
  if (!scaled) return;
  const QueryResult r = batchccd::query_ccd(record.kind, *scaled, options_for(mode, record.need_toi));
  require(r.status == original.status && r.hit == original.hit, "scaling by 2^k keeps the decision",
          batchccd::to_string(mode));
  if (mode != exact_mode()) require(r.toi == original.toi, "scaling by 2^k keeps the toi bit for bit",
                                    batchccd::to_string(mode));
}

// Every mode on one query alone, scaled in the setup's mode; returns the
// answers in modes_to_check order.
std::vector<QueryResult> check_alone(const KernelRecord& record, Mode setup_mode) {
  const bool finite = all_finite(record.query);
  std::vector<QueryResult> answers;
  for (const Mode mode : modes_to_check()) {
    const QueryResult r = batchccd::query_ccd(record.kind, record.query, options_for(mode, record.need_toi));
    check_well_formed(r, finite);
    if (is_certified(mode)) check_forced_contact(record, r);
    if (mode == setup_mode && mode != Mode::cubic) check_scaling(record, mode, r);
    answers.push_back(r);
  }
  if (exact_mode()) {
    const QueryResult& conservative = answers.front();
    const QueryResult& exact = answers.back();
    if (exact.hit && exact.status == Status::ok) {
      require(conservative.hit, "conservative says no where exact says yes (a false negative)");
      if (record.need_toi) require(conservative.toi <= exact.toi + 0x1p-40, "conservative toi no later than exact");
    }
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
// point, mode and instruction set, against their answers alone.
void check_batch(Kind kind, const std::vector<const KernelRecord*>& records, const std::vector<QueryResult>& alone,
                 bool need_toi, Mode mode, Isa isa, bool through_mesh) {
  if (records.empty()) return;
  std::vector<Query> queries;
  for (const KernelRecord* record : records) queries.push_back(record->query);
  Options options = options_for(mode, need_toi);
  options.isa = isa;
  if (through_mesh) {
    const RecordMesh mesh = as_mesh(kind, queries);
    check_same_decisions(batchccd::mesh_ccd({mesh.t0, mesh.t1, mesh.faces}, mesh.candidates, options), alone,
                         batchccd::to_string(isa));
  } else {
    check_same_decisions(batchccd::batch_ccd(kind, queries, options), alone, batchccd::to_string(isa));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const batchccd::fuzz::KernelInput input = batchccd::fuzz::decode_input(std::span(data, size));
  static const std::vector<Mode> modes = modes_to_check();
  static const std::vector<Isa> isas = batchccd::available_isas();
  const std::size_t mode_index = input.setup.mode_index % modes.size();
  const Isa isa = isas[input.setup.isa_index % isas.size()];
  // A batch call shares one need_toi: group by kind and need_toi.
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge})
    for (const bool need_toi : {true, false}) {
      std::vector<const KernelRecord*> group;
      std::vector<QueryResult> alone;  // in the setup's mode
      for (const KernelRecord& record : input.records) {
        if (record.kind != kind || record.need_toi != need_toi) continue;
        group.push_back(&record);
        alone.push_back(check_alone(record, modes[mode_index])[mode_index]);
      }
      check_batch(kind, group, alone, need_toi, modes[mode_index], isa, input.setup.mesh);
    }
  return 0;
}

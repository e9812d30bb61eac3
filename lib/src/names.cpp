#include <algorithm>

#include "batchccd/batch.hpp"
#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

namespace batchccd {

const char* to_string(Kind kind) {
  switch (kind) {
    case Kind::vertex_face: return "vf";
    case Kind::edge_edge: return "ee";
    case Kind::vertex_edge: return "ve";
    case Kind::vertex_vertex: return "vv";
  }
  return "?";
}

const char* to_string(Mode mode) {
  switch (mode) {
    case Mode::conservative: return "conservative";
    case Mode::fast: return "fast";
    case Mode::cubic: return "cubic";
    case Mode::exact: return "exact";
  }
  return "?";
}

const char* to_string(Isa isa) {
  switch (isa) {
    case Isa::automatic: return "auto";
    case Isa::scalar: return "scalar";
    case Isa::sse4: return "sse4";
    case Isa::avx2: return "avx2";
    case Isa::avx512: return "avx512";
  }
  return "?";
}

Counters& Counters::operator+=(const Counters& other) {
  candidates += other.candidates;
  culled += other.culled;
  culled_by_sign += other.culled_by_sign;
  culled_by_separation += other.culled_by_separation;
  solved += other.solved;
  hits += other.hits;
  undecided += other.undecided;
  invalid += other.invalid;
  exact_escalations += other.exact_escalations;
  max_query_seconds = std::max(max_query_seconds, other.max_query_seconds);
  return *this;
}

}  // namespace batchccd

#include "batchccd/batch.hpp"
#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

namespace batchccd {

const char* to_string(Kind kind) { return kind == Kind::vertex_face ? "vf" : "ee"; }

const char* to_string(Mode mode) {
  switch (mode) {
    case Mode::conservative: return "conservative";
    case Mode::fast: return "fast";
    case Mode::cubic: return "cubic";
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
  solved += other.solved;
  hits += other.hits;
  undecided += other.undecided;
  invalid += other.invalid;
  return *this;
}

}  // namespace batchccd

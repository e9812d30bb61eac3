#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <stdexcept>
#include <string>

#include <xsimd/xsimd.hpp>

#include "reference/filter.hpp"
#include "reference/scaled_query.hpp"
#include "simd/filter.hpp"

namespace batchccd::simd {
namespace {

// The scalar reference filter behind the same interface: Isa::scalar.
template <class Source>
std::size_t filter_range_scalar(const Source& source, std::size_t begin, std::size_t end,
                                const reference::FilterSettings& settings, std::uint32_t* survivors,
                                std::uint8_t* free_pieces, FilterCounts& counts) {
  std::size_t kept = 0;
  reference::FilterSettings own = settings;  // a candidate's own separation
  for (std::size_t i = begin; i < end; ++i) {
    own.min_distance = settings.separation_of(i);
    const reference::FilterVerdict verdict = reference::run_filters(source.kind, query_at(source, i), own);
    counts.sign += verdict.sign;
    counts.separation += verdict.separation;
    counts.pieces += verdict.pieces;
    counts.swept_box += verdict.swept_box;
    if (verdict.culled()) continue;
    survivors[kept] = static_cast<std::uint32_t>(i - begin);
    free_pieces[kept++] = verdict.free_pieces;
  }
  return kept;
}

// The kernel tables this build compiled (simd/CMakeLists.txt defines
// BATCHCCD_KERNELS_<set> for each), best first, the scalar path last.
const FilterKernels* const kCompiled[] = {
#ifdef BATCHCCD_KERNELS_AVX512
    &kAvx512Kernels,
#endif
#ifdef BATCHCCD_KERNELS_AVX2
    &kAvx2Kernels,
#endif
#ifdef BATCHCCD_KERNELS_SSE4
    &kSse4Kernels,
#endif
#ifdef BATCHCCD_KERNELS_NEON
    &kNeonKernels,
#endif
    &kScalarKernels,
};

// Whether the processor runs a set this build compiled.
bool processor_has(Isa isa) {
  // BATCHCCD_HIDE_ISA=avx2,avx512 hides sets, so the unavailable path is testable anywhere.
  if (const char* hidden = std::getenv("BATCHCCD_HIDE_ISA"); hidden && isa != Isa::scalar &&
      (std::string(",") + hidden + ",").find(std::string(",") + to_string(isa) + ",") != std::string::npos)
    return false;
  const auto available = xsimd::available_architectures();
  switch (isa) {
    case Isa::scalar: return true;
    case Isa::sse4: return available.sse4_2;
    case Isa::avx2: return available.avx2 && available.fma3_avx2;
    case Isa::avx512:
      return available.avx512f && available.avx512dq && available.avx512bw && available.avx512cd;
    case Isa::neon: return available.neon64;  // every AArch64 processor
    case Isa::automatic: return true;
  }
  return false;
}

}  // namespace

const FilterKernels kScalarKernels = {Isa::scalar, &filter_range_scalar<RawQueries>,
                                      &filter_range_scalar<MeshVertexFace>,
                                      &filter_range_scalar<MeshEdgeEdge>};

const FilterKernels& filter_kernels(Isa isa) {
  for (const FilterKernels* kernels : kCompiled)
    if ((isa == Isa::automatic || kernels->isa == isa) && processor_has(kernels->isa)) return *kernels;
  const bool compiled = std::any_of(std::begin(kCompiled), std::end(kCompiled),
                                    [isa](const FilterKernels* kernels) { return kernels->isa == isa; });
  throw std::invalid_argument(std::string("instruction set ") + to_string(isa) +
                              (compiled ? " is not supported by this processor"
                                        : " is not in this build (another processor family, or "
                                          "BATCHCCD_PORTABLE_ONLY)"));
}

}  // namespace batchccd::simd

#pragma once

#include <cstddef>
#include <cstdint>

#include "batchccd/options.hpp"
#include "reference/filter.hpp"
#include "simd/sources.hpp"

// The lane filters over a range of candidates, one implementation per
// instruction set behind one table (docs/design.md §8: portable front,
// per-instruction-set kernels, runtime dispatch).
namespace batchccd::simd {

// Candidates each filter culled (each cull counted once, by the first stage
// that makes it: reference::FilterVerdict).
struct FilterCounts {
  std::size_t sign = 0;
  std::size_t separation = 0;
  std::size_t pieces = 0;
  std::size_t swept_box = 0;
};

// Candidates a worker filters at once (the scheduler's batches): the second
// filter revisits the first one's survivors while they are still in cache,
// the survivor list stays small, and there are enough pieces to balance two
// or more threads.
inline constexpr std::size_t kFilterBatch = 2048;

// Writes, in increasing order, the indices i - begin of the candidates in
// [begin, end) that the filters cannot cull, and beside each in
// `free_pieces` the pieces of its step they proved free of contact
// (reference::FilterVerdict::free_pieces); returns how many, and adds each
// filter's culls to `counts`.
template <class Source>
using FilterFunction = std::size_t (*)(const Source& source, std::size_t begin, std::size_t end,
                                       const reference::FilterSettings& settings, std::uint32_t* survivors,
                                       std::uint8_t* free_pieces, FilterCounts& counts);

struct FilterKernels {
  Isa isa;
  FilterFunction<RawQueries> raw;
  FilterFunction<MeshVertexFace> vertex_face;
  FilterFunction<MeshEdgeEdge> edge_edge;
};

// The kernels for `isa` (automatic: the best this processor runs). Throws
// std::invalid_argument when the processor or the build lacks it.
const FilterKernels& filter_kernels(Isa isa);

// Per instruction set, defined in kernel_*.cpp and dispatch.cpp; a build
// defines only those of its processor family (simd/CMakeLists.txt).
extern const FilterKernels kScalarKernels;
extern const FilterKernels kSse4Kernels;
extern const FilterKernels kAvx2Kernels;
extern const FilterKernels kAvx512Kernels;
extern const FilterKernels kNeonKernels;

}  // namespace batchccd::simd

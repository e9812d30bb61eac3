#pragma once

#include <cstddef>
#include <cstdint>

#include "batchccd/options.hpp"
#include "simd/sources.hpp"

// The sign filter over a range of candidates, one implementation per
// instruction set behind one table (DESIGN.md §4: portable front,
// per-instruction-set kernels, runtime dispatch).
namespace batchccd::simd {

// Writes, in increasing order, the indices i - begin of the candidates in
// [begin, end) that the sign filter cannot cull; returns how many.
// certified: cull only on certified signs (conservative); else plain signs.
template <class Source>
using FilterFunction = std::size_t (*)(const Source& source, std::size_t begin, std::size_t end,
                                       bool certified, std::uint32_t* survivors);

struct FilterKernels {
  Isa isa;
  FilterFunction<RawQueries> raw;
  FilterFunction<MeshVertexFace> vertex_face;
  FilterFunction<MeshEdgeEdge> edge_edge;
};

// The kernels for `isa` (automatic: the best this processor runs). Throws
// std::invalid_argument when the processor or the build lacks it.
const FilterKernels& filter_kernels(Isa isa);

// Per instruction set, defined in kernel_*.cpp and dispatch.cpp.
extern const FilterKernels kScalarKernels;
extern const FilterKernels kSse4Kernels;
extern const FilterKernels kAvx2Kernels;
extern const FilterKernels kAvx512Kernels;

}  // namespace batchccd::simd

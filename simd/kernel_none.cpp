// BATCHCCD_PORTABLE_ONLY: the vector kernels' tables without kernels. The
// dispatcher never picks them (processor_has is false for every vector set),
// so the library links and runs the scalar path on any target.
#include "simd/filter.hpp"

namespace batchccd::simd {
const FilterKernels kSse4Kernels = {Isa::sse4, nullptr, nullptr, nullptr};
const FilterKernels kAvx2Kernels = {Isa::avx2, nullptr, nullptr, nullptr};
const FilterKernels kAvx512Kernels = {Isa::avx512, nullptr, nullptr, nullptr};
}  // namespace batchccd::simd

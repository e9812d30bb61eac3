// SSE4.2 kernels: this file alone is compiled with -msse4.2.
#include "simd/lane_kernels.hpp"

namespace batchccd::simd {
const FilterKernels kSse4Kernels = make_kernels<xsimd::sse4_2>(Isa::sse4);
}

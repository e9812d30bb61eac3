// AVX2 kernels: this file alone is compiled with -mavx2 -mfma.
#include "simd/lane_kernels.hpp"

namespace batchccd::simd {
const FilterKernels kAvx2Kernels = make_kernels<xsimd::avx2>(Isa::avx2);
}

// AVX-512 kernels: this file alone is compiled with -mavx512f -mavx512dq -mavx512vl -mavx512bw.
#include "simd/lane_kernels.hpp"

namespace batchccd::simd {
const FilterKernels kAvx512Kernels = make_kernels<xsimd::avx512bw>(Isa::avx512);
}

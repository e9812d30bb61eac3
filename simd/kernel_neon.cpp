// NEON kernels (64-bit ARM, two doubles a lane group): every AArch64
// processor has them, so this file needs no flag of its own.
#include "simd/lane_kernels.hpp"

namespace batchccd::simd {
const FilterKernels kNeonKernels = make_kernels<xsimd::neon64>(Isa::neon);
}

// The NEON lanes' max and min against the scalar reference's, lane by lane,
// where NEON's own instructions (fmax, fmin) decide otherwise: zeros of
// either sign and NaN operands. Only an AArch64 build has NEON lanes; `./dev
// arm64` runs this test under qemu-user, and it skips anywhere else.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#ifdef __aarch64__
#include "simd/lane_kernels.hpp"  // the overloads the kernels use, NEON needing no flag
#endif
#include "reference/bernstein.hpp"

namespace batchccd {
namespace {

#ifdef __aarch64__
std::string bits(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%a (0x%016llx)", x,
                static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(x)));
  return text;
}
#endif

// Both operand orders, each in either lane: every pair of these values, a
// NaN with its sign bit set and one with a payload among them, whose bits
// the reference passes on unchanged.
TEST(NeonLanes, MaxAndMinDecideAsTheReferenceOnSignedZerosAndNaNs) {
#ifndef __aarch64__
  GTEST_SKIP() << "NEON lanes exist in AArch64 builds alone (./dev arm64 runs this test under qemu-user)";
#else
  using Double = simd::Lanes<xsimd::neon64>::Double;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double infinity = std::numeric_limits<double>::infinity();
  const double values[] = {0.0, -0.0, nan, -nan, std::bit_cast<double>(0x7ff8000000000123ull),
                           1.0, -1.0, infinity, -infinity, 0x1p-1074};
  int differs_from_fmax = 0;  // pairs where NEON's own instructions would fail this test
  for (const double a : values)
    for (const double b : values) {
      const double first[2] = {a, b}, second[2] = {b, a};
      const Double x = Double::load_unaligned(first), y = Double::load_unaligned(second);
      // As the filters call them: reference::max_of (xsimd's max by
      // argument-dependent lookup) and xsimd::max named directly.
      const Double results[4] = {reference::max_of(x, y), xsimd::max(x, y), reference::min_of(x, y),
                                 xsimd::min(x, y)};
      const char* names[4] = {"max_of", "xsimd::max", "min_of", "xsimd::min"};
      for (int r = 0; r < 4; ++r) {
        double lanes[2];
        results[r].store_unaligned(lanes);
        for (int j = 0; j < 2; ++j) {
          const double expected = r < 2 ? reference::max_of(first[j], second[j])
                                        : reference::min_of(first[j], second[j]);
          EXPECT_EQ(std::bit_cast<std::uint64_t>(lanes[j]), std::bit_cast<std::uint64_t>(expected))
              << names[r] << " lane " << j << " of " << bits(first[j]) << " and " << bits(second[j]);
        }
      }
      const double fmax = vgetq_lane_f64(vmaxq_f64(x, y), 0);
      differs_from_fmax += std::bit_cast<std::uint64_t>(fmax) !=
                           std::bit_cast<std::uint64_t>(reference::max_of(a, b));
    }
  // The values reach what sets NEON's instructions apart: (+0, -0) and
  // every pair with a NaN.
  EXPECT_GT(differs_from_fmax, 0);
#endif
}

}  // namespace
}  // namespace batchccd

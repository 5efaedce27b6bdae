// Private: the small, branch-free arithmetic of the colony's inner loop — a base-2 logarithm and
// exponential accurate to about 1e-4 relative (enough for roulette weights, which only need to
// rank and proportion candidates) that compile to a few integer and float operations and
// vectorise, so no call into the maths library is made per evaluated candidate.
#pragma once

#include <bit>
#include <cstdint>

/// With GCC on x86-64 Linux, a function marked ANTCD_VECTOR_CLONES is compiled twice, for the
/// baseline (SSE2) and for AVX2, and the loader picks the clone the CPU runs (ifunc). Only for
/// loops the compiler vectorises; -ffp-contract=off keeps both clones' arithmetic identical (no
/// FMA), so results do not depend on the CPU.
/// Not under ThreadSanitizer: the loader runs ifunc resolvers while relocating, before the TSan
/// runtime is initialised, and GCC instruments the generated resolver, so every executable linking
/// the library would crash at startup (seen as a SIGSEGV in elf_machine_lazy_rel).
/// Not with Clang either: Clang 14 rejects the attribute on a member function defined after its
/// declaration ("cannot become a multiversioned function after first usage"); Clang builds get the
/// baseline.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && \
    !defined(ANTCD_NO_CLONES) && !defined(__SANITIZE_THREAD__)
#define ANTCD_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ANTCD_VECTOR_CLONES
#endif

namespace antcd::detail {

/// log2(x) for finite x > 0 (normal floats): exponent from the bits, then a cubic in the mantissa
/// m in [1, 2) fitted to log2(m) (max error about 1.1e-3 absolute in log2, i.e. 0.08 % relative in
/// the value 2^log2). Denormals and zero give about -127 (a tiny weight), never NaN.
inline float fast_log2(float x) {
  const auto bits = std::bit_cast<std::uint32_t>(x);
  const float exponent = static_cast<float>(static_cast<std::int32_t>(bits >> 23) - 127);
  const float m = std::bit_cast<float>((bits & 0x007FFFFFU) | 0x3F800000U);  // [1, 2)
  // Least-squares cubic for log2 on [1, 2), exact at both ends.
  const float p = ((0.15638611f * m - 1.04640899f) * m + 3.04452418f) * m - 2.1545013f;
  return exponent + p;
}

/// 2^x, clamped to [2^-126, 2^126]: integer part into the exponent bits, a cubic for the
/// fraction (max relative error about 1e-4).
inline float fast_exp2(float x) {
  x = x < -126.0f ? -126.0f : (x > 126.0f ? 126.0f : x);
  const std::int32_t whole = static_cast<std::int32_t>(x) - (x < 0 ? 1 : 0);  // floor, or one less
  const float f = x - static_cast<float>(whole);                              // [0, 1]
  const float p = ((0.07912522f * f + 0.22494631f) * f + 0.69592847f) * f + 1.0f;  // 2^f, [1, 2]
  // p's exponent field is 127 (or 128 at f = 1); adding `whole` to it scales by 2^whole.
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(p) +
                              (static_cast<std::uint32_t>(whole) << 23));
}

}  // namespace antcd::detail

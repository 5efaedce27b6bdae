// Private: the 16 lanes of a colony step as two 8-lane GCC / Clang vectors, for the masks and
// reductions of run_colony (aco.cpp) that the compilers do not vectorise from plain loops once
// the 16-iteration loops are unrolled and the lane arrays split into scalars. Elementwise
// operations only (no reassociation of float sums): the values are those of the scalar loops.
// Both compilers lower 256-bit vectors to pairs of 128-bit ones on the SSE2 baseline.
#pragma once

#include <cstdint>
#include <cstring>

#include "util/portable.hpp"

#if !ANTCD_HAVE_VECTOR_EXTENSIONS
#error "src/random/lane_vectors.hpp needs GCC (12+) or Clang vector extensions (util/portable.hpp)"
#endif

// The helpers below and their callers pass 256-bit vectors by value; all of it is inlined into
// run_colony, so GCC's note that such a call's ABI differs with and without AVX concerns no real
// call. Silenced for the file that includes this header (aco.cpp only).
#if defined(__clang__)
#if __has_warning("-Wpsabi")
#pragma clang diagnostic ignored "-Wpsabi"
#endif
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace antcd::detail::lanes {

using F8 = float __attribute__((vector_size(32)));
using U8 = std::uint32_t __attribute__((vector_size(32)));
using I8 = std::int32_t __attribute__((vector_size(32)));
using F4 = float __attribute__((vector_size(16)));
using U4 = std::uint32_t __attribute__((vector_size(16)));
/// Unaligned loads (the idiom of _mm_loadu_ps).
typedef float F4Unaligned __attribute__((vector_size(16), aligned(4), may_alias));
typedef std::uint32_t U4Unaligned __attribute__((vector_size(16), aligned(4), may_alias));

inline F8 load(const float* p) {
  F8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline U8 load(const std::uint32_t* p) {
  U8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, const F8& v) { std::memcpy(p, &v, sizeof v); }
inline void store(std::uint32_t* p, const U8& v) { std::memcpy(p, &v, sizeof v); }

inline U8 splat(std::uint32_t x) { return U8{} + x; }
inline F8 splat(float x) { return F8{} + x; }

/// Lane k of half h (lanes 8h .. 8h + 7) is ~0 when bit 8h + k of `mask` is set, else 0.
inline U8 expand(std::uint32_t mask, std::uint32_t half) {
  const U8 bit = {1, 2, 4, 8, 16, 32, 64, 128};
  return (U8)((splat(mask >> (8 * half)) & bit) != 0);
}
/// The inverse: bit k of the result is set when lane k (of lo, then hi) is not 0.
inline std::uint32_t to_mask(const U8& lo, const U8& hi);

inline std::uint32_t reduce_or(const U8& x) {
  U8 v = x;
  v |= __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  v |= __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5);
  v |= __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6);
  return v[0];
}
inline std::uint32_t reduce_add(const U8& x) {
  U8 v = x;
  v += __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  v += __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5);
  v += __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6);
  return v[0];
}
inline U8 min(const U8& a, const U8& b) { return (a & (U8)(a < b)) | (b & ~(U8)(a < b)); }
inline I8 max(const I8& a, const I8& b) { return (a & (I8)(a > b)) | (b & ~(I8)(a > b)); }
inline std::uint32_t reduce_min(const U8& x) {
  U8 v = x;
  v = min(v, __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3));
  v = min(v, __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5));
  v = min(v, __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6));
  return v[0];
}
inline std::int32_t reduce_max(const I8& x) {
  I8 v = x;
  v = max(v, __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3));
  v = max(v, __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5));
  v = max(v, __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6));
  return v[0];
}

inline std::uint32_t to_mask(const U8& lo, const U8& hi) {
  const U8 bit = {1, 2, 4, 8, 16, 32, 64, 128};
  return reduce_or((lo & bit) | (hi & (bit << 8)));
}

/// The vector types of a lane element type.
template <typename T>
struct Vec;
template <>
struct Vec<float> {
  using V4 = F4;
  using V8 = F8;
  using V4Unaligned = F4Unaligned;
};
template <>
struct Vec<std::uint32_t> {
  using V4 = U4;
  using V8 = U8;
  using V4Unaligned = U4Unaligned;
};

/// Side A's values of the 16 lanes of an interior cell (row c, every lane inside the grid).
/// Lanes 0–7 take rows c - 1, c - 1, c - 1, c, c, c + 1, c + 1, c + 1 (the first offsets of
/// run_colony's kDirections), lanes 8–15 the same with hop: one unaligned load of v[c - 1 ..
/// c + 2] and three scalars, spread by two constant shuffles. Copies only: the values of a gather.
template <typename T>
inline void spread_rows(const T* v, std::uint32_t c, std::uint32_t hop, T* out) {
  using V4 = typename Vec<T>::V4;
  using V8 = typename Vec<T>::V8;
  const V4 near = *reinterpret_cast<const typename Vec<T>::V4Unaligned*>(v + c - 1);
  const V4 far = {v[c - hop], v[c], v[c + hop], v[c]};
  const V8 lo = __builtin_shufflevector(near, near, 0, 0, 0, 1, 1, 2, 2, 2);
  const V8 hi = __builtin_shufflevector(far, far, 0, 0, 0, 1, 1, 2, 2, 2);
  std::memcpy(out, &lo, sizeof lo);
  std::memcpy(out + 8, &hi, sizeof hi);
}
/// Side B's: lanes 0–7 take columns c - 1, c, c + 1, c - 1, c + 1, c - 1, c, c + 1 (the second
/// offsets of kDirections), lanes 8–15 the same with hop.
template <typename T>
inline void spread_columns(const T* v, std::uint32_t c, std::uint32_t hop, T* out) {
  using V4 = typename Vec<T>::V4;
  using V8 = typename Vec<T>::V8;
  const V4 near = *reinterpret_cast<const typename Vec<T>::V4Unaligned*>(v + c - 1);
  const V4 far = {v[c - hop], v[c], v[c + hop], v[c]};
  const V8 lo = __builtin_shufflevector(near, near, 0, 1, 2, 0, 2, 0, 1, 2);
  const V8 hi = __builtin_shufflevector(far, far, 0, 1, 2, 0, 2, 0, 1, 2);
  std::memcpy(out, &lo, sizeof lo);
  std::memcpy(out + 8, &hi, sizeof hi);
}

/// Float bits under a lane mask (0 / ~0): the value where set, `other` elsewhere.
inline F8 select(const U8& m, const F8& v, const F8& other) {
  return (F8)(((U8)v & m) | ((U8)other & ~m));
}

}  // namespace antcd::detail::lanes

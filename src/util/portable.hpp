// Private: compiler extensions behind macros, so that the library builds with GCC, Clang and (the
// core, geometry to world) MSVC. Each macro is a hint or a capability test: none changes a result.
//
//   ANTCD_PREFETCH(p)        hints that *p will be read soon (GCC/Clang __builtin_prefetch;
//                            _mm_prefetch on MSVC for x86; nothing elsewhere).
//   ANTCD_PREFETCH_WRITE(p)  the same for a write.
//   ANTCD_HAVE_VECTOR_EXTENSIONS  1 when GCC/Clang vector types (vector_size,
//                            __builtin_shufflevector) exist, else 0. The random searches' lane code
//                            (src/random/lane_vectors.hpp) needs them.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define ANTCD_PREFETCH(p) __builtin_prefetch(p)
#define ANTCD_PREFETCH_WRITE(p) __builtin_prefetch((p), 1)
#elif defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
#include <xmmintrin.h>
#define ANTCD_PREFETCH(p) _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0)
#define ANTCD_PREFETCH_WRITE(p) _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0)
#else
#define ANTCD_PREFETCH(p) ((void)(p))
#define ANTCD_PREFETCH_WRITE(p) ((void)(p))
#endif

// __builtin_shufflevector: Clang always, GCC from 12.
#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 12)
#define ANTCD_HAVE_VECTOR_EXTENSIONS 1
#else
#define ANTCD_HAVE_VECTOR_EXTENSIONS 0
#endif

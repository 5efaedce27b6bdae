// Whether the test is built with ThreadSanitizer. Debian's libtbb is not instrumented, so TSan
// cannot see how oneTBB hands tasks over between its threads and reports every access of a task
// body, antcd's included, as a race. Tests therefore keep TSan runs off oneTBB's parallel paths;
// those paths are checked by the answers in the ASan and Release builds instead.
#pragma once

namespace antcd::test {

#if defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderTsan = true;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
inline constexpr bool kUnderTsan = true;
#else
inline constexpr bool kUnderTsan = false;
#endif
#else
inline constexpr bool kUnderTsan = false;
#endif

}  // namespace antcd::test

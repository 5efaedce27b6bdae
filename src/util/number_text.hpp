// Private: the text of a double that reads back as exactly the same double, for messages and
// mesh output. std::to_chars (the shortest such text, locale-independent) where the standard
// library has it for floating point (__cpp_lib_to_chars); otherwise "%.17g", which also round-trips
// (libc++ 14, e.g. Emscripten 3.1's, lacks floating-point to_chars; its C locale is fixed).
#pragma once

#include <charconv>
#include <cstdio>
#include <string>
#include <system_error>

namespace antcd::detail {

/// Appends the round-trip text of x to out.
inline void append_double(std::string& out, double x) {
  char buf[32];
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, ec == std::errc{} ? end : buf);
#else
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  out.append(buf, n > 0 && n < static_cast<int>(sizeof buf) ? static_cast<std::size_t>(n) : 0);
#endif
}

}  // namespace antcd::detail

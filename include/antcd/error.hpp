// antcd/error.hpp — what antcd throws.
//
// Every exception antcd throws on bad input is an antcd::Error, whose what() is one line naming the
// input (file, object, function argument) and the problem:
// - MeshError: a mesh could not be loaded or is invalid;
// - SceneError: a scene file is invalid;
// - ArgumentError: a library call got an invalid argument (a negative threshold, a frame out of
//   range, a search request without agents, ...).
// Besides these a library call lets escape only std::bad_alloc (out of memory) and
// std::logic_error, which means an internal invariant failed (a bug in antcd, never bad input:
// e.g. the hierarchy build's node-count check in src/bvh/build.cpp).
#pragma once

#include <antcd/export.hpp>

#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace antcd {

/// Base of every error antcd throws. what() is one line that names the input (file, object,
/// argument) and the problem.
class ANTCD_API Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A mesh could not be loaded or is invalid. what() is "<source>: <problem>".
class ANTCD_API MeshError : public Error {
 public:
  MeshError(std::string source, const std::string& problem)
      : Error(source + ": " + problem), source_(std::move(source)) {}
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  std::string source_;
};

/// A scene file is invalid. what() is "<file>: <object or field>: <problem>".
class ANTCD_API SceneError : public Error {
 public:
  using Error::Error;
};

/// A library call got an invalid argument. what() names the function or the argument and the
/// problem.
class ANTCD_API ArgumentError : public Error {
 public:
  using Error::Error;
};

/// Appends the text of `x` that reads back as exactly the same double ("1.5", "-1", "inf", "nan"),
/// for the numbers messages quote (each front end quotes them the same way): std::to_chars, the
/// shortest such text, where the standard library has it for floating point; otherwise "%.17g",
/// which also round-trips (libc++ 14, e.g. Emscripten 3.1's, lacks floating-point to_chars).
inline void append_number_text(std::string& out, double x) {
  char buf[32];
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, ec == std::errc{} ? end : buf);
#else
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  out.append(buf, n > 0 && n < static_cast<int>(sizeof buf) ? static_cast<std::size_t>(n) : 0);
#endif
}

/// append_number_text into a new string ("?" in the impossible case of no text).
[[nodiscard]] inline std::string number_text(double x) {
  std::string text;
  append_number_text(text, x);
  return text.empty() ? std::string("?") : text;
}

}  // namespace antcd

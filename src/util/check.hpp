// Private: the one argument check of the library. Every rejected number throws ArgumentError
// (error.hpp) with one message format, naming the function and the argument:
//   "<function>: <argument> must be <requirement>, got <value>"
// e.g. "distance: rel_tolerance must be in [0, 1), got 1.5". Values print in the shortest form
// that reads back to the same double. The checks are inline and cheap (a comparison or two); the
// message is built only on failure.
#pragma once

#include <antcd/error.hpp>
#include <antcd/math.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

namespace antcd::detail {

[[noreturn]] inline void argument_error(std::string_view function, std::string_view argument,
                                        std::string_view requirement, std::string_view got) {
  std::string msg(function);
  msg.append(": ").append(argument).append(" must be ").append(requirement);
  msg.append(", got ").append(got);
  throw ArgumentError(msg);
}

/// finite
inline void require_finite(std::string_view function, std::string_view argument, Scalar value) {
  if (!std::isfinite(value)) argument_error(function, argument, "finite", number_text(value));
}

/// finite and >= 0
inline void require_non_negative(std::string_view function, std::string_view argument,
                                 Scalar value) {
  if (!(value >= 0) || !std::isfinite(value)) {
    argument_error(function, argument, "finite and >= 0", number_text(value));
  }
}

/// finite and > 0
inline void require_positive(std::string_view function, std::string_view argument, Scalar value) {
  if (!(value > 0) || !std::isfinite(value)) {
    argument_error(function, argument, "finite and > 0", number_text(value));
  }
}

/// >= 0, +inf allowed (a bound that may be absent)
inline void require_bound(std::string_view function, std::string_view argument, Scalar value) {
  if (!(value >= 0)) argument_error(function, argument, ">= 0 (or +inf)", number_text(value));
}

/// in [lo, hi) (half_open) or [lo, hi]; `range` is how the message writes it, e.g. "[0, pi]"
inline void require_in_range(std::string_view function, std::string_view argument, Scalar value,
                             Scalar lo, Scalar hi, bool half_open, std::string_view range) {
  if (!(value >= lo && (half_open ? value < hi : value <= hi))) {
    argument_error(function, argument, std::string("in ").append(range), number_text(value));
  }
}

/// an integer count >= minimum (any integer types)
template <class Int, class Min>
void require_at_least(std::string_view function, std::string_view argument, Int value,
                      Min minimum) {
  if (std::cmp_less(value, minimum)) {
    argument_error(function, argument, ">= " + std::to_string(minimum), std::to_string(value));
  }
}

}  // namespace antcd::detail
